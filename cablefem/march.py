"""BDF2 steps on the compiled kernel, many in one numba call: the policy's compiled ops.

``cablefem.policy`` writes the Newton policy once (iterations, line search, branch corrections,
retries, halving and growth); this module binds it to compiled ops and compiles it (``STEPS``).
A step spent ~90 us per Newton iteration in Python around the compiled kernel (state updates,
norms, LU calls through scipy, the boundary motion), more than the kernel itself on the small
meshes of the coarse accuracy levels (verification/work_precision/README.md); here runs of
steps go without returning to Python, and the numbers are those of the Python ops to round-off
(``tests/test_march.py``).

The scheme is variable-step BDF2 (desire2023 Sec. 2.1.2: backward Euler to start, then
y' ~ c0 y_{n+1} + c1 y_n + c2 y_{n-1} on X and V). The banded LU is ``cablefem.banded``
(LAPACK's dgbtf2/dgbtrs written out for numba: numba cannot cache a ctypes call to LAPACK).

The seabed is projected in the loop too: a plane by the kernel itself, a ``DepthGrid`` by its
compiled bilinear projection, a ``TriangulatedSurface`` by its compiled walk
(``geometry._walk_jit.project``), which starts where the seabed's last call for these points ended
and hands its last call back. When the walk cannot place a point (it moved beyond its triangle's
neighbours), the loop stops and that step goes on in Python, whose search finds it.
"""

from collections import namedtuple

import numpy as np
from numba import njit

from . import kernels, policy
from .banded import lu_factor, lu_solve
from .geometry import _walk_jit as walk
from .geometry.grid import _project as _grid_project
from .geometry._search import WALK_STEPS

#: seabeds the loop projects itself: a plane (in the kernel), a depth grid, a triangulated surface
PLANE, GRID, TRIANGULATED = 0, 1, 2
#: a step of the compiled loop may be halved this many times (the fairlead's positions at the
#: 2**DEPTH - 1 points that split each step evenly are given); deeper, the Python ops go on
DEPTH = 3
FRACTIONS = 2 ** DEPTH

#: the seabed's projection in the loop: kind, a grid's axes and depths, a triangulated surface's
#: tables (``walk.Surface``) and typical triangle size [m], the walk's warm start (``walk.Start``),
#: and scratch: what the walk finds with the packed outputs (``walk.Result``; a grid's outputs in
#: its ``out``) and the points (3, n)
Projector = namedtuple("Projector", "kind gx gy gz surface typical start result xyz")
#: a run's clock (one record): t [s], the step before (0 at the start), the last step (0 if none), the
#: attempt that stopped the run, the last attempt's final relative residual, the attempt's c0
CLOCK = np.dtype([("t", "f8"), ("h_before", "f8"), ("last_h", "f8"), ("stopped", "f8"), ("residual", "f8"),
                  ("c0", "f8")])
#: what modified Newton's kept factors belong to (one record, kept between runs): the c0 of the
#: factors (NaN: none) and "auto"'s full-Newton attempts still to run
FACTORS = np.dtype([("c0", "f8"), ("auto_left", "f8")])
#: everything the compiled ops read and write (``Marcher.problem``): the kernel's records; the state
#: X, V, A, the step before's Xp, Vp, the last predictor and the rows M A + G (N, 3), updated in
#: place; the trial X1, V1, A1, the guess, BDF2's histories and Newton's base (N, 3); the increment,
#: Newton's step and its own step when corrected (n,); the band and its LU (flat, LAPACK's
#: column-major layout), pivots and multipliers; the base's branch state; the byte views (dst, src)
#: that keep the branch state as the base's and commit the trial history; the clock (CLOCK) and the
#: factors' key (FACTORS); counters (policy.COUNTERS); the anchor and the fairlead at the end of
#: each step (m, 2, 3) and at its splits (m, FRACTIONS - 1, 2, 3), and at the end of the attempt
#: (2, 3) (an end that is not prescribed, ``Line.prescribed``, is an unknown like the others)
Problem = namedtuple("Problem", "settings mesh bed pts work projector free_nodes free_order all_elements "
                                "end_elements anchor_node fairlead_node scale "
                                "X V A Xp Vp prediction rows X1 V1 A1 guess x_hist v_hist base "
                                "rhs step original band lu ipiv multipliers base_full base_reduced keeps commits "
                                "clock factors counters ends fractions target")


@njit(cache=True, _nrt=False)
def _copy_rows(dst, src):
    """dst[:] = src for (N, 3) arrays, as a loop (a slice copy would need numba's runtime)."""
    for i in range(dst.shape[0]):
        for a in range(3):
            dst[i, a] = src[i, a]


@njit(cache=True, _nrt=False)
def _copy_flat(dst, src):
    """dst[:] = src for 1-d arrays, as a loop."""
    for i in range(dst.shape[0]):
        dst[i] = src[i]


@njit(cache=True, _nrt=False)
def _largest(x):
    """max |x_j|, or NaN if an entry is NaN."""
    size = 0.0
    for j in range(x.shape[0]):
        v = abs(x[j])
        if v != v:
            return v
        if v > size:
            size = v
    return size


