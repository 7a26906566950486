"""The seabed interface every surface implements (desire2023 Sec. 2.2.1).

For points r (n, 3) a seabed returns the penetration depth d_G (Eq. 7,
positive above the seabed, negative when buried), the unit projection
direction d_P (Eq. 6, pointing to the water), the closest point r' on the
surface, and the derivatives of d_G and d_P with respect to r that the
Newton tangent needs. Geometry knows nothing of the FEM.
"""

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Projection:
    """Projection of n points onto a seabed (arrays; SI units).

    gap: (n,) penetration depth d_G [m], > 0 above the seabed.
    direction: (n, 3) unit projection direction d_P, towards the water.
    closest: (n, 3) projected point r' on the surface [m].
    gap_gradient: (n, 3) d(d_G)/dr.
    direction_gradient: (n, 3, 3) d(d_P)_a / dr_b, zero on planes.
    """

    gap: np.ndarray
    direction: np.ndarray
    closest: np.ndarray
    gap_gradient: np.ndarray
    direction_gradient: np.ndarray


class Seabed:
    """Base class: a surface below the water that lines rest on."""

    #: short name of the model in use ("horizontal", "plane", "grid", "mesh")
    kind = "seabed"

    def project(self, points):
        """Projection of points (n, 3) [m] onto the surface, as a ``Projection``."""
        raise NotImplementedError

    def elevation(self, xy):
        """Seabed elevation z [m], shape (n,), below horizontal positions xy (n, 2)."""
        raise NotImplementedError

    def surface(self, bounds=None):
        """The surface as (points (m, 3), triangles (k, 3)) over bounds ((xmin, xmax), (ymin, ymax))."""
        raise NotImplementedError

    def describe(self):
        """One line saying which model this is and its parameters."""
        return self.kind

    def gap_only(self, points):
        """Penetration depth d_G [m], shape (n,), without the derivatives."""
        return self.project(points).gap
