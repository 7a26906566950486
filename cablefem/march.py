"""BDF2 steps with their Newton iterations in one compiled loop (numba, LAPACK's banded LU).

``cablefem.fused`` compiles the residual and the banded tangent; a step still
spent ~90 us per Newton iteration in Python around them (the state update,
norms, the LU and solve calls through scipy, the boundary motion), more than
the compiled work itself on the small meshes that the coarse accuracy levels
use (verification/work_precision/README.md). This module runs whole steps,
and runs of steps, without returning to Python: the same variable-step BDF2
(``cablefem.dynamics.BDF2``, desire2023 Sec. 2.1.2: backward Euler to start,
then y' ~ c0 y_{n+1} + c1 y_n + c2 y_{n-1} on X and V) and the same Newton
(full or modified, with the residual line search) with the same convergence
tests as ``Integrator.newton``, line for line, and a step that fails halved
once in the loop as ``Integrator.step`` halves it (to its midpoint, then on),
so both paths give the same numbers to round-off (tests/test_march.py).
Before the halving moved into the loop, every failed step returned to Python
for its halves: ~30 % of a coarse snap-load run's time (P2 x 10, dt 0.16 s).

The banded LU is ``cablefem.banded`` (LAPACK's dgbtf2/dgbtrs written out for
numba).

The seabed is projected in the loop too: a plane by the fused kernel itself,
a ``DepthGrid`` by its compiled bilinear projection, a ``TriangulatedSurface``
by its compiled walk (``_vertex_normal_jit.project``), which starts where the
seabed's last call for these points ended and hands its last call back. When
the walk cannot place a point (it moved beyond its triangle's neighbours), the
loop stops and that step projects in Python, whose search finds it. Other
seabeds, and loads the fused kernel does not know, keep the per-step Python path.
"""

import numpy as np
from numba import njit

from .banded import lu_factor, lu_solve
from .branches import branches, keep_branches
from .fused import _assemble_loop
from .geometry import DepthGrid, TriangulatedSurface
from .geometry import _vertex_normal_jit as walk
from .geometry.grid import _project as _grid_project
from .geometry.triangulated import WALK_STEPS

#: status of a run of steps: all taken, Newton failed at step k, step k grows too fast, or the
#: compiled walk on a triangulated seabed did not place a point (Python projects that step)
DONE, FAILED, TOO_LONG, PROJECTION = 0, 1, 2, 3
#: seabeds the loop projects itself: a plane (in the fused kernel), a depth grid, a triangulated
#: surface (the compiled walk of ``_vertex_normal_jit``)
PLANE, GRID, TRIANGULATED = 0, 1, 2
#: what ``_newton`` returns
_CONVERGED, _DIVERGED, _LOST = 0, 1, 2
#: False and True as run-time values for the tangent flag: numba compiles a callee once more for
#: every literal argument, and the kernel's copies for literal True and False took ~30 s of the
#: first run's compilation
_FLAG = np.array([False, True])


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


@njit(cache=True)
def _project(projector, X1, dofs, phi, gap, normal, grad_gap, dnormal, derivatives):
    """Project the full quadrature points of X1 onto a grid or triangulated seabed into gap
    (nel, nq), normal and, with ``derivatives`` (a tangent needs them), grad_gap (nel, nq, 3) and
    dnormal (nel, nq, 3, 3), as ``FusedEvaluator.evaluate`` does through ``Seabed.project``; the
    walk's warm start moves on to this call. Returns the number of points the walk did not
    place (-1: moved too far)."""
    (kind, gx, gy, gz, rows, across, safe, size, typical, origin, start, unheld, start_h, triangle, sth,
     xyz, out) = projector
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
    if kind == GRID:
        _grid_project(xyz, gx, gy, gz, True, out)
    else:
        mode = walk.EVERYTHING if derivatives else walk.GAP_AND_DIRECTION
        lost = walk.project(xyz, origin, start, start_h, unheld, rows, across, safe, size, typical,
                            WALK_STEPS, True, mode, triangle, sth, out)
        if lost != 0:
            return lost
        for p in range(xyz.shape[1]):  # the next call starts here (loops: no temporary copies)
            for a in range(3):
                origin[a, p] = xyz[a, p]
            start[p] = triangle[p]
            start_h[p] = sth[2, p]
            unheld[p] = False
    for e in range(nel):
        for g in range(nq):
            p = e * nq + g
            gap[e, g] = out[0, p]
            for a in range(3):
                normal[e, g, a] = out[1 + a, p]
                if derivatives:
                    grad_gap[e, g, a] = out[7 + a, p]
                    for b in range(3):
                        dnormal[e, g, a, b] = out[10 + 3 * a + b, p]
    return 0


