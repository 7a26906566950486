"""Start-up (docs/architecture.md, "Start-up"): what a command loads, and that what it skips
changes no number. Times are measured by benchmarks/startup.py, not asserted here."""

import math
import subprocess
import sys
from pathlib import Path

import numpy as np

from cablefem.roots import brentq

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"


def _modules_after(command):
    """The modules a fresh ``cablefem`` process holds after running ``command`` (a list of args)."""
    code = ("import sys; from cablefem.cli import main; status = main(%r); "
            "print(status); print(' '.join(sorted(sys.modules)))" % (command,))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    status, modules = done.stdout.strip().splitlines()[-2:]
    assert status == "0", done.stdout
    return set(modules.split())


def test_run_on_a_plane_imports_neither_scipy_optimize_nor_scipy_spatial(tmp_path):
    modules = _modules_after(["run", str(BENCHMARKS / "flume_snap.toml"), "--out", str(tmp_path),
                              "--duration", "0.34"])
    assert "scipy.optimize" not in modules
    assert "scipy.spatial" not in modules


def _random_cases(count=600, seed=7):
    """(f, a, b, options) of scalar root problems over many scales, either orientation."""
    rng = np.random.default_rng(seed)
    options = [{}, {"xtol": 1e-300, "rtol": 1e-15}, {"xtol": 1e-300, "rtol": 1e-15, "maxiter": 500},
               {"xtol": 1e-12, "rtol": 1e-14}, {"maxiter": 4}]
    for k in range(count):
        c = rng.normal(size=4) * 10.0 ** rng.integers(-5, 5)
        family = [lambda x, c=c: float(np.polyval(c, x)), lambda x, c=c: math.sinh(c[0] * x) - c[1],
                  lambda x, c=c: math.atan(x - c[0]) + 1e-3 * c[1], lambda x, c=c: x ** 3 - c[0]]
        a, b = sorted(rng.normal(size=2) * 10.0 ** rng.integers(-3, 3))
        yield (family[k % 4], a, b, options[k % 5]) if k % 2 else (family[k % 4], b, a, options[k % 5])


def _outcome(solver, f, a, b, options):
    try:
        return solver(f, a, b, **options)
    except (ValueError, RuntimeError, OverflowError) as error:
        return type(error).__name__, str(error)


def test_brentq_gives_scipys_roots_bit_for_bit():
    """The port of scipy's C brentq: the same roots (==, not approx) and the same errors (no sign
    change, too few iterations, NaN) on random problems and on the catenary start's own."""
    from scipy.optimize import brentq as scipy_brentq

    cases = list(_random_cases())
    cases += [(lambda x: x, 0.0, 1.0, {}), (lambda x: x * x + 1.0, -1.0, 1.0, {}),
              (lambda x: math.nan, 0.0, 1.0, {}), (lambda x: -0.0 if x < 0.3 else 1.0, 0.0, 1.0, {}),
              (lambda x: -1e-200 if x < 0.5 else 1e-200, 0.0, 1.0, {}),
              (lambda x: math.cosh(x / 120.0) * 120.0 - 100.0 - x, 0.0, 900.0, {"xtol": 1e-300, "rtol": 1e-15})]
    for f, a, b, options in cases:
        assert _outcome(brentq, f, a, b, options) == _outcome(scipy_brentq, f, a, b, options), (a, b, options)
