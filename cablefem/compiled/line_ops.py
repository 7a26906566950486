"""The Newton policy's compiled ops on one string (a line alone, or a string of a group), ``p`` its
``cablefem.compiled.steps.Problem``: its evaluation (``_assemble``: the scheme's evaluation point, then
the seabed's projection, the element loop and the node loads, called by address), its Newton increment
on the banded LU (``cablefem.compiled.banded``), the trial's moves, the scheme's steps, its local error
and its forces on the ends. ``cablefem.compiled.steps`` binds them with a scheme's functions to the
policy (``steps.bound``, which copies those that read the scheme); ``cablefem.compiled.group_ops``
loops them over a group's strings.
"""

from collections import namedtuple

import numpy as np
from numba import njit, types
from numba import uint64 as _index  # an unsigned index: no wrap-around fix-up (cablefem.compiled.banded)

from cablefem.compiled import calls, kernels
from cablefem.compiled.banded import lu_factor, lu_solve
from cablefem.compiled.seabed import PLANE, project
from cablefem.dynamics import policy

#: the slots of a ``Problem``'s ``calls`` that the policy's layers take (``steps.CALLS``); ``THROUGH``'s follow
LAYER_SLOTS = 3


def _state(p):
    """The type of a state (X, V, A, t) of string p (a ``Problem``'s numba type)."""
    rows = p.types[p.fields.index("X")]
    return types.Tuple((rows, rows, rows, types.float64))


def _field(p, name):
    return p.types[p.fields.index(name)]


_BAND = types.Array(types.float64, 2, "F")  # the band as the assembly writes it (``_assemble_at``)
_FACTORS = types.UniTuple(types.float64, 3)


def _assemble_types(p):
    """What ``kernels.assemble`` takes from string p (``_assemble_at``)."""
    return (_field(p, "mesh"), _field(p, "bed"), _field(p, "water"), _field(p, "pts"), _field(p, "work"), _state(p),
            _FACTORS, types.boolean, types.boolean, _field(p, "X"), _BAND, _field(p, "all_elements"))


def _nodes_types(p):
    """What ``kernels.assemble_nodes`` takes from string p (``_assemble_at``)."""
    return (_field(p, "mesh"), _field(p, "water"), _field(p, "pts"), _field(p, "work"), _state(p), _FACTORS,
            types.boolean, _field(p, "X"), _BAND)


def _subtract_types(p):
    """What ``kernels.subtract_node_loads`` takes from string p (``_forces``)."""
    return (_field(p, "mesh"), _field(p, "water"), _field(p, "pts"), _field(p, "work"), _state(p), types.int64,
            types.float64[::1])


def _project_types(p):
    """What ``seabed.project`` takes from string p (``_assemble_at``)."""
    return _field(p, "projector"), _field(p, "X"), _field(p, "mesh"), _field(p, "bed"), types.boolean


def _with_nodes(p):
    return p.mesh.nodes.shape[0] > 0


def _on_seabed(p):
    return p.projector.kind != PLANE


#: a function a string's ``Problem`` calls by address with the arguments it names (``calls.through``): its
#: slot in ``calls``, the function, the types of its arguments (of the Problem's type), what it returns
#: (declared: checked where its address is written, ``calls.address``) and whether a string needs it
#: (None: every one; its address is written, and the function compiled, only where one of the group's does)
Through = namedtuple("Through", "slot function types_of returns needed")
THROUGH = {"assemble": Through(LAYER_SLOTS, kernels.assemble, _assemble_types, types.none, None),
           "assemble_nodes": Through(LAYER_SLOTS + 1, kernels.assemble_nodes, _nodes_types, types.none, _with_nodes),
           "subtract_node_loads": Through(LAYER_SLOTS + 2, kernels.subtract_node_loads, _subtract_types, types.none,
                                          _with_nodes),
           "project": Through(LAYER_SLOTS + 3, project, _project_types, types.int64, _on_seabed)}
_assemble_kernel, _nodes_kernel, _subtract_kernel, _project_kernel = (
    calls.through(t.function, t.types_of, t.slot, t.returns) for t in THROUGH.values())


