"""Seabed surfaces, independent of the FEM (desire2023 Sec. 2.2; housner2022 Sec. 2.1).

Every seabed implements ``Seabed.project`` (penetration depth, projection
direction, closest point and their derivatives) for points of shape (n, 3).
"""

from .base import Projection, Seabed
from .planes import Horizontal, Plane

__all__ = ["Horizontal", "Plane", "Projection", "Seabed"]

from .triangulated import TriangulatedSurface  # noqa: E402  (issue 3: vertex-normal projection)

__all__ += ["TriangulatedSurface"]

from .grid import DepthGrid  # noqa: E402  (issue 3: rectangular grids, readers, generators)
from .readers import read_seabed  # noqa: E402
from .simplify import choose_seabed, least_squares_plane, mean_depth_horizontal, simplify  # noqa: E402
from .export import write_seabed_vtu  # noqa: E402
from . import generators  # noqa: E402

__all__ += ["DepthGrid", "choose_seabed", "generators", "least_squares_plane", "mean_depth_horizontal",
            "read_seabed", "simplify", "write_seabed_vtu"]
