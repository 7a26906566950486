"""cablefem variants that switch one physics difference to MoorDyn-C's model, for the side-by-side
study only (cablefem itself keeps the models of desire2023).

- ``VerticalSeabed``: MoorDyn-C 2.7's seabed contact is vertical (``Line::getStateDeriv``:
  B_z = ((z_b - z) kBot - v_z cBot) d l, "vertical-only for now"; housner2022 Eq. 3), and its
  friction acts on the horizontal velocity (v_x, v_y). Wrapping a seabed so that its
  projection direction is e_z and its gap the vertical height z - z_b(x, y) gives cablefem's
  contact (desire2023 Eq. 11) and friction (Eq. 12, in the plane normal to d_P) exactly
  these directions, with cablefem's own penalty law and exact derivatives.
- ``PerUnstretchedLength``: MoorDyn-C weights drag and added mass by the unstretched segment
  length (and volume); desire2023 Eq. 1 by the stretched one, |r'| = 1 + e times more. The
  wrapper divides any load's force and derivatives by |r'|.
- MoorDyn-C's seabed damping on points moving out, once a wrapper here, is cablefem's
  ``[seabed] damping_when_opening`` (``cablefem.loads.contact``).
"""

import numpy as np

from cablefem.geometry import DepthGrid, Plane
from cablefem.geometry.base import Projection, Seabed
from cablefem.loads import Terms, outer

UP = np.array([0.0, 0.0, 1.0])


def _slopes(seabed, xy):
    """Elevation z_b (n,) [m] and slopes dz_b/dx, dz_b/dy (n,) of a Plane or DepthGrid below xy (n, 2)."""
    if isinstance(seabed, Plane):
        n = seabed.normal
        count = len(xy)
        return seabed.elevation(xy), np.full(count, -n[0] / n[2]), np.full(count, -n[1] / n[2])
    if isinstance(seabed, DepthGrid):
        elevation, slope_x, slope_y, _ = seabed._patch(xy)
        return elevation, slope_x, slope_y
    raise TypeError(f"VerticalSeabed wraps a Plane or a DepthGrid, not {type(seabed).__name__}")


class VerticalSeabed(Seabed):
    """``seabed`` (Plane or DepthGrid) with MoorDyn-C's vertical contact: gap z - z_b(x, y) [m],
    projection direction e_z, closest point (x, y, z_b)."""

    def __init__(self, seabed):
        self.inner = seabed
        self.kind = f"vertical {seabed.kind}"

    def project(self, points):
        """Vertical gap, direction e_z and their derivatives for points (n, 3) [m]."""
        points = np.asarray(points, dtype=float).reshape(-1, 3)
        elevation, slope_x, slope_y = _slopes(self.inner, points[:, :2])
        count = len(points)
        gap = points[:, 2] - elevation
        gradient = np.column_stack([-slope_x, -slope_y, np.ones(count)])
        closest = points.copy()
        closest[:, 2] = elevation
        return Projection(gap=gap, direction=np.broadcast_to(UP, (count, 3)), closest=closest,
                          gap_gradient=gradient, direction_gradient=np.zeros((count, 3, 3)))

    def gap_only(self, points):
        """Vertical gap z - z_b [m], shape (n,), for points (n, 3) [m]."""
        points = np.asarray(points, dtype=float).reshape(-1, 3)
        return points[:, 2] - self.inner.elevation(points[:, :2])

    def elevation(self, xy):
        """Seabed elevation z_b [m], shape (n,), below xy (n, 2) [m]."""
        return self.inner.elevation(xy)

    def surface(self, bounds=None):
        """The wrapped seabed's surface (points (m, 3), triangles (k, 3))."""
        return self.inner.surface(bounds)

    def describe(self):
        """One line: the wrapped seabed and the vertical contact."""
        return f"{self.inner.describe()}, contact and friction made vertical/horizontal (MoorDyn-C)"


class PerUnstretchedLength:
    """A load (drag, added mass) per unit unstretched length: its force and derivatives over |r'|."""

    def __init__(self, load):
        self.wrapped = load
        self.rule = getattr(load, "rule", "full")

    def evaluate(self, state, jacobian=True):
        terms = self.wrapped.evaluate(state, jacobian)
        if terms.force is None:
            return terms
        stretch = np.sqrt(np.einsum("ceq,ceq->eq", state.dr, state.dr))
        force = terms.force / stretch
        scaled = Terms(force=force)
        if not jacobian:
            return scaled
        for name in ("force_r", "force_v", "force_dv", "force_a"):
            block = getattr(terms, name)
            setattr(scaled, name, None if block is None else block / stretch)
        # f / |r'|: d/dr' = (df/dr' - (f / |r'|) t^T) / |r'|, t = r' / |r'|
        tangent = state.dr / stretch
        base = 0.0 if terms.force_dr is None else terms.force_dr
        scaled.force_dr = (base - outer(force, tangent)) / stretch
        return scaled