@njit(cache=True, _nrt=False)
def _point(X1, x_hist, v_hist, c0, V1, A1):
    """V and A of BDF2 at positions X1: V = c0 X1 + x_hist, A = c0 V + v_hist."""
    for i in range(X1.shape[0]):
        for a in range(3):
            V1[i, a] = c0 * X1[i, a] + x_hist[i, a]
            A1[i, a] = c0 * V1[i, a] + v_hist[i, a]


@njit(cache=True, _nrt=False)
def _evaluate(kernel, projector, X1, V1, A1, c0, tangent, rows, band2, scratch, elements, counters,
              held=False):
    """The step residual M A + G at X1, V1, A1 into ``rows`` over ``elements`` and, with
    ``tangent``, its banded tangent into ``band2`` (both zeroed first), the seabed projected first
    unless it is a plane (with its derivatives when a tangent is assembled); ``held``: the points
    scratch's hold and pull flags hold on their branches (see ``_newton``). Returns the
    projection's status (0, or the points the walk did not place)."""
    (dofs, position, phi, dphi, dx, rphi, rdphi, rdx, params, tension, mass, bed, plane, gap,
     normal, grad_gap, dnormal, kl, ku) = kernel[:19]
    if projector[0] != PLANE:
        lost = _project(projector, X1, dofs, phi, gap, normal, grad_gap, dnormal, tangent)
        if lost != 0:
            return lost
    vec, blk, Re, Ke, M, u = scratch[:6]
    hold, pull, slip, taut, contact = scratch[7], scratch[8], scratch[9], scratch[10], scratch[13]
    rows[:] = 0.0
    if tangent:
        band2.T[:] = 0.0  # the contiguous (nb, ld) view: a memset, not a strided walk
    _assemble_loop(X1, V1, A1, dofs, position, phi, dphi, dx, rphi, rdphi, rdx, params, tension, mass, bed,
                   plane, gap, normal, grad_gap, dnormal, c0, c0 * c0, tangent, rows, band2, kl, ku,
                   position.shape[0] - 1, vec, blk, Re, Ke, M, u, elements, hold, pull, held, slip,
                   taut, contact)  # position: a permutation
    counters[2] += 1
    return 0


@njit(cache=True, _nrt=False)
def _increment(refactor, lu, band, kl, ku, ipiv, multipliers, lu_key, c0, counters, rows, free_order, rhs):
    """The Newton increment of the free unknowns for residual ``rows`` into ``rhs`` (band order),
    with ``refactor`` from fresh LU factors of the tangent ``band`` (counted; lu_key[0] the c0
    they belong to, NaN when singular), else from those in ``lu``. Returns its largest entry:
    NaN if the tangent is singular, inf or NaN if the increment is not finite."""
    if refactor:
        counters[3] += 1
        _copy_flat(lu, band)
        lu_key[0] = np.nan
        if not lu_factor(lu, ipiv.shape[0], kl, ku, ipiv, multipliers):
            return np.nan
        counters[4] += 1
        lu_key[0] = c0
    for j in range(free_order.shape[0]):
        for a in range(3):
            rhs[3 * j + a] = -rows[free_order[j], a]
    lu_solve(lu, rhs.shape[0], kl, ku, ipiv, rhs)
    return _largest(rhs)


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


@njit(cache=True, _nrt=False)
def _add_step(X1, free_order, step, scale):
    """X1 += scale step on the free unknowns (step in band order)."""
    for j in range(free_order.shape[0]):
        for a in range(3):
            X1[free_order[j], a] += scale * step[3 * j + a]


