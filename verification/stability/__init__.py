"""Numerical stability on hard cases (issue 6 item 3): ``python -m verification.stability.run``."""
