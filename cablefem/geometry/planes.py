"""Horizontal and inclined plane seabeds: point-to-plane projection in closed form
(desire2023 Sec. 2.2.2.1, Eq. 8-9)."""

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry.base import Projection, Seabed


def _grid_triangles(nx, ny):
    """Triangles (k, 3) of a structured nx x ny vertex grid, row-major (x fastest)."""
    i, j = np.meshgrid(np.arange(nx - 1), np.arange(ny - 1), indexing="xy")
    v0 = (j * nx + i).ravel()
    v1, v2, v3 = v0 + 1, v0 + nx + 1, v0 + nx
    return np.concatenate([np.stack([v0, v1, v2], 1), np.stack([v0, v2, v3], 1)])


class Plane(Seabed):
    """The plane through ``point`` with upward unit ``normal`` (n_z > 0)."""

    kind = "plane"

    def __init__(self, point, normal):
        point = np.asarray(point, dtype=float)
        normal = np.asarray(normal, dtype=float)
        if point.shape != (3,) or not np.all(np.isfinite(point)):
            raise InputError(f"expected 3 finite numbers, got {point.tolist()}", key="point")
        length = np.linalg.norm(normal) if normal.shape == (3,) else 0.0
        if not np.isfinite(length) or length == 0.0:
            raise InputError("expected a finite, non-zero 3-vector", key="normal")
        normal = normal / length
        if normal[2] <= 1e-6:
            raise InputError("the seabed normal must point up (n_z > 0)", key="normal")
        self.point = point
        self.normal = normal
        self.offset = float(normal @ point)  # k in r . n = k (Eq. 8)

    @classmethod
    def from_slope(cls, point, angle, azimuth=0.0):
        """Plane rising at ``angle`` [rad] towards the horizontal direction ``azimuth`` [rad]."""
        direction = np.array([np.cos(azimuth), np.sin(azimuth), 0.0])
        normal = np.array([0.0, 0.0, np.cos(angle)]) - np.sin(angle) * direction
        return cls(point, normal)

    def project(self, points):
        points = np.asarray(points, dtype=float)
        gap = points @ self.normal - self.offset  # -mu_i of Eq. 9
        n = len(points)
        direction = np.broadcast_to(self.normal, (n, 3))
        return Projection(
            gap=gap,
            direction=direction,
            closest=points - gap[:, None] * self.normal,
            gap_gradient=direction,
            direction_gradient=np.zeros((n, 3, 3)),
        )

    def gap_only(self, points):
        return np.asarray(points, dtype=float) @ self.normal - self.offset

    def elevation(self, xy):
        xy = np.asarray(xy, dtype=float)
        return (self.offset - xy @ self.normal[:2]) / self.normal[2]

    def surface(self, bounds=None, resolution=2):
        (x0, x1), (y0, y1) = bounds if bounds is not None else ((-1000.0, 1000.0), (-1000.0, 1000.0))
        x, y = np.meshgrid(np.linspace(x0, x1, resolution), np.linspace(y0, y1, resolution))
        xy = np.column_stack([x.ravel(), y.ravel()])
        points = np.column_stack([xy, self.elevation(xy)])
        return points, _grid_triangles(resolution, resolution)

    def slope_angle(self):
        """Inclination of the plane to the horizontal [rad]."""
        return float(np.arccos(np.clip(self.normal[2], -1.0, 1.0)))

    def describe(self):
        n = self.normal
        return (f"plane through {np.round(self.point, 6).tolist()} with normal "
                f"[{n[0]:.6g}, {n[1]:.6g}, {n[2]:.6g}] "
                f"({np.degrees(self.slope_angle()):.4g} deg slope)")


class Horizontal(Plane):
    """The horizontal seabed z = -depth (d_P = e_3, d_G = z + depth)."""

    kind = "horizontal"

    def __init__(self, depth):
        if isinstance(depth, bool) or not isinstance(depth, (int, float, np.floating, np.integer)) \
                or not np.isfinite(depth) or depth <= 0:
            raise InputError(f"must be a finite number > 0, got {depth!r}", key="depth")
        self.depth = float(depth)
        super().__init__([0.0, 0.0, -self.depth], [0.0, 0.0, 1.0])

    def project(self, points):
        points = np.asarray(points, dtype=float)
        gap = points[:, 2] + self.depth
        n = len(points)
        closest = points.copy()
        closest[:, 2] = -self.depth
        direction = np.broadcast_to(self.normal, (n, 3))
        return Projection(gap, direction, closest, direction, np.zeros((n, 3, 3)))

    def gap_only(self, points):
        return np.asarray(points, dtype=float)[:, 2] + self.depth

    def elevation(self, xy):
        return np.full(len(np.asarray(xy)), -self.depth)

    def describe(self):
        return f"horizontal at z = {-self.depth:g} m"