@njit(cache=True, _nrt=False)
def _newton(kernel, projector, X1, V1, A1, x_hist, v_hist, c0, rows, band, lu, ipiv, lu_key, rhs, base,
            step, scratch, settings, counters, reuse, max_corrections):
    """Newton on the step residual M A + G = 0 from X1 (updated in place), as
    ``Integrator._newton``: full (a fresh tangent each iteration) or, with ``reuse``,
    modified (the LU factors ``lu``/``ipiv`` kept across iterations and steps while the step's
    c0 is ``lu_key[0]``, rebuilt when the iteration contracts slower than settings[6]).
    ``band`` (the size of ``lu``) takes a fresh tangent before it is factored into ``lu``; a step
    that does not reduce the residual norm is halved down to settings[7] (Armijo), from
    ``base`` (N, 3) along ``step`` (n,) (scratch).
    Returns (outcome, refreshed, the last relative residual): _CONVERGED, with V1, A1 and the end
    rows of ``rows`` at the solution, _DIVERGED, or _LOST when the seabed projection
    (``projector``, see ``bdf2_steps``) could not place a point; refreshed: kept factors were
    rebuilt for slow contraction."""
    kl, ku, free_nodes, free_order, all_elements, end_elements = kernel[17:23]
    tolerance, increment_tolerance, scale = settings[0], settings[1], settings[2]
    contraction = settings[6]
    nb = rhs.shape[0]
    ld = 2 * kl + ku + 1
    band2 = band.reshape((nb, ld)).T  # the (ld, nb) column-major view the assembly writes
    multipliers, original = scratch[6], scratch[15]  # original: Newton's own step, when corrected
    fresh = not reuse or lu_key[0] != c0
    previous, refreshed, norm = -1.0, False, np.inf  # none yet
    base_norm, damping, min_damping = -1.0, 1.0, settings[7]  # base_norm < 0: no step taken yet
    damped = False  # the step taken started from a point a damped step reached
    corrections = 0  # of the step from the base
    for _ in range(int(settings[3])):
        _point(X1, x_hist, v_hist, c0, V1, A1)
        # the tangent with the residual unless the last residual promises convergence (Newton) or
        # the step started from a damped point (its full step is mostly rejected)
        with_tangent = fresh and damping == 1.0 and not damped and (
            base_norm < 0.0 or base_norm > np.sqrt(tolerance))
        if _evaluate(kernel, projector, X1, V1, A1, c0, with_tangent, rows, band2, scratch, all_elements,
                     counters) != 0:
            return _LOST, refreshed, norm
        norm = 0.0
        for i in free_nodes:
            for a in range(3):
                norm += rows[i, a] * rows[i, a]
        norm = np.sqrt(norm) / scale
        if norm <= tolerance and previous >= 0.0:
            return _CONVERGED, refreshed, norm
        if base_norm >= 0.0 and damping > min_damping and not norm <= (1 - 1e-4 * damping) * base_norm:
            if damping == 1.0 and corrections < max_corrections and fresh and branches(
                    scratch, kernel[11][5], corrections > 0):  # Newton again from the base on the new branches
                if corrections == 0:
                    _copy_flat(original, step)
                corrections += 1
                counters[6] += 1
                _copy_rows(X1, base)
                _point(X1, x_hist, v_hist, c0, V1, A1)
                _evaluate(kernel, projector, X1, V1, A1, c0, _FLAG[1], rows, band2, scratch, all_elements,
                          counters, _FLAG[1])
                size = _increment(True, lu, band, kl, ku, ipiv, multipliers, lu_key, c0, counters, rows,
                                  free_order, rhs)
                if not np.isfinite(size):
                    break
                _copy_flat(step, rhs)
                _add_step(X1, free_order, rhs, 1.0)
                counters[1] += 1
                previous = size
                continue
            if damping == 1.0 and corrections > 0:  # no correction passed: the line search halves Newton's step
                _copy_flat(step, original)
                previous = _largest(original)
            damping *= 0.5
            _copy_rows(X1, base)
            _add_step(X1, free_order, step, damping)
            continue
        if not np.isfinite(norm):
            break
        if fresh and not with_tangent:  # the same point again, with the tangent (the walk places it)
            _evaluate(kernel, projector, X1, V1, A1, c0, _FLAG[1], rows, band2, scratch, all_elements, counters)
        size = _increment(fresh, lu, band, kl, ku, ipiv, multipliers, lu_key, c0, counters, rows, free_order,
                          rhs)
        if not np.isfinite(size):
            break
        _copy_rows(base, X1)
        _copy_flat(step, rhs)
        base_norm, damping, damped = norm, 1.0, damping < 1.0
        keep_branches(scratch)
        corrections = 0
        _add_step(X1, free_order, rhs, 1.0)
        counters[1] += 1
        rho = size / previous if previous > 0.0 else -1.0
        if (fresh and size <= increment_tolerance) or (
                0.0 <= rho < 1.0 and size * rho / (1 - rho) <= increment_tolerance):
            # the reactions need only the end rows: evaluate the two end elements
            _point(X1, x_hist, v_hist, c0, V1, A1)
            if _evaluate(kernel, projector, X1, V1, A1, c0, _FLAG[0], rows, band2, scratch, end_elements,
                         counters) != 0:
                return _LOST, refreshed, norm
            return _CONVERGED, refreshed, norm
        fresh = not reuse or rho > contraction
        refreshed = refreshed or (reuse and fresh)
        previous = size
    lu_key[0] = np.nan
    return _DIVERGED, refreshed, norm


