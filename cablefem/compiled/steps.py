"""Time steps on the compiled kernel, many in one numba call: the policy's compiled ops.

``cablefem.dynamics.policy`` writes the Newton policy once (iterations, line search, branch corrections,
retries, halving and growth); this module binds it to compiled ops and compiles it (``STEPS``).
A step spent ~90 us per Newton iteration in Python around the compiled kernel (state updates,
norms, LU calls through scipy, the boundary motion), more than the kernel itself on the small
meshes of the coarse accuracy levels (verification/work_precision/README.md); here runs of
steps go without returning to Python, and the numbers are those of the Python ops to round-off
(``tests/test_march.py``, ``tests/test_march_alpha.py``).

The scheme is a run-time value of the ``Problem`` (``SCHEME``), one compiled policy for both:
variable-step BDF2 (desire2023 Sec. 2.1.2: backward Euler to start, then y' ~ c0 y_{n+1} + c1 y_n
+ c2 y_{n-1} on X and V) or generalised-alpha (``cablefem.dynamics.schemes.GeneralizedAlpha``: the loads
at the alpha-weighted point of the Newmark update, the tangent scaled by g_x = 1 - alpha_f, the
end forces evaluated at t_{n+1}). The banded LU is ``cablefem.compiled.banded`` (LAPACK's dgbtf2/dgbtrs
written out for numba: numba cannot cache a ctypes call to LAPACK). The seabed is projected in the
loop too (``cablefem.compiled.seabed``); where the walk cannot place a point, the loop stops and that
step goes on in Python, whose search finds it.
"""

from collections import namedtuple

import numpy as np
from numba import njit
from numba import uint64 as _index  # an unsigned index: no wrap-around fix-up (cablefem.banded)

from cablefem.compiled import kernels
from cablefem.dynamics import policy
from cablefem.compiled.banded import lu_factor, lu_solve
from cablefem.compiled.seabed import PLANE, project

#: a step of the compiled loop may be halved this many times (the fairlead's positions at the
#: 2**DEPTH - 1 points that split each step evenly are given); deeper, the Python ops go on
DEPTH = 3
FRACTIONS = 2 ** DEPTH

#: the schemes (``SCHEME.kind``): BDF2, generalised-alpha
BDF2, GENERALIZED_ALPHA = 0, 1
#: a run's scheme (one record): its kind and generalised-alpha's alpha_m, alpha_f, gamma, beta
SCHEME = np.dtype([("kind", "i8"), ("alpha_m", "f8"), ("alpha_f", "f8"), ("gamma", "f8"), ("beta", "f8")])
#: a run's clock (one record): t [s], the step before (0 at the start), the last step (0 if none), the
#: attempt that stopped the run, the last attempt's final relative residual, the attempt's factors
#: (v_x, a_x, g_x) (``cablefem.dynamics.integrator``; BDF2's (c0, c0^2, 1)) and its size h [s]
CLOCK = np.dtype([("t", "f8"), ("h_before", "f8"), ("last_h", "f8"), ("stopped", "f8"), ("residual", "f8"),
                  ("v_x", "f8"), ("a_x", "f8"), ("g_x", "f8"), ("h", "f8")])
#: what modified Newton's kept factors belong to (one record, kept between runs): the v_x of the
#: factors (NaN: none; a_x and g_x follow from it) and "auto"'s full-Newton attempts still to run
FACTORS = np.dtype([("v_x", "f8"), ("auto_left", "f8"), ("contraction", "f8")])
#: everything the compiled ops read and write (``Marcher.problem``): the kernel's records; the state
#: X, V, A, the step before's Xp, Vp, the last predictor and the rows M A + G (N, 3), updated in
#: place; the trial X1, the velocity and acceleration V1, A1 where the loads are evaluated (BDF2: at
#: X1; generalised-alpha: the alpha-weighted ones, at the positions X_alpha), the guess, BDF2's
#: histories and Newton's base (N, 3); the increment, Newton's step and its own step when corrected
#: (n,); the band and its LU (flat, LAPACK's column-major layout), pivots and multipliers; the
#: base's branch state; the byte views (dst, src) that keep the branch state as the base's and
#: commit the trial history; the clock (CLOCK), the factors' key (FACTORS) and the scheme (SCHEME);
#: counters (policy.COUNTERS); the anchor and the fairlead at the end of each step (m, 2, 3) and at
#: its splits (m, FRACTIONS - 1, 2, 3), and at the end of the attempt (2, 3) (an end that is not prescribed, ``Line.prescribed``, is an unknown like the others)
Problem = namedtuple("Problem", "settings mesh bed water pts work projector free_nodes free_order all_elements "
                                "end_elements anchor_node fairlead_node scale "
                                "X V A Xp Vp prediction rows X1 V1 A1 X_alpha guess x_hist v_hist base "
                                "rhs step original band lu ipiv multipliers base_full base_reduced keeps commits "
                                "clock factors scheme counters ends fractions target")


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


