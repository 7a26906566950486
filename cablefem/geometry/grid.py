"""Rectangular depth grid with bilinear interpolation (housner2022 Sec. 2.1, Eq. 4).

The seabed elevation z_b(x, y) is bilinear inside each grid cell and constant
(clamped to the nearest edge) outside the grid, as MoorDyn-C's
``Seafloor::getDepthAt`` does. The projection is MoorDyn's: the gap is the
vertical height above the seabed times the vertical component of the local unit
normal, d_G = (z - z_b(x, y)) n_z (housner2022 Eq. 4, "(z_b - r_3) n_z" with
the sign of desire2023 Eq. 7), the projection direction is the normal of the
bilinear patch below the point, d_P = n, and the closest point is r - d_G n.
Its derivatives are those of this surface, exact.

The normal is continuous inside a cell and jumps across grid lines where the
slope does (a bilinear grid is only C0); the vertex-normal triangulated
surface is the smooth alternative (desire2023 Sec. 2.2.2.2).

``project`` and ``gap_only`` run as one compiled loop over the points
(``_project``, numba): a line has ~100 points, for which the numpy
version's ~30 array calls take ~100 us and the loop ~7 us. The numpy
version stays as the reference (``DepthGrid.compiled = False``); both give
the same bits (``tests/test_projection_compiled.py``).
"""

import numpy as np
from numba import njit

from cablefem.errors import InputError
from cablefem.geometry.base import Projection, Seabed
from cablefem.geometry.planes import _grid_triangles


def _axis(values, name):
    """A strictly increasing axis (m,) of finite floats [m], or an InputError naming it."""
    axis = np.asarray(values, dtype=float)
    if axis.ndim != 1 or len(axis) < 2:
        raise InputError(f"needs at least 2 values in a 1-D list, got shape {axis.shape}", key=name)
    bad = np.flatnonzero(~np.isfinite(axis))
    if len(bad):
        raise InputError(f"{name}[{bad[0]}] = {axis[bad[0]]} is not a finite number", key=name)
    step = np.flatnonzero(np.diff(axis) <= 0)
    if len(step):
        k = step[0] + 1
        raise InputError(f"must increase strictly: {name}[{k}] = {axis[k]:g} "
                         f"follows {name}[{k - 1}] = {axis[k - 1]:g}", key=name)
    return np.ascontiguousarray(axis)


def _locate(axis, values):
    """Cell index (n,), local coordinate in [0, 1] (n,), cell size [m] (n,) and
    whether the coordinate lies on the grid (n,) for coordinates values (n,) [m]."""
    clamped = np.clip(values, axis[0], axis[-1])
    cell = np.clip(np.searchsorted(axis, clamped, side="right") - 1, 0, len(axis) - 2)
    size = axis[cell + 1] - axis[cell]
    inside = (values >= axis[0]) & (values <= axis[-1])
    return cell, (clamped - axis[cell]) / size, size, inside


@njit(cache=True, error_model="numpy")
def _cell(axis, value):
    """``_locate`` for one coordinate [m]: cell, local coordinate, cell size [m], on the grid."""
    last = len(axis) - 1
    clamped = axis[0] if value < axis[0] else (axis[last] if value > axis[last] else value)
    cell = min(max(np.searchsorted(axis, clamped, side="right") - 1, 0), last - 1)
    size = axis[cell + 1] - axis[cell]
    return cell, (clamped - axis[cell]) / size, size, axis[0] <= value <= axis[last]