@njit(cache=True, _nrt=False)
def _attempt(kernel, projector, state, history, h, position, anchor, settings, lu, ipiv, lu_key, work,
             counters):
    """One BDF2 step of size h from t = history[0] with the fairlead at ``position`` (3,) (see
    ``bdf2_steps`` for the arguments; ``work``: its scratch), its time arithmetic that of
    ``BDF2.attempt`` (t + h). On _CONVERGED the state and history move on to t + h and ``rows``
    holds the reactions; otherwise (_DIVERGED, _LOST) they are those
    before the step. A step whose modified Newton fails is retried once from its start with a
    fresh tangent ("auto": in full Newton)."""
    anchor_node, fairlead_node = kernel[23], kernel[24]  # the kernel tuple's last two
    X, V, A, Xp, Vp, prediction, rows = state
    rhs, step, band, base, X1, V1, A1, guess, x_hist, v_hist, scratch = work
    N = X.shape[0]
    t, h_before = history[0], history[1]
    start = h_before == 0.0
    if start:  # backward Euler to start (BDF2.coefficients)
        c0, c1, c2 = 1.0 / h, -1.0 / h, 0.0
    else:
        w = h / h_before
        c0, c1, c2 = (1 + 2 * w) / ((1 + w) * h), -(1 + w) / h, w * w / ((1 + w) * h)
    for i in range(N):
        for a in range(3):
            x_hist[i, a] = c1 * X[i, a] + c2 * (X[i, a] if start else Xp[i, a])
            v_hist[i, a] = c1 * V[i, a] + c2 * (V[i, a] if start else Vp[i, a])
            guess[i, a] = X[i, a] + h * V[i, a] + 0.5 * h * h * A[i, a]  # Integrator.predict
    for a in range(3):
        guess[fairlead_node, a] = position[a]
        guess[anchor_node, a] = anchor[a]
    # full or modified Newton; "auto" (settings[5] == 2): modified unless lu_key[1] attempts are
    # still to run in full Newton, as Integrator.newton chooses
    reuse = settings[5] == 1.0 or (settings[5] == 2.0 and lu_key[1] <= 0.0)
    _copy_rows(X1, guess)
    corrected = counters[6]
    outcome, trouble, last = _newton(kernel, projector, X1, V1, A1, x_hist, v_hist, c0, rows, band, lu, ipiv,
                                           lu_key, rhs, base, step, scratch, settings, counters, reuse, settings[11])
    if reuse and outcome == _DIVERGED:  # once more from the start: modified with a fresh tangent, or full
        trouble = True
        _copy_rows(X1, guess)
        outcome, _, last = _newton(kernel, projector, X1, V1, A1, x_hist, v_hist, c0, rows, band, lu, ipiv,
                                         lu_key, rhs, base, step, scratch, settings, counters, settings[5] == 1.0,
                                         settings[11])
    if outcome == _DIVERGED and counters[6] > corrected:  # corrected and failed: once more without
        _copy_rows(X1, guess)
        lu_key[0] = np.nan
        outcome, _, last = _newton(kernel, projector, X1, V1, A1, x_hist, v_hist, c0, rows, band, lu, ipiv,
                                         lu_key, rhs, base, step, scratch, settings, counters, settings[5] == 1.0, 0.0)
    history[4] = last
    if settings[5] == 2.0 and outcome != _LOST:
        if reuse and trouble:
            lu_key[1] = settings[9]
        elif not reuse:
            lu_key[1] -= 1.0
    if outcome != _CONVERGED:
        return outcome
    _copy_rows(prediction, guess)
    _copy_rows(Xp, X)
    _copy_rows(Vp, V)
    _copy_rows(X, X1)
    _copy_rows(V, V1)
    _copy_rows(A, A1)
    history[0], history[1], history[2] = t + h, h, h
    counters[0] += 1
    return _CONVERGED