# ------------------------------------------------------------------------- the policy's ops
@njit(cache=True, inline="always", _nrt=False)
def _newmark(prob, i, a, h, g, b):
    """Generalised-alpha's V and A at t + h of row i, component a, from X1 (``GeneralizedAlpha.newmark``)."""
    X, V, A = prob.X, prob.V, prob.A
    acceleration = (prob.X1[i, a] - X[i, a] - h * V[i, a]) / (b * h * h) - (0.5 / b - 1.0) * A[i, a]
    return V[i, a] + h * ((1 - g) * A[i, a] + g * acceleration), acceleration


@njit(cache=True, _nrt=False)
def _point(prob):
    """V1 and A1 at the trial positions X1: BDF2's V = c0 X1 + x_hist, A = c0 V + v_hist; or
    generalised-alpha's alpha-weighted point of the Newmark update (``GeneralizedAlpha.point``),
    its positions into X_alpha."""
    X1, V1, A1, clock = prob.X1, prob.V1, prob.A1, prob.clock[0]
    if prob.scheme[0].kind == BDF2:
        c0, x_hist, v_hist = clock.v_x, prob.x_hist, prob.v_hist
        for i in range(X1.shape[0]):
            for a in range(3):
                V1[i, a] = c0 * X1[i, a] + x_hist[i, a]
                A1[i, a] = c0 * V1[i, a] + v_hist[i, a]
        return
    scheme, X, V, A, Xa = prob.scheme[0], prob.X, prob.V, prob.A, prob.X_alpha
    am, af = scheme.alpha_m, scheme.alpha_f
    for i in range(X1.shape[0]):
        for a in range(3):
            velocity, acceleration = _newmark(prob, i, a, clock.h, scheme.gamma, scheme.beta)
            Xa[i, a] = (1 - af) * X1[i, a] + af * X[i, a]
            V1[i, a] = (1 - af) * velocity + af * V[i, a]
            A1[i, a] = (1 - am) * acceleration + am * A[i, a]


@njit(cache=True, inline="always", _nrt=False)  # a call would copy the Problem's fields once more
def _assemble_at(prob, X, V, A, time, tangent, held, elements):
    """M A + G at (X, V, A) and ``time`` [s] into ``prob.rows`` over ``elements`` and, with
    ``tangent``, its banded tangent into ``prob.band`` (both zeroed first), the seabed projected first
    unless it is a plane. Returns the projection's status (0, or the points the walk did not place)."""
    if prob.projector.kind != PLANE:
        lost = project(prob.projector, X, prob.mesh, prob.bed, tangent)
        if lost != 0:
            return lost
    factors = (prob.clock[0].v_x, prob.clock[0].a_x)
    nb = prob.rhs.shape[0]
    ld = 2 * prob.mesh.kl + prob.mesh.ku + 1
    band2 = prob.band.reshape((nb, ld)).T  # the (ld, nb) column-major view the assembly writes
    prob.rows[:] = 0.0
    if tangent:
        band2.T[:] = 0.0  # the contiguous (nb, ld) view: a memset, not a strided walk
    kernels.assemble(prob.mesh, prob.bed, prob.water, prob.pts, prob.work, (X, V, A, time), factors, tangent, held,
                     prob.rows, band2, elements)
    if prob.mesh.nodes.shape[0]:
        kernels.assemble_nodes(prob.mesh, prob.water, prob.pts, prob.work, (X, V, A, time), factors, tangent,
                               prob.rows, band2)
    return 0