#: the scheme's arithmetic, bound per scheme by ``bound`` (``cablefem.dynamics.scheme``)
scheme_begin = scheme_point = scheme_accept = scheme_error = None
ROWS_AT_STATE = True
_balance_lag = njit(cache=True, inline="always", _nrt=False)(policy.balance_lag)


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


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _solve_small(A, b, n):
    """Solve A x = b (n x n, in place: x into b) by Gaussian elimination with partial pivoting;
    False if A is singular."""
    for c in range(n):
        p = c
        for r in range(c + 1, n):
            if abs(A[r, c]) > abs(A[p, c]):
                p = r
        if A[p, c] == 0.0:
            return False
        if p != c:
            for j in range(n):
                A[c, j], A[p, j] = A[p, j], A[c, j]
            b[c], b[p] = b[p], b[c]
        for r in range(c + 1, n):
            f = A[r, c] / A[c, c]
            for j in range(c, n):
                A[r, j] -= f * A[c, j]
            b[r] -= f * b[c]
    for c in range(n - 1, -1, -1):
        total = b[c]
        for j in range(c + 1, n):
            total -= A[c, j] * b[j]
        b[c] = total / A[c, c]
    return True


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _inverse(M, out, n, work, column):
    """out = M^-1 (n x n) column by column (work, column: scratch); False if singular."""
    for j in range(n):
        for r in range(n):
            for c in range(n):
                work[r, c] = M[r, c]
            column[r] = 1.0 if r == j else 0.0
        if not _solve_small(work, column, n):
            return False
        for r in range(n):
            out[r, j] = column[r]
    return True


# ---------------------------------------------------------------------------- one string
@njit(cache=True, inline="always", _nrt=False)  # a call would copy the Problem's fields once more
def _assemble_at(p, X, V, A, time, tangent, held, elements, rows):
    """M A + G at (X, V, A) and ``time`` [s] into ``rows`` over ``elements`` (and the node loads) and,
    with ``tangent``, its banded tangent into ``p.band`` (both zeroed first), the seabed projected
    first unless it is a plane. Returns the projection's status (0, or the points the walk did not
    place)."""
    if p.projector.kind != PLANE:
        lost = _project_kernel(p, (p.projector, X, p.mesh, p.bed, tangent))
        if lost != 0:
            return lost
    factors = (p.clock[0].v_x, p.clock[0].a_x, p.clock[0].h)  # h: loads whose history evolves in time
    nb = p.rhs.shape[0]
    ld = 2 * p.mesh.kl + p.mesh.ku + 1
    band2 = p.band.reshape((nb, ld)).T  # the (ld, nb) column-major view the assembly writes
    rows[:] = 0.0
    if tangent:
        band2.T[:] = 0.0  # the contiguous (nb, ld) view: a memset, not a strided walk
    _assemble_kernel(p, (p.mesh, p.bed, p.water, p.pts, p.work, (X, V, A, time), factors, tangent, held, rows, band2,
                         elements))
    if p.mesh.nodes.shape[0]:
        _nodes_kernel(p, (p.mesh, p.water, p.pts, p.work, (X, V, A, time), factors, tangent, rows, band2))
    return 0


