"""Seabed surfaces, independent of the FEM (desire2023 Sec. 2.2; housner2022 Sec. 2.1).

Every seabed implements ``Seabed.project`` (penetration depth, projection
direction, closest point and their derivatives) for points of shape (n, 3).
"""

from .base import Projection, Seabed
from .planes import Horizontal, Plane

__all__ = ["Horizontal", "Plane", "Projection", "Seabed"]