#: a step of ``bdf2_steps`` may be halved this many times in its loop (the fairlead's positions at
#: the 2**DEPTH - 1 points that split each step evenly are given); deeper, ``Integrator.step`` halves
DEPTH = 3
FRACTIONS = 2 ** DEPTH


@njit(cache=True)
def bdf2_steps(kernel, projector, state, history, times, fairlead, fractions, anchor, settings, lu, ipiv,
               lu_key, forces, counters):
    """BDF2 steps to ``times`` (m,) in turn, the fairlead at ``fairlead`` (m, 3) and the anchor at
    ``anchor`` (3,). Returns (status, k): DONE with k = m, or FAILED / TOO_LONG / PROJECTION at
    step k, the state being that after the attempts of step k that went through; history[3] is
    then the size of the attempt that stopped.

    With ``fractions`` (m, FRACTIONS - 1, 3), the fairlead at t_(k-1) + j (t_k - t_(k-1)) /
    FRACTIONS for j = 1 .. FRACTIONS - 1, each step is taken as ``Integrator.step`` takes it, line
    for line: an attempt whose Newton fails is halved, no attempt is longer than settings[4]
    times the last step, none leaves less than settings[10] of itself to go. The loop stops for
    ``Integrator.step`` to go on when an attempt does not end on one of those points (TOO_LONG
    before it; FAILED when a halving would go deeper) or a halved step would be shorter than
    settings[8] (FAILED). Without (``fractions`` empty: ``BDF2.attempt``), step k is one attempt
    of t_k - t_(k-1), and a failure stops the loop (FAILED).

    kernel: the fused evaluator's arrays (``Marcher.kernel``); projector: (kind, grid x, y, z,
    the walk's tables and warm start, scratch) (``Marcher.projector``); state: (X, V, A, Xp, Vp,
    prediction, rows), each (N, 3), updated in place (Xp, Vp: the step before's; rows: M A + G
    with only the anchor and fairlead rows evaluated); history: [t, h of the step before (0 at
    the start), the last step (0 if none), the stopping attempt's size, the last attempt's final
    relative residual], updated; settings:
    [tolerance, increment tolerance, residual scale, max iterations, largest growth of a step
    over the last, Newton (0 full, 1 modified, 2 auto), contraction limit, smallest line-search
    damping, smallest step, auto's full-Newton attempts after trouble, the stretch of a step
    that lands on its end, corrections of a Newton step on new branches]; lu
    (n (2 kl + ku + 1),) (see ``cablefem.banded``), ipiv (n,),
    lu_key (2,): the c0 modified Newton's factors belong to (NaN: none) and auto's full-Newton
    attempts still to run, kept between calls; forces (m, 2, 3): the line's forces on fairlead
    and anchor after each step; counters: [steps, newton iterations, residual evaluations,
    tangents, LU factorisations, failed attempts, corrections], added to.
    """
    anchor_node, fairlead_node = kernel[23], kernel[24]
    X, rows = state[0], state[6]
    N = X.shape[0]
    nloc, nel, nq = kernel[2].shape
    nr = kernel[5].shape[2]
    # _attempt's scratch: rhs, step, band, base, X1, V1, A1, guess, x_hist, v_hist, and the
    # evaluation's and Newton's: vec, blk, Re, Ke, M, u (the kernel's), LU multipliers (6), the
    # branch holds of full and reduced points (7, 8), slip velocities (9), taut points (10), the
    # base's slip and taut points (11, 12), contact states and the base's (13, 14), Newton's own
    # step when corrected (15)
    work = (np.empty(ipiv.shape[0]), np.empty(ipiv.shape[0]), np.zeros(lu.shape[0]), np.empty((N, 3)),
            np.empty((N, 3)), np.empty((N, 3)), np.empty((N, 3)), np.empty((N, 3)), np.empty((N, 3)),
            np.empty((N, 3)),
            (np.zeros((7, 3)), np.zeros((4, 3, 3)), np.zeros((nloc, 3)), np.zeros((nloc, 3, nloc, 3)),
             np.zeros((12, 3, 3)), np.zeros((12, 3)), np.empty(kernel[17] + 1),
             np.zeros((nel, nq), dtype=np.int8), np.zeros((nel, nr), dtype=np.bool_), np.zeros((nel, nq, 3)),
             np.zeros((nel, nr), dtype=np.bool_), np.zeros((nel, nq, 3)), np.zeros((nel, nr), dtype=np.bool_),
             np.zeros((nel, nq), dtype=np.int8), np.zeros((nel, nq), dtype=np.int8), np.empty(ipiv.shape[0])))
    stepping = fractions.shape[0] > 0
    growth, stretch, min_step = settings[4], settings[10], settings[8]
    parts = fractions.shape[1] + 1
    for k in range(times.shape[0]):
        target = times[k] - history[0]
        if not stepping:
            history[3] = target
            outcome = _attempt(kernel, projector, state, history, target, fairlead[k], anchor, settings, lu,
                               ipiv, lu_key, work, counters)
            if outcome == _DIVERGED:
                return FAILED, k
        else:  # Integrator.step
            done, h, outcome, halved = 0.0, target, _CONVERGED, False
            while target - done > 1e-9 * target:
                remaining = target - done
                h = min(h, remaining)
                if history[2] > 0.0:
                    h = min(h, growth * history[2])
                if remaining - h <= stretch * h:
                    h = remaining
                history[3] = h
                share = (done + h) / target * parts  # where the attempt ends, in 1/parts of the step
                j = int(np.round(share))
                if abs(share - j) > 1e-6 or j < 1:  # Integrator.step goes on from here
                    if halved:
                        history[3] = 2.0 * h  # the attempt that failed
                        return FAILED, k
                    return TOO_LONG, k
                position = fairlead[k] if j == parts else fractions[k, j - 1]
                outcome = _attempt(kernel, projector, state, history, h, position, anchor, settings, lu, ipiv,
                                   lu_key, work, counters)
                if outcome == _LOST:
                    break
                if outcome == _DIVERGED:
                    counters[5] += 1
                    if 0.5 * h < min_step:
                        return FAILED, k
                    h *= 0.5
                    halved = True
                    continue
                done += h
                h, halved = target, False
        if outcome == _LOST:
            return PROJECTION, k
        for a in range(3):
            forces[k, 0, a] = -rows[fairlead_node, a]
            forces[k, 1, a] = -rows[anchor_node, a]
    return DONE, times.shape[0]