@njit(cache=True, error_model="numpy")
def _project(xyz, x, y, z, derivatives, out):
    """``DepthGrid.project`` (or, without ``derivatives``, ``gap_only``) of points xyz (3, n) [m]
    into out (19, n): the gap, direction (3), closest point (3), gap gradient (3) and direction
    gradient (3 x 3, row a at 3 a), as ``_walk_jit.project`` packs them."""
    for k in range(xyz.shape[1]):
        i, u, hx, in_x = _cell(x, xyz[0, k])
        j, v, hy, in_y = _cell(y, xyz[1, k])
        z00 = z[j, i]
        dzx = z[j, i + 1] - z00
        dzy = z[j + 1, i] - z00
        twist = z[j + 1, i + 1] - z[j, i + 1] - dzy
        elevation = z00 + dzx * u + dzy * v + twist * u * v
        p = (dzx + twist * v) / hx if in_x else 0.0
        q = (dzy + twist * u) / hy if in_y else 0.0
        height = xyz[2, k] - elevation
        if not derivatives:
            out[0, k] = height / np.sqrt(1.0 + p * p + q * q)
            continue
        s = twist / (hx * hy) if in_x and in_y else 0.0
        n_z = 1.0 / np.sqrt(1.0 + p * p + q * q)
        n0, n1 = -p * n_z, -q * n_z
        gap = height * n_z
        out[0, k], out[1, k], out[2, k], out[3, k] = gap, n0, n1, n_z
        out[4, k], out[5, k], out[6, k] = xyz[0, k] - gap * n0, xyz[1, k] - gap * n1, xyz[2, k] - gap * n_z
        # dN = [[0, -s, 0], [-s, 0, 0], [0, 0, 0]]; d(d_P) = n_z (dN - n (n^T dN))
        along0, along1 = -s * n1, -s * n0
        out[10, k], out[11, k], out[12, k] = n_z * (-n0 * along0), n_z * (-s - n0 * along1), 0.0
        out[13, k], out[14, k], out[15, k] = n_z * (-s - n1 * along0), n_z * (-n1 * along1), 0.0
        out[16, k], out[17, k], out[18, k] = n_z * (-n_z * along0), n_z * (-n_z * along1), 0.0
        out[7, k], out[8, k], out[9, k] = n0 + height * out[16, k], n1 + height * out[17, k], n_z
    return out