@njit(cache=True, _nrt=False)
def _assemble(prob, tangent, held, elements):
    """The step residual at the trial point over ``elements`` (``_assemble_at``), counted: at t + h
    (BDF2) or t + (1 - alpha_f) h (generalised-alpha's ``t_eval``)."""
    _point(prob)
    clock, scheme = prob.clock[0], prob.scheme[0]
    if scheme.kind == BDF2:
        X, time = prob.X1, clock.t + clock.h
    else:
        X, time = prob.X_alpha, clock.t + (1.0 - scheme.alpha_f) * clock.h
    lost = _assemble_at(prob, X, prob.V1, prob.A1, time, tangent, held, elements)
    if lost == 0:
        prob.counters[policy.NFEV] += 1
    return lost


@njit(cache=True, inline="always", _nrt=False)
def evaluate(prob, tangent, held):
    return _assemble(prob, tangent, held, prob.all_elements)


@njit(cache=True, inline="always", _nrt=False)
def finish(prob):
    """The rows at the converged point: BDF2's reactions need only the two end elements; a line whose
    loads keep history (its commits not empty) evaluates them all, so that the history committed is
    the converged point's, as on the Python ops (``python_ops.finish``). Generalised-alpha's
    reactions evaluate at the state (``reactions``): without history it evaluates nothing."""
    keeps = prob.commits[0][0].shape[0] > 0 or prob.commits[1][0].shape[0] > 0
    if not keeps and prob.scheme[0].kind != BDF2:
        return 0
    return _assemble(prob, policy.FLAG[0], policy.FLAG[0], prob.all_elements if keeps else prob.end_elements)


@njit(cache=True, inline="always", _nrt=False)
def norm(prob):
    total = 0.0
    for node in prob.free_nodes:
        i = _index(node)
        for a in range(3):
            total += prob.rows[i, a] * prob.rows[i, a]
    return np.sqrt(total) / prob.scale


@njit(cache=True, _nrt=False)
def increment(prob, refactor):
    """The Newton increment of the free unknowns for the rows into ``prob.rhs`` (band order): with
    ``refactor`` from fresh LU factors of g_x times the band (counted; ``factors.v_x`` the v_x they
    belong to, NaN when singular), else from those kept. Returns its largest entry (NaN: singular)."""
    mesh, key, counters, rhs, clock = prob.mesh, prob.factors[0], prob.counters, prob.rhs, prob.clock[0]
    if refactor:
        counters[policy.NJEV] += 1
        if clock.g_x == 1.0:
            _copy_flat(prob.lu, prob.band)
        else:  # the tangent of the unknowns X1: g_x (K + a_x M), as ``Integrator.factorize``
            for j in range(prob.lu.shape[0]):
                prob.lu[j] = clock.g_x * prob.band[j]
        key.v_x = np.nan
        if not lu_factor(prob.lu, prob.ipiv.shape[0], mesh.kl, mesh.ku, prob.ipiv, prob.multipliers):
            return np.nan
        counters[policy.NLU] += 1
        key.v_x = clock.v_x
    for j in range(prob.free_order.shape[0]):
        i = _index(prob.free_order[j])
        for a in range(3):
            rhs[3 * j + a] = -prob.rows[i, a]
    lu_solve(prob.lu, rhs.shape[0], mesh.kl, mesh.ku, prob.ipiv, rhs)
    size = _largest(rhs)
    _copy_flat(prob.step, rhs)
    return size


@njit(cache=True, inline="always", _nrt=False)
def factors_current(prob):
    return prob.factors[0].v_x == prob.clock[0].v_x


@njit(cache=True, inline="always", _nrt=False)
def forget_factors(prob):
    prob.factors[0].v_x = np.nan