class Marcher:
    """Runs a ``BDF2`` integrator's steps through ``bdf2_steps``; built by ``for_integrator``."""

    def __init__(self, integ, kind):
        fem, ev = integ.fem, integ.fused
        self.seabed, self.kind = integ.system.seabed, kind
        nel, nq = ev.full.dx.shape
        if kind == PLANE:  # the kernel computes the gap itself
            gap, normal, grad_gap, dnormal = ev.unused
        else:  # written by ``_project`` each evaluation
            gap, normal, grad_gap, dnormal = (np.zeros((nel, nq)), np.zeros((nel, nq, 3)), np.zeros((nel, nq, 3)),
                                              np.zeros((nel, nq, 3, 3)))
        ends = np.unique(np.flatnonzero(np.isin(ev.dofs, (fem.anchor_dof, fem.fairlead_dof)).any(axis=1)))
        self.kernel = (ev.dofs, ev.position, ev.full.phi, ev.full.dphi, ev.full.dx, ev.reduced.phi,
                       ev.reduced.dphi, ev.reduced.dx, ev.params, ev.tension, ev.mass, ev.bed, ev.plane,
                       gap, normal, grad_gap, dnormal, ev.kl, ev.ku, fem.free_dofs.astype(np.int64),
                       ev.free_order.astype(np.int64), np.arange(fem.n_elements, dtype=np.int64),
                       ends.astype(np.int64), int(fem.anchor_dof), int(fem.fairlead_dof))
        self.points = nel * nq
        self.rule = fem.full  # positions at its quadrature points: the walk's start
        self.anchor = np.asarray(integ.system.line.anchor, dtype=float)
        self.settings = np.array([integ.tolerance, integ.increment_tolerance, integ.scale,
                                  integ.max_iterations, integ.MAX_GROWTH,
                                  2.0 if integ.switching else float(integ.reuse_jacobian),
                                  integ.CONTRACTION, integ.MIN_DAMPING, integ.min_dt, integ.AUTO_FULL_STEPS,
                                  integ.STRETCH, integ.MAX_CORRECTIONS])
        self.lu = np.zeros(ev.n * (2 * ev.kl + ev.ku + 1))  # LAPACK's column-major band, flat
        self.ipiv = np.zeros(ev.n, dtype=np.int64)
        self.lu_key = np.full(2, np.nan)

    @classmethod
    def for_integrator(cls, integ):
        """A marcher for ``integ`` when it evaluates with the fused kernel on a plane, a depth grid
        or a triangulated surface with compiled projections; None otherwise (the per-step Python
        path applies)."""
        ev, seabed = integ.fused, integ.system.seabed
        if ev is None:
            return None
        if ev.plane.size:
            return cls(integ, PLANE)
        if isinstance(seabed, DepthGrid) and seabed.compiled:
            return cls(integ, GRID)
        if isinstance(seabed, TriangulatedSurface) and seabed.compiled:
            return cls(integ, TRIANGULATED)
        return None

    def projector(self, X):
        """The projector tuple of ``bdf2_steps`` for state X (N, 3): the seabed's arrays, the
        walk's warm start from the seabed's last call at these points, and scratch."""
        n = self.points
        zero1, zero2 = np.zeros(1), np.zeros((1, 1))
        grid = (self.seabed.x, self.seabed.y, self.seabed.z) if self.kind == GRID else (zero1, zero1, zero2)
        if self.kind == TRIANGULATED:
            walker = self.seabed.walk_start(self.rule.interpolate(X)[0])
        else:  # unused, typed as the walk's own
            walker = (zero2, np.zeros((1, 3), dtype=np.int64), zero1, zero1, 0.0, np.zeros((3, n)),
                      np.zeros(n, dtype=np.int64), np.zeros(n, dtype=bool), np.zeros(n))
        return ((self.kind,) + grid + walker
                + (np.zeros(n, dtype=np.int64), np.zeros((3, n)), np.zeros((3, n)), np.zeros((walk.OUTPUTS, n))))

    def run(self, integ, times, fairlead, fractions=None):
        """Steps of ``integ`` to ``times`` (m,) with the fairlead at ``fairlead`` (m, 3). With
        ``fractions`` (m, FRACTIONS - 1, 3), the fairlead at the points that split each step
        evenly (``BDF2.march``), each step is taken as ``Integrator.step`` takes it (halved on
        failure, grown back) and the steps and failed attempts are counted into ``integ`` here;
        without (``BDF2.attempt``), each step is one attempt and ``Integrator.step`` halves and
        counts. Returns (status, k, forces (m, 2, 3), the size of the attempt that stopped the
        loop)."""
        h_before, Xp, Vp = (0.0, integ.X, integ.V) if integ.previous is None else integ.previous
        state = tuple(np.array(x, dtype=float) for x in (integ.X, integ.V, integ.A, Xp, Vp, integ.X,
                                                         np.zeros_like(integ.X)))
        history = np.array([integ.t, h_before, integ.last_h or 0.0, 0.0, np.nan])
        forces = np.empty((len(times), 2, 3))
        counters = np.zeros(7, dtype=np.int64)
        projector = self.projector(integ.X)
        splits = (np.zeros((0, FRACTIONS - 1, 3)) if fractions is None
                  else np.ascontiguousarray(fractions, dtype=float))
        self.lu_key[1] = integ.full_steps_left  # "auto" Newton's state, shared with the Python path
        status, k = bdf2_steps(self.kernel, projector, state, history, np.asarray(times, dtype=float),
                               np.ascontiguousarray(fairlead, dtype=float), splits, self.anchor, self.settings,
                               self.lu, self.ipiv, self.lu_key, forces, counters)
        integ.full_steps_left = int(self.lu_key[1])
        if self.kind == TRIANGULATED and counters[2]:  # the walk's last call: the next one starts there
            origin, triangle, h = projector[9], projector[10], projector[12]
            self.seabed.walk_end(origin, triangle, h)
        integ.newton_iterations += int(counters[1])
        integ.nfev += int(counters[2])
        integ.njev += int(counters[3])
        integ.nlu += int(counters[4])
        if fractions is not None:
            integ.steps += int(counters[0])
            integ.rejected += int(counters[5])
        integ.corrections += int(counters[6])
        if counters[0] > 0:
            X, V, A, Xp, Vp, prediction, rows = state
            integ.X, integ.V, integ.A, integ.prediction, integ.residual_rows = X, V, A, prediction, rows
            integ.previous = (float(history[1]), Xp, Vp)
            integ.t, integ.last_h = float(history[0]), float(history[2])
        if status != DONE:
            integ.last_residual = float(history[4])
        return status, k, forces, float(history[3])