class DepthGrid(Seabed):
    """Seabed elevation z (ny, nx) [m, negative below water] on axes x (nx,), y (ny,) [m].

    Bilinear inside the cells, clamped outside; ``z[j, i]`` is the elevation at
    ``(x[i], y[j])``.
    """

    kind = "grid"
    #: project with the compiled loop (``_project``); False: the numpy reference
    compiled = True

    def __init__(self, x, y, z):
        self.x = _axis(x, "x")
        self.y = _axis(y, "y")
        z = np.asarray(z, dtype=float)
        shape = (len(self.y), len(self.x))
        if z.shape != shape:
            raise InputError(f"expected shape (ny, nx) = {shape}, got {z.shape}", key="z")
        holes = np.argwhere(~np.isfinite(z))
        if len(holes):
            j, i = holes[0]
            raise InputError(f"no finite elevation at x = {self.x[i]:g}, y = {self.y[j]:g} "
                             f"({len(holes)} such nodes)", key="z")
        self.z = np.ascontiguousarray(z)  # as the compiled loop takes it

    @property
    def vertices(self):
        """Grid nodes (nx * ny, 3) [m], x fastest (row j of z after row j - 1)."""
        gx, gy = np.meshgrid(self.x, self.y)
        return np.column_stack([gx.ravel(), gy.ravel(), self.z.ravel()])

    @property
    def bounds(self):
        """((xmin, xmax), (ymin, ymax)) of the grid [m]."""
        return (float(self.x[0]), float(self.x[-1])), (float(self.y[0]), float(self.y[-1]))

    def _patch(self, xy):
        """Elevation z_b (n,), slopes dz_b/dx, dz_b/dy (n,) and twist d2z_b/dxdy (n,)
        of the clamped bilinear surface below xy (n, 2) [m]."""
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        i, u, hx, in_x = _locate(self.x, xy[:, 0])
        j, v, hy, in_y = _locate(self.y, xy[:, 1])
        z00 = self.z[j, i]
        dzx = self.z[j, i + 1] - z00                     # along x at v = 0
        dzy = self.z[j + 1, i] - z00                     # along y at u = 0
        twist = self.z[j + 1, i + 1] - self.z[j, i + 1] - dzy
        elevation = z00 + dzx * u + dzy * v + twist * u * v
        # Outside the grid the clamped coordinate does not move with the point.
        slope_x = np.where(in_x, (dzx + twist * v) / hx, 0.0)
        slope_y = np.where(in_y, (dzy + twist * u) / hy, 0.0)
        curvature = np.where(in_x & in_y, twist / (hx * hy), 0.0)
        return elevation, slope_x, slope_y, curvature

    def elevation(self, xy):
        """Seabed elevation z_b [m], shape (n,), below horizontal positions xy (n, 2) [m]."""
        return self._patch(xy)[0]

    def normal(self, xy):
        """Upward unit normal (n, 3) of the bilinear patch below xy (n, 2) [m]."""
        _, p, q, _ = self._patch(xy)
        n_z = 1.0 / np.sqrt(1.0 + p * p + q * q)
        return np.column_stack([-p * n_z, -q * n_z, n_z])

    def project(self, points):
        """Gap (z - z_b) n_z, direction n, closest point and exact derivatives for points (n, 3) [m]."""
        if self.compiled:
            xyz = np.ascontiguousarray(np.asarray(points, dtype=float).reshape(-1, 3).T)
            out = _project(xyz, self.x, self.y, self.z, True, np.empty((19, xyz.shape[1])))
            return Projection(gap=out[0], direction=out[1:4].T, closest=out[4:7].T, gap_gradient=out[7:10].T,
                              direction_gradient=out[10:19].reshape(3, 3, -1).transpose(2, 0, 1))
        points = np.asarray(points, dtype=float).reshape(-1, 3)
        elevation, p, q, s = self._patch(points[:, :2])
        n_z = 1.0 / np.sqrt(1.0 + p * p + q * q)
        normal = np.column_stack([-p * n_z, -q * n_z, n_z])
        height = points[:, 2] - elevation
        gap = height * n_z
        # n = N / |N| with N = (-p, -q, 1); dN/dx = (0, -s, 0), dN/dy = (-s, 0, 0),
        # dN/dz = 0 (the Hessian of a bilinear patch is [[0, s], [s, 0]]), and
        # dn = (I - n n^T) dN / |N|.
        n_points = len(points)
        jac_N = np.zeros((n_points, 3, 3))
        jac_N[:, 1, 0] = -s
        jac_N[:, 0, 1] = -s
        along_n = np.einsum("na,nab->nb", normal, jac_N)
        direction_gradient = n_z[:, None, None] * (jac_N - normal[:, :, None] * along_n[:, None, :])
        # d(height n_z)/dr = N n_z + height dn_z/dr, and N n_z = n.
        gap_gradient = normal + height[:, None] * direction_gradient[:, 2, :]
        return Projection(gap=gap, direction=normal, closest=points - gap[:, None] * normal,
                          gap_gradient=gap_gradient, direction_gradient=direction_gradient)

    def gap_only(self, points):
        """Gap (z - z_b) n_z [m], shape (n,), for points (n, 3) [m], without derivatives."""
        if self.compiled:
            xyz = np.ascontiguousarray(np.asarray(points, dtype=float).reshape(-1, 3).T)
            return _project(xyz, self.x, self.y, self.z, False, np.empty((1, xyz.shape[1])))[0]
        points = np.asarray(points, dtype=float).reshape(-1, 3)
        elevation, p, q, _ = self._patch(points[:, :2])
        return (points[:, 2] - elevation) / np.sqrt(1.0 + p * p + q * q)

    def surface(self, bounds=None):
        """The grid as (points (m, 3), triangles (k, 3)), two triangles per cell, over bounds.

        bounds ((xmin, xmax), (ymin, ymax)) [m] defaults to the grid's own; the
        grid lines inside the bounds are kept and lines on the bounds added, so
        the clamped extension outside the grid is drawn exactly.
        """
        if bounds is None:
            gx, gy = self.x, self.y
        else:
            (x0, x1), (y0, y1) = bounds
            if not (x1 > x0 and y1 > y0):
                raise InputError(f"expected ((xmin, xmax), (ymin, ymax)) with max > min, got {bounds}",
                                 key="bounds")
            gx = np.concatenate([[x0], self.x[(self.x > x0) & (self.x < x1)], [x1]])
            gy = np.concatenate([[y0], self.y[(self.y > y0) & (self.y < y1)], [y1]])
        mx, my = np.meshgrid(gx, gy)
        xy = np.column_stack([mx.ravel(), my.ravel()])
        points = np.column_stack([xy, self.elevation(xy)])
        return points, _grid_triangles(len(gx), len(gy))

    def least_squares_plane(self):
        """The plane fitted to the grid nodes in the least-squares sense (desire2023 Sec. 5)."""
        from cablefem.geometry.simplify import least_squares_plane
        return least_squares_plane(self.vertices)

    def mean_depth_horizontal(self):
        """The horizontal seabed at the mean elevation of the grid nodes (desire2023 Sec. 5)."""
        from cablefem.geometry.simplify import mean_depth_horizontal
        return mean_depth_horizontal(self.vertices)

    def describe(self):
        """One line: grid size, extent and elevation range."""
        (x0, x1), (y0, y1) = self.bounds
        return (f"grid {len(self.x)} x {len(self.y)} over x [{x0:g}, {x1:g}] m, "
                f"y [{y0:g}, {y1:g}] m, z from {self.z.min():g} to {self.z.max():g} m "
                f"(bilinear, clamped outside)")