@njit(cache=True, _nrt=False, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _assemble(p, tangent, held, elements):
    """The step residual of string p at its trial point over ``elements`` (``_assemble_at``), counted."""
    scheme_point(p.scheme, p.clock, p.X, p.V, p.A, p.memory, p.X1, p.Xe, p.Ve, p.Ae)
    lost = _assemble_at(p, p.Xe, p.Ve, p.Ae, p.clock[0].t_eval, tangent, held, elements, p.rows)
    if lost == 0:
        p.counters[policy.NFEV] += 1
    return lost


@njit(cache=True, _nrt=False, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _increment(p, refactor):
    """String p's Newton increment for its rows into ``p.step`` (band order): with ``refactor`` from
    fresh LU factors of g_x times the band (counted; ``factors.v_x`` the v_x they belong to, NaN when
    singular), else from those kept. Returns its largest entry (NaN: singular)."""
    mesh, key, counters, rhs, clock = p.mesh, p.factors[0], p.counters, p.rhs, p.clock[0]
    if refactor:
        counters[policy.NJEV] += 1
        if clock.g_x == 1.0:
            _copy_flat(p.lu, p.band)
        else:  # the tangent of the unknowns X1: g_x (K + a_x M), as ``Evaluator.factorize``
            for j in range(p.lu.shape[0]):
                p.lu[j] = clock.g_x * p.band[j]
        key.v_x = np.nan
        if not lu_factor(p.lu, p.ipiv.shape[0], mesh.kl, mesh.ku, p.ipiv, p.multipliers):
            return np.nan
        counters[policy.NLU] += 1
        key.v_x = clock.v_x
    for j in range(p.free_order.shape[0]):
        i = _index(p.free_order[j])
        for a in range(3):
            rhs[3 * j + a] = -p.rows[i, a]
    lu_solve(p.lu, rhs.shape[0], mesh.kl, mesh.ku, p.ipiv, rhs)
    size = _largest(rhs)
    _copy_flat(p.step, rhs)
    return size


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _columns(p, g):
    """The columns Z of string p's K^-1 at its junction ends and their end stiffness S = Z_E^-1, from
    its kept LU; False if singular."""
    ends, Z, scratch = p.junction_ends, p.Z, p.original  # ``original`` is free before the corrections
    m = np.int64(0)  # not literal: numba would compile ``_inverse`` once more for a literal 0
    for s in range(2):
        if ends[s, 0] >= 0:
            m += 3
    ZE, j = g.ZE, 0
    for s in range(2):
        row = ends[s, 0]
        if row < 0:
            continue
        for c in range(3):
            scratch[:] = 0.0
            scratch[3 * row + c] = 1.0
            lu_solve(p.lu, scratch.shape[0], p.mesh.kl, p.mesh.ku, p.ipiv, scratch)
            for i in range(scratch.shape[0]):
                Z[i, j] = scratch[i]
            i = 0
            for t in range(2):  # column j of ZE: Z's rows at the junction ends
                if ends[t, 0] >= 0:
                    for d in range(3):
                        ZE[i, j] = scratch[3 * ends[t, 0] + d]
                        i += 1
            j += 1
    return _inverse(ZE, p.S, m, g.work, g.column)


@njit(cache=True, inline="always", _nrt=False)
def _joined(p):
    """Whether string p ends at a junction."""
    return p.junction_ends[0, 0] >= 0 or p.junction_ends[1, 0] >= 0


# ------------------------------------------------------------------ the policy's ops on one string
# (a line alone: ``prob`` is its ``Problem``; inlined into the compiled policy)
@njit(cache=True, inline="always", _nrt=False)
def evaluate(p, tangent, held):
    return _assemble(p, tangent, held, p.all_elements)


@njit(cache=True, inline="always", _nrt=False)
def finish(p):
    """The rows at the converged point: BDF2's reactions need only the two end elements; a line whose
    loads keep history (its commits not empty) evaluates them all, so that the history committed is
    the converged point's, as on the Python ops (``python_ops.finish``). A scheme whose reactions
    evaluate at the state (``reactions``; ``Scheme.rows_at_state`` False) evaluates nothing here
    without history."""
    keeps = p.commits[0][0].shape[0] > 0 or p.commits[1][0].shape[0] > 0
    if not keeps and not ROWS_AT_STATE:
        return 0
    return _assemble(p, policy.FLAG[0], policy.FLAG[0], p.all_elements if keeps else p.end_elements)


@njit(cache=True, inline="always", _nrt=False)
def _sum_squares(p):
    """The sum of squares of the string's rows at its free nodes that are no junction end."""
    total = 0.0
    for node in p.interior:
        i = _index(node)
        for a in range(3):
            total += p.rows[i, a] * p.rows[i, a]
    return total


@njit(cache=True, inline="always", _nrt=False)
def norm(p):
    return np.sqrt(_sum_squares(p)) / p.scale


@njit(cache=True, inline="always", _nrt=False)
def increment(p, refactor):
    return _increment(p, refactor)


@njit(cache=True, inline="always", _nrt=False)
def factors_current(p):
    return p.factors[0].v_x == p.clock[0].v_x


@njit(cache=True, inline="always", _nrt=False)
def forget_factors(p):
    p.factors[0].v_x = np.nan


@njit(cache=True, inline="always", _nrt=False)
def take_step(p, fraction):
    """X1 = base + fraction step on the free unknowns (step in band order)."""
    _copy_rows(p.X1, p.base)
    for j in range(p.free_order.shape[0]):
        i = _index(p.free_order[j])
        for a in range(3):
            p.X1[i, a] += fraction * p.step[3 * j + a]


@njit(cache=True, inline="always", _nrt=False)
def set_base(p):
    """The trial becomes Newton's base, with its branch state (the holds compare against it)."""
    _copy_rows(p.base, p.X1)
    for dst, src in p.keeps:
        _copy_flat(dst, src)


@njit(cache=True, inline="always", _nrt=False)
def restore_base(p):
    _copy_rows(p.X1, p.base)


@njit(cache=True, inline="always", _nrt=False)
def hold(p, again):
    return kernels.hold_points(p.pts, p.base_full, p.base_reduced, again)


@njit(cache=True, inline="always", _nrt=False)
def save_original(p):
    _copy_flat(p.original, p.step)


@njit(cache=True, inline="always", _nrt=False)
def restore_original(p):
    _copy_flat(p.step, p.original)
    return _largest(p.original)


@njit(cache=True, inline="always", _nrt=False)
def begin(p, h):
    """The step of h from the state (the scheme's ``begin``) with the prescribed ends in place
    (``p.target``, set by ``place_ends``)."""
    scheme_begin(p.scheme, p.clock, p.X, p.V, p.A, p.memory, p.guess, h)
    for a in range(3):
        if p.mesh.hi < p.X.shape[0] - 1:  # the fairlead end is prescribed
            p.guess[p.fairlead_node, a] = p.target[1, a]
        if p.mesh.lo == 1:  # the anchor end
            p.guess[p.anchor_node, a] = p.target[0, a]


@njit(cache=True, inline="always", _nrt=False)
def restart(p):
    _copy_rows(p.X1, p.guess)


@njit(cache=True, inline="always", _nrt=False)
def accept(p, h):
    """The trial is the new state at t + h (the scheme's ``accept``), its history committed."""
    _copy_rows(p.prediction, p.guess)
    scheme_accept(p.scheme, p.clock, p.X, p.V, p.A, p.memory, p.X1)
    for dst, src in p.commits:
        _copy_flat(dst, src)
    clock = p.clock[0]
    clock.t, clock.h_before, clock.last_h = clock.t + h, h, h
    if ROWS_AT_STATE:  # the balance's end rows, and the reactions' part carrying them on to t
        lag = _balance_lag(clock.t, clock.t_eval, clock.t_balance)
        for k in range(2):
            node = p.fairlead_node if k == 0 else p.anchor_node
            for a in range(3):
                row = p.rows[node, a]
                p.balance_rows[1, k, a] = lag * (row - p.balance_rows[0, k, a]) if lag != 0.0 else 0.0
                p.balance_rows[0, k, a] = row
        clock.t_balance = clock.t_eval


@njit(cache=True, inline="always", _nrt=False)
def auto_left(p):
    return p.factors[0].auto_left


@njit(cache=True, inline="always", _nrt=False)
def set_auto_left(p, value):
    p.factors[0].auto_left = value


@njit(cache=True, inline="always", _nrt=False)
def contraction(p):
    return p.factors[0].contraction


@njit(cache=True, inline="always", _nrt=False)
def set_contraction(p, value):
    p.factors[0].contraction = value


@njit(cache=True, inline="always", _nrt=False)
def count(p, counter, amount):
    p.counters[counter] += amount
    return p.counters[counter]


@njit(cache=True, inline="always", _nrt=False)
def time(p):
    return p.clock[0].t


@njit(cache=True, inline="always", _nrt=False)
def last_step(p):
    return p.clock[0].last_h


@njit(cache=True, inline="always", _nrt=False)
def record_residual(p, value):
    p.clock[0].residual = value


@njit(cache=True, inline="always", _nrt=False)
def record_stop(p, h):
    p.clock[0].stopped = h


@njit(cache=True, inline="always", _nrt=False)
def place_ends(p, k, j, h):
    """The ends where step k's attempt ending at its j-th split puts them (the last split: the step's
    end; ``p.fractions`` holds the others)."""
    position = p.ends[k] if j == p.fractions.shape[1] + 1 else p.fractions[k, j - 1]
    for e in range(2):
        for a in range(3):
            p.target[e, a] = position[e, a]
    return True


@njit(cache=True, _nrt=False, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _tension_error(p, X1, low):
    """The local error of positions X1 against a solution of lower order ``low`` as a fraction of the
    line's largest tension: EA |d(X1 - low)/ds| at the axial (reduced) points, over the largest
    EA max(|dX1/ds| - 1, 0), or over the largest at the start where that is larger
    (``Integrator.tension_error``)."""
    mesh = p.mesh
    largest, tension, stiffest = 0.0, 0.0, 0.0
    for e in range(mesh.dofs.shape[0]):
        EA = p.EA[e]
        stiffest = max(stiffest, EA)
        for g in range(mesh.rdphi.shape[2]):
            d0 = d1 = d2 = r0 = r1 = r2 = 0.0
            for l in range(mesh.dofs.shape[1]):
                i, w = _index(mesh.dofs[e, l]), mesh.rdphi[l, e, g]
                d0 += w * (X1[i, 0] - low[i, 0])
                d1 += w * (X1[i, 1] - low[i, 1])
                d2 += w * (X1[i, 2] - low[i, 2])
                r0 += w * X1[i, 0]
                r1 += w * X1[i, 1]
                r2 += w * X1[i, 2]
            stretch = np.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
            if stretch > 0.0:  # the strain's part: the tangent's component
                largest = max(largest, EA * abs(r0 * d0 + r1 * d1 + r2 * d2) / stretch)
            tension = max(tension, EA * max(stretch - 1.0, 0.0))
    return largest / max(tension, p.clock[0].tension_scale, 1e-12 * stiffest)


@njit(cache=True, inline="always", _nrt=False)
def error(p):
    """The converged trial's local tension error (the scheme's ``error``, ``_tension_error``); -1 where
    the scheme has none (``p.Xe``, free between evaluations, holds the solution of lower order)."""
    if not scheme_error(p.scheme, p.clock, p.X, p.V, p.A, p.memory, p.X1, p.guess, p.Xe):
        return -1.0
    return _tension_error(p, p.X1, p.Xe)


@njit(cache=True, inline="always", _nrt=False)
def last_error(p):
    return p.clock[0].error


@njit(cache=True, inline="always", _nrt=False)
def record_error(p, value):
    p.clock[0].error = value


@njit(cache=True, inline="always", _nrt=False)
def proposal(p):
    return p.clock[0].proposal


@njit(cache=True, inline="always", _nrt=False)
def set_proposal(p, value):
    p.clock[0].proposal = value


@njit(cache=True, inline="always", _nrt=False)
def _forces(p, out):
    """The string's forces on its fairlead and anchor into ``out`` (2, 3): minus its rows there (less a
    point's load riding on the end, a free end's mass or a junction's clump:
    ``kernels.subtract_node_loads``), which ``finish`` left at the converged point (BDF2: the state;
    generalised-alpha: its balance at t_{n+1-alpha_f}); a scheme whose reactions evaluate at the
    state (``Scheme.rows_at_state`` False) evaluates its rows there over the end elements first,
    uncounted (as ``Integrator.reactions``). Returns the projection's status (0, or the points the
    walk did not place)."""
    if not ROWS_AT_STATE:
        lost = _assemble_at(p, p.X, p.V, p.A, p.clock[0].t, policy.FLAG[0], policy.FLAG[0], p.end_elements,
                            p.rows)
        if lost != 0:
            return lost
    lagged = ROWS_AT_STATE and p.clock[0].t_balance == p.clock[0].t_eval  # the rows are the last balance
    for a in range(3):
        out[0, a] = -p.rows[p.fairlead_node, a] - (p.balance_rows[1, 0, a] if lagged else 0.0)
        out[1, a] = -p.rows[p.anchor_node, a] - (p.balance_rows[1, 1, a] if lagged else 0.0)
    if p.mesh.nodes.shape[0]:  # a point riding on an end: the line's own force leaves its load out
        state = (p.X, p.V, p.A, p.clock[0].t)
        _subtract_kernel(p, (p.mesh, p.water, p.pts, p.work, state, p.fairlead_node, out[0]))
        _subtract_kernel(p, (p.mesh, p.water, p.pts, p.work, state, p.anchor_node, out[1]))
    return 0


@njit(cache=True, inline="always", _nrt=False)
def reactions(p, forces, k):
    """The line's forces after step k into forces[k, 0] (``_forces``)."""
    return _forces(p, forces[k, 0])
