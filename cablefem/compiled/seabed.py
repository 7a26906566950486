"""The seabed projected inside the compiled steps (``cablefem.compiled.steps``): a plane by the kernel itself,
a ``DepthGrid`` by its compiled bilinear projection, a ``TriangulatedSurface`` by its compiled walk
(``geometry._walk_jit.project``), which starts where the seabed's last call for these points ended.
When the walk cannot place a point (it moved beyond its triangle's neighbours), ``project`` says so
and the step goes on in Python, whose search finds it.
"""

from collections import namedtuple

from numba import njit

from cablefem.dynamics import policy
from cablefem.geometry import _walk_jit as walk
from cablefem.geometry.grid import _project as _grid_project

#: seabeds the loop projects itself: a plane (in the kernel), a depth grid, a triangulated surface
PLANE, GRID, TRIANGULATED = 0, 1, 2
#: the seabed's projection in the loop: kind, a grid's axes and depths, a triangulated surface's
#: tables (``walk.Surface``) and typical triangle size [m], the walk's warm start (``walk.Start``),
#: and scratch: what the walk finds with the packed outputs (``walk.Result``; a grid's outputs in
#: its ``out``) and the points (3, n)
Projector = namedtuple("Projector", "kind gx gy gz surface typical start result xyz")


@njit(cache=True)
def project(proj, X1, mesh, bed, derivatives):
    """Project the full quadrature points of X1 onto a grid or triangulated seabed into the bed's
    gap (nel, nq), normal and, with ``derivatives`` (a tangent needs them), gap gradient (nel, nq, 3)
    and normal gradient (nel, nq, 3, 3), as ``FusedEvaluator.bed`` does through ``Seabed.project``;
    the walk's warm start moves on to this call. Returns the number of points the walk did not
    place (-1: moved too far)."""
    dofs, phi, xyz, out = mesh.dofs, mesh.phi, proj.xyz, proj.result.out
    nel, nloc = dofs.shape
    nq = phi.shape[2]
    for e in range(nel):
        for g in range(nq):
            p = e * nq + g
            for a in range(3):
                acc = 0.0
                for l in range(nloc):
                    acc += phi[l, e, g] * X1[dofs[e, l], a]
                xyz[a, p] = acc
    if proj.kind == GRID:
        _grid_project(xyz, proj.gx, proj.gy, proj.gz, policy.FLAG[1], out)
    else:
        mode = walk.EVERYTHING if derivatives else walk.GAP_AND_DIRECTION
        lost = walk.project(xyz, proj.surface, proj.start, proj.typical, policy.FLAG[1], mode, proj.result)
        if lost != 0:
            return lost
        start, result = proj.start, proj.result
        for p in range(xyz.shape[1]):  # the next call starts here (loops: no temporary copies)
            for a in range(3):
                start.origin[a, p] = xyz[a, p]
            start.triangle[p] = result.triangle[p]
            start.h[p] = result.sth[2, p]
            start.unheld[p] = False
    for e in range(nel):
        for g in range(nq):
            p = e * nq + g
            bed.gap[e, g] = out[walk.GAP, p]
            for a in range(3):
                bed.normal[e, g, a] = out[1 + a, p]  # walk.DIRECTION
                if derivatives:
                    bed.grad_gap[e, g, a] = out[7 + a, p]  # walk.GAP_GRADIENT
                    for b in range(3):
                        bed.dnormal[e, g, a, b] = out[10 + 3 * a + b, p]  # walk.DIRECTION_GRADIENT
    return 0
