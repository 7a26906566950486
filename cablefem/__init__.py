"""cablefem: finite element mooring lines and marine cables on real seabeds.

The line is a field r(s) in R^3 over unstretched arc length s (desire2023
Eq. 1), discretised with scikit-fem; seabeds live in ``cablefem.geometry``.
"""

from cablefem.compiled.cache import refresh as _refresh_jit_cache
from cablefem.errors import ConvergenceError, InputError
from cablefem.model.line import Line, LineType, Segment

_refresh_jit_cache()  # before any compiled kernel is loaded from numba's cache

__all__ = ["ConvergenceError", "InputError", "Line", "LineType", "Segment", "sweep"]
__version__ = "0.1.0"


def __getattr__(name):
    """``cablefem.sweep`` (``cablefem.sweeps.sweep``), imported on first use: dask and pandas stay
    out of ``import cablefem``."""
    if name == "sweep":
        from cablefem.sweeps import sweep

        return sweep
    raise AttributeError(f"module 'cablefem' has no attribute {name!r}")
