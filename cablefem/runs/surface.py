"""The free surface of a run in waves: ``waves.pvd``, a VTK time series of a grid over the scene's
extent whose heights are the elevation eta at the frames' times, so that ParaView and pyvista show
the lines under the waves (docs/outputs.md).

The grid spans the scene's horizontal extent (the seabed's bounds of ``cablefem.runs.run``); its
spacing resolves the shortest wave that carries energy (components of at least ``SIGNIFICANT`` of
the largest amplitude) with ``POINTS_PER_WAVELENGTH`` points, between ``MIN_POINTS`` and
``MAX_POINTS`` per side: each frame sums every component at every point of the grid, which for an
irregular sea of 200 components on a 200 x 64 grid cost more than the run's steps.
"""

import meshio
import numpy as np

from cablefem.io.vtk import TimeSeriesWriter

#: the collection's name: DIR/waves.pvd with frames DIR/waves_<k>.vtu
NAME = "waves"
POINTS_PER_WAVELENGTH, MIN_POINTS, MAX_POINTS, SIGNIFICANT = 8, 2, 100, 0.1


def grid_axes(sea, bounds):
    """x (nx,) and y (ny,) [m] of the surface's grid over bounds ((x0, x1), (y0, y1))."""
    amplitude, _, k = np.array(sea.amplitude), None, sea.arrays[2]
    carrying = k[(amplitude >= SIGNIFICANT * amplitude.max()) & (k > 0.0)]
    wavelength = 2.0 * np.pi / carrying.max() if carrying.size else np.inf
    axes = []
    for lo, hi in bounds:
        count = int(np.clip(np.ceil((hi - lo) / wavelength * POINTS_PER_WAVELENGTH) + 1, MIN_POINTS, MAX_POINTS))
        axes.append(np.linspace(lo, hi, count))
    return axes


def surface_mesh(x, y, eta):
    """A meshio mesh of quads over the grid x (nx,), y (ny,) with heights eta (ny, nx) as z and as the
    point data "eta"."""
    gx, gy = np.meshgrid(x, y)
    points = np.column_stack([gx.ravel(), gy.ravel(), eta.ravel()])
    nx, ny = len(x), len(y)
    corner = (np.arange(ny - 1)[:, None] * nx + np.arange(nx - 1)[None, :]).ravel()
    quads = np.column_stack([corner, corner + 1, corner + nx + 1, corner + nx])
    return meshio.Mesh(points, [("quad", quads)], point_data={"eta": eta.ravel()})


class SurfaceFrames:
    """The waves' frames of a run: ``write(t)`` adds the surface at time t [s] to waves.pvd."""

    def __init__(self, sea, bounds, folder):
        self.sea = sea
        self.x, self.y = grid_axes(sea, bounds)
        self.writer = TimeSeriesWriter(folder, NAME)

    def write(self, t):
        gx, gy = np.meshgrid(self.x, self.y)
        self.writer.write(t, surface_mesh(self.x, self.y, self.sea.elevation(gx, gy, t)))

    @property
    def listed(self):
        return self.writer.listed

    def close(self):
        self.writer.close()