@njit(cache=True, inline="always", _nrt=False)
def take_step(prob, fraction):
    """X1 = base + fraction step on the free unknowns (step in band order)."""
    _copy_rows(prob.X1, prob.base)
    for j in range(prob.free_order.shape[0]):
        i = _index(prob.free_order[j])
        for a in range(3):
            prob.X1[i, a] += fraction * prob.step[3 * j + a]


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
    """The scheme's factors for a step of h from the current state (BDF2: backward Euler to start,
    then its histories x_hist = c1 X + c2 Xp, v_hist = c1 V + c2 Vp; generalised-alpha:
    ``GeneralizedAlpha.begin``'s) and the Taylor predictor X + h V + h^2/2 A with the prescribed ends
    in place (``prob.target``, set by ``place_ends``)."""
    X, V, A, Xp, Vp, guess = prob.X, prob.V, prob.A, prob.Xp, prob.Vp, prob.guess
    clock, scheme = prob.clock[0], prob.scheme[0]
    clock.h = h
    if scheme.kind == BDF2:
        h_before = clock.h_before
        start = h_before == 0.0
        if start:
            c0, c1, c2 = 1.0 / h, -1.0 / h, 0.0
        else:
            w = h / h_before
            c0, c1, c2 = (1 + 2 * w) / ((1 + w) * h), -(1 + w) / h, w * w / ((1 + w) * h)
        clock.v_x, clock.a_x, clock.g_x = c0, c0 * c0, 1.0
        for i in range(X.shape[0]):
            for a in range(3):
                prob.x_hist[i, a] = c1 * X[i, a] + c2 * (X[i, a] if start else Xp[i, a])
                prob.v_hist[i, a] = c1 * V[i, a] + c2 * (V[i, a] if start else Vp[i, a])
                guess[i, a] = X[i, a] + h * V[i, a] + 0.5 * h * h * A[i, a]
    else:
        am, af, g, b = scheme.alpha_m, scheme.alpha_f, scheme.gamma, scheme.beta
        clock.v_x, clock.a_x, clock.g_x = g / (b * h), (1 - am) / ((1 - af) * b * h * h), 1 - af
        for i in range(X.shape[0]):
            for a in range(3):
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
    """The trial is the new state at t + h: BDF2's memory moves on; generalised-alpha's V and A are
    the Newmark update's."""
    _copy_rows(prob.prediction, prob.guess)
    scheme = prob.scheme[0]
    if scheme.kind == BDF2:
        _copy_rows(prob.Xp, prob.X)
        _copy_rows(prob.Vp, prob.V)
        _copy_rows(prob.X, prob.X1)
        _copy_rows(prob.V, prob.V1)
        _copy_rows(prob.A, prob.A1)
    else:
        for i in range(prob.X.shape[0]):
            for a in range(3):
                prob.V[i, a], prob.A[i, a] = _newmark(prob, i, a, h, scheme.gamma, scheme.beta)
                prob.X[i, a] = prob.X1[i, a]
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
def contraction(prob):
    return prob.factors[0].contraction


@njit(cache=True, inline="always", _nrt=False)
def set_contraction(prob, value):
    prob.factors[0].contraction = value


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
    """The line's forces on fairlead and anchor into forces[k]: minus the rows there (less a point's
    load riding on the end, ``kernels.subtract_node_loads``), which BDF2's
    ``finish`` left at the state; generalised-alpha's balance holds at t_{n+1-alpha_f}, so its rows are
    evaluated at the state over the end elements first, uncounted (as ``Integrator.reactions``).
    Returns the projection's status (0, or the points the walk did not place)."""
    if prob.scheme[0].kind != BDF2:
        lost = _assemble_at(prob, prob.X, prob.V, prob.A, prob.clock[0].t, policy.FLAG[0], policy.FLAG[0],
                            prob.end_elements)
        if lost != 0:
            return lost
    for a in range(3):
        forces[k, 0, a] = -prob.rows[prob.fairlead_node, a]
        forces[k, 1, a] = -prob.rows[prob.anchor_node, a]
    if prob.mesh.nodes.shape[0]:  # a point riding on an end: the line's own force leaves its load out
        state = (prob.X, prob.V, prob.A, prob.clock[0].t)
        kernels.subtract_node_loads(prob.mesh, prob.water, prob.pts, prob.work, state, prob.fairlead_node,
                                    forces[k, 0])
        kernels.subtract_node_loads(prob.mesh, prob.water, prob.pts, prob.work, state, prob.anchor_node,
                                    forces[k, 1])
    return 0


# -------------------------------------------------------------------- the compiled policy
#: the policy bound to these ops and compiled; ``policy.advance`` calls ``attempt`` through the ops
_BOUND = policy.bind(__import__(__name__, fromlist=["_"]), compile=njit(cache=True), name="march")
attempt, STEPS = _BOUND["attempt"], _BOUND["steps"]