@njit(cache=True)
def _project(proj, X1, mesh, bed, derivatives):
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
        lost = walk.project(xyz, proj.surface, proj.start, proj.typical, WALK_STEPS, policy.FLAG[1], mode,
                            proj.result)
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


# ------------------------------------------------------------------------- the policy's ops
@njit(cache=True, _nrt=False)
def _point(prob):
    """V and A of BDF2 at the trial positions X1: V = c0 X1 + x_hist, A = c0 V + v_hist."""
    c0 = prob.clock[0].c0
    X1, V1, A1, x_hist, v_hist = prob.X1, prob.V1, prob.A1, prob.x_hist, prob.v_hist
    for i in range(X1.shape[0]):
        for a in range(3):
            V1[i, a] = c0 * X1[i, a] + x_hist[i, a]
            A1[i, a] = c0 * V1[i, a] + v_hist[i, a]


@njit(cache=True, _nrt=False)
def _assemble(prob, tangent, held, elements):
    """The step residual M A + G at the trial point into ``prob.rows`` over ``elements`` and, with
    ``tangent``, its banded tangent into ``prob.band`` (both zeroed first), the seabed projected first
    unless it is a plane. Returns the projection's status (0, or the points the walk did not place)."""
    _point(prob)
    if prob.projector.kind != PLANE:
        lost = _project(prob.projector, prob.X1, prob.mesh, prob.bed, tangent)
        if lost != 0:
            return lost
    c0 = prob.clock[0].c0
    nb = prob.rhs.shape[0]
    ld = 2 * prob.mesh.kl + prob.mesh.ku + 1
    band2 = prob.band.reshape((nb, ld)).T  # the (ld, nb) column-major view the assembly writes
    prob.rows[:] = 0.0
    if tangent:
        band2.T[:] = 0.0  # the contiguous (nb, ld) view: a memset, not a strided walk
    kernels.assemble(prob.mesh, prob.bed, prob.pts, prob.work, (prob.X1, prob.V1, prob.A1), (c0, c0 * c0),
                     tangent, held, prob.rows, band2, elements)
    if prob.mesh.nodes.shape[0]:
        kernels.assemble_nodes(prob.mesh, prob.pts, prob.work, (prob.X1, prob.V1, prob.A1), (c0, c0 * c0),
                               tangent, prob.rows, band2)
    prob.counters[policy.NFEV] += 1
    return 0


@njit(cache=True, inline="always", _nrt=False)
def evaluate(prob, tangent, held):
    return _assemble(prob, tangent, held, prob.all_elements)


@njit(cache=True, inline="always", _nrt=False)
def finish(prob):
    """The reactions need only the end rows: evaluate the two end elements."""
    return _assemble(prob, policy.FLAG[0], policy.FLAG[0], prob.end_elements)


@njit(cache=True, inline="always", _nrt=False)
def norm(prob):
    total = 0.0
    for i in prob.free_nodes:
        for a in range(3):
            total += prob.rows[i, a] * prob.rows[i, a]
    return np.sqrt(total) / prob.scale


@njit(cache=True, _nrt=False)
def increment(prob, refactor):
    """The Newton increment of the free unknowns for the rows into ``prob.rhs`` (band order): with
    ``refactor`` from fresh LU factors of the band (counted; ``factors.c0`` the c0 they belong to,
    NaN when singular), else from those kept. Returns its largest entry (NaN: singular)."""
    mesh, key, counters, rhs = prob.mesh, prob.factors[0], prob.counters, prob.rhs
    if refactor:
        counters[policy.NJEV] += 1
        _copy_flat(prob.lu, prob.band)
        key.c0 = np.nan
        if not lu_factor(prob.lu, prob.ipiv.shape[0], mesh.kl, mesh.ku, prob.ipiv, prob.multipliers):
            return np.nan
        counters[policy.NLU] += 1
        key.c0 = prob.clock[0].c0
    for j in range(prob.free_order.shape[0]):
        for a in range(3):
            rhs[3 * j + a] = -prob.rows[prob.free_order[j], a]
    lu_solve(prob.lu, rhs.shape[0], mesh.kl, mesh.ku, prob.ipiv, rhs)
    size = _largest(rhs)
    _copy_flat(prob.step, rhs)
    return size


@njit(cache=True, inline="always", _nrt=False)
def factors_current(prob):
    return prob.factors[0].c0 == prob.clock[0].c0


@njit(cache=True, inline="always", _nrt=False)
def forget_factors(prob):
    prob.factors[0].c0 = np.nan


@njit(cache=True, inline="always", _nrt=False)
def take_step(prob, fraction):
    """X1 = base + fraction step on the free unknowns (step in band order)."""
    _copy_rows(prob.X1, prob.base)
    for j in range(prob.free_order.shape[0]):
        for a in range(3):
            prob.X1[prob.free_order[j], a] += fraction * prob.step[3 * j + a]


