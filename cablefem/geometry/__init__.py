"""Seabed surfaces, independent of the FEM (desire2023 Sec. 2.2; housner2022 Sec. 2.1).

Every seabed implements ``Seabed.project`` (penetration depth, projection
direction, closest point and their derivatives) for points of shape (n, 3).

The planes are imported with the package; everything else (grids, triangulated
surfaces with their compiled walk, readers, generators) on first use, so that a
scene on a plane loads none of that machinery (start-up of ``cablefem static``).
"""

from importlib import import_module

from cablefem.geometry.base import Projection, Seabed
from cablefem.geometry.planes import Horizontal, Plane
from cablefem.geometry.simplify import choose_seabed, least_squares_plane, mean_depth_horizontal, simplify  # light: planes only

#: the package's other names -> the module that holds each
_LAZY = {"TriangulatedSurface": "triangulated", "DepthGrid": "grid", "read_seabed": "readers",
         "write_seabed_vtu": "export"}

__all__ = ["Horizontal", "Plane", "Projection", "Seabed", "choose_seabed", "generators", "least_squares_plane",
           "mean_depth_horizontal", "simplify", *_LAZY]


def __getattr__(name):
    """The lazily imported names (``_LAZY``) and the ``generators`` module."""
    if name == "generators":
        return import_module(f"{__name__}.generators")
    if name in _LAZY:
        return getattr(import_module(f"{__name__}.{_LAZY[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