@njit(cache=True, inline="always", _nrt=False)
def set_base(prob):
    """The trial becomes Newton's base, with its branch state (the holds compare against it)."""
    _copy_rows(prob.base, prob.X1)
    for dst, src in prob.keeps:
        _copy_flat(dst, src)


@njit(cache=True, inline="always", _nrt=False)
def restore_base(prob):
    _copy_rows(prob.X1, prob.base)


@njit(cache=True, inline="always", _nrt=False)
def hold(prob, again):
    return kernels.hold_points(prob.pts, prob.base_full, prob.base_reduced, again)


@njit(cache=True, inline="always", _nrt=False)
def save_original(prob):
    _copy_flat(prob.original, prob.step)


@njit(cache=True, inline="always", _nrt=False)
def restore_original(prob):
    _copy_flat(prob.step, prob.original)
    return _largest(prob.original)


@njit(cache=True, inline="always", _nrt=False)
def begin(prob, h):
    """BDF2's coefficients for a step of h from the current state (backward Euler to start), its
    histories x_hist = c1 X + c2 Xp, v_hist = c1 V + c2 Vp, and the Taylor predictor X + h V + h^2/2 A
    with the prescribed ends in place (``prob.target``, set by ``place_ends``)."""
    X, V, A, Xp, Vp, guess = prob.X, prob.V, prob.A, prob.Xp, prob.Vp, prob.guess
    clock = prob.clock[0]
    h_before = clock.h_before
    start = h_before == 0.0
    if start:
        c0, c1, c2 = 1.0 / h, -1.0 / h, 0.0
    else:
        w = h / h_before
        c0, c1, c2 = (1 + 2 * w) / ((1 + w) * h), -(1 + w) / h, w * w / ((1 + w) * h)
    clock.c0 = c0
    for i in range(X.shape[0]):
        for a in range(3):
            prob.x_hist[i, a] = c1 * X[i, a] + c2 * (X[i, a] if start else Xp[i, a])
            prob.v_hist[i, a] = c1 * V[i, a] + c2 * (V[i, a] if start else Vp[i, a])
            guess[i, a] = X[i, a] + h * V[i, a] + 0.5 * h * h * A[i, a]
    for a in range(3):
        if prob.mesh.hi < X.shape[0] - 1:  # the fairlead end is prescribed
            guess[prob.fairlead_node, a] = prob.target[1, a]
        if prob.mesh.lo == 1:  # the anchor end
            guess[prob.anchor_node, a] = prob.target[0, a]


@njit(cache=True, inline="always", _nrt=False)
def restart(prob):
    _copy_rows(prob.X1, prob.guess)


@njit(cache=True, inline="always", _nrt=False)
def accept(prob, h):
    """The trial is the new state at t + h: BDF2's memory moves on."""
    _copy_rows(prob.prediction, prob.guess)
    _copy_rows(prob.Xp, prob.X)
    _copy_rows(prob.Vp, prob.V)
    _copy_rows(prob.X, prob.X1)
    _copy_rows(prob.V, prob.V1)
    _copy_rows(prob.A, prob.A1)
    for dst, src in prob.commits:
        _copy_flat(dst, src)
    clock = prob.clock[0]
    clock.t, clock.h_before, clock.last_h = clock.t + h, h, h


@njit(cache=True, inline="always", _nrt=False)
def auto_left(prob):
    return prob.factors[0].auto_left


@njit(cache=True, inline="always", _nrt=False)
def set_auto_left(prob, value):
    prob.factors[0].auto_left = value


@njit(cache=True, inline="always", _nrt=False)
def count(prob, counter, amount):
    prob.counters[counter] += amount
    return prob.counters[counter]


@njit(cache=True, inline="always", _nrt=False)
def time(prob):
    return prob.clock[0].t


@njit(cache=True, inline="always", _nrt=False)
def last_step(prob):
    return prob.clock[0].last_h


@njit(cache=True, inline="always", _nrt=False)
def record_residual(prob, value):
    prob.clock[0].residual = value


@njit(cache=True, inline="always", _nrt=False)
def record_stop(prob, h):
    prob.clock[0].stopped = h


@njit(cache=True, inline="always", _nrt=False)
def place_ends(prob, k, j, h):
    """The ends where step k's attempt ending at its j-th split (of FRACTIONS) puts them."""
    position = prob.ends[k] if j == FRACTIONS else prob.fractions[k, j - 1]
    for e in range(2):
        for a in range(3):
            prob.target[e, a] = position[e, a]
    return True


@njit(cache=True, inline="always", _nrt=False)
def reactions(prob, forces, k):
    for a in range(3):
        forces[k, 0, a] = -prob.rows[prob.fairlead_node, a]
        forces[k, 1, a] = -prob.rows[prob.anchor_node, a]


# -------------------------------------------------------------------- the compiled policy
#: the policy bound to these ops and compiled; ``policy.advance`` calls ``attempt`` through the ops
_BOUND = policy.bind(__import__(__name__, fromlist=["_"]), compile=njit(cache=True), name="bdf2")
attempt, STEPS = _BOUND["attempt"], _BOUND["steps"]
