"""Time steps on the compiled kernel, many in one numba call: the Newton policy's compiled ops.

``cablefem.dynamics.policy`` writes the Newton policy once (iterations, line search, branch
corrections, retries, halving and growth); ``bound(scheme)`` binds it to the compiled ops here,
with a scheme's arithmetic (``cablefem.dynamics.scheme``: BDF2, generalised-alpha, or any scheme a
file defines), and compiles it. The policy steps a ``Group`` of strings: a line alone is a group of
one; the strings that meet at junction points are a group whose junctions are solved with them,
each string condensed onto its junction ends (``cablefem.dynamics.group``). Runs of steps go without
returning to Python, with the numbers of the Python ops (``cablefem.dynamics.python_ops``) to
round-off (tests/test_march.py, tests/test_march_alpha.py, tests/test_junction_steps.py).

The banded LU is ``cablefem.compiled.banded`` (LAPACK's dgbtf2/dgbtrs written out: numba cannot cache
a ctypes call to LAPACK). The seabed is projected in the loop too (``cablefem.compiled.seabed``);
where the walk cannot place a point, the loop stops and that step goes on in Python, whose search
finds it.

Compile time. Every function here is compiled once per scheme (``bound``): they are rebound to the
scheme's functions, under names that carry the scheme's name and a hash of its code, so that each
binding has its own on-disk cache. The strings of a group have one numba type (the catalog's records
and the seabed's projector are the same for every line; only sizes differ), so they come in numba's
typed List (``strings_list``), whose type does not hold their number: one compilation serves every
network. A tuple's does (each size compiled the group's steps again, minutes each, longer the more
strings), and ``numba.literal_unroll`` versions each loop body per element. No numba runtime on a
string, nor on a line's policy (the small solves' scratch is in the group; the group's ops and policy
have it for the List), and no literal arguments (each compiles a callee once more: ``policy.FLAG``).
numba links the code of every callee into its caller and optimises and compiles it there again, so
each layer of the policy (steps, advance, attempt, newton) cost again all it called, the element
loop among it, 3-5 s of the first run each: the layers call each other by address (``CALLS``,
``cablefem.compiled.calls``; ``advance`` is inlined into ``steps``), and so does a string's evaluation call the element loop, the seabed's
projection and the node loads (``THROUGH``): each compiled once, its address in the ``calls`` of
the ``Problem`` and ``Group`` (``fill_calls``), the projection and the node loads only for a scene
that has them. Python calls one function (``_entry``: numba's Python wrapper unboxes the ``Problem``
in code as large as a layer's), the others have no Python wrapper, none has a C wrapper.
"""

import hashlib
import sys
from collections import namedtuple
from types import FunctionType, ModuleType

import numpy as np
from numba import njit, types
from numba.typed import List
from numba import uint64 as _index  # an unsigned index: no wrap-around fix-up (cablefem.compiled.banded)

from cablefem.compiled import calls, kernels
from cablefem.compiled.banded import lu_factor, lu_solve
from cablefem.compiled.seabed import PLANE, project
from cablefem.dynamics import policy

#: a step of the compiled loop may be halved this many times (the ends' positions at the
#: 2**DEPTH - 1 points that split each step evenly are given); deeper, the Python ops go on
DEPTH = 3
FRACTIONS = 2 ** DEPTH

#: one string (``cablefem.compiled.problem.Packer``): the policy's settings, the kernel's records (mesh, bed, water,
#: pts, work) and the seabed's projector; its free nodes, those of them that are not junction ends
#: (``interior``), the free unknowns in band order, all and the end elements, the anchor and fairlead
#: nodes, its residual scale, the factor that puts its increments in the group's increment
#: tolerance and the axial stiffness per element [N] (the error control's tension scale); the state X, V, A, the scheme's memory (MEMORY, N, 3), the last predictor and the rows
#: M A + G (N, 3), updated in place; the trial X1, the evaluation point Xe, Ve, Ae, the guess and
#: Newton's base (N, 3); the increment, Newton's
#: step and its own step when corrected (n,); the band and its LU (flat, LAPACK's column-major
#: layout), pivots and multipliers; the base's branch state; the byte views (dst, src) that keep the
#: branch state as the base's and commit the trial history; the clock (``policy.CLOCK``), the kept
#: factors' key (``policy.FACTORS``), the scheme's record, counters (``policy.COUNTERS``); the anchor
#: and fairlead at the end of each step (m, 2, 3), at its splits (m, FRACTIONS - 1, 2, 3) and at the
#: end of the attempt (2, 3); its junction ends, (2, 3) rows of (band row, junction, node), -1 where
#: unused, the columns Z (n, 6) of K^-1 there, their end stiffness S (6, 6) and the string's own step
#: there yE (6,); the last balance's fairlead and anchor rows and what the reactions add to them
#: (2, 2, 3) (``Integrator.balance_rows``); the addresses of the functions its ops call (``CALLS``)
Problem = namedtuple("Problem", "settings mesh bed water pts work projector free_nodes interior free_order all_elements "
                                "end_elements anchor_node fairlead_node scale increment_scale EA "
                                "X V A memory prediction rows X1 Xe Ve Ae guess base "
                                "rhs step original band lu ipiv multipliers base_full base_reduced keeps commits "
                                "clock factors scheme counters ends fractions target junction_ends Z S yE "
                                "balance_rows calls")
#: the strings stepped together: the policy's settings, the strings (numba's typed List of ``Problem``:
#: ``strings_list``), the number of junctions, their step dq (3 J,), the string and node whose predictor
#: places each junction (J, 2) and that place (J, 3), the junctions' balance (J, 3), the group's
#: residual scale, and scratch of the small solves: the junctions' system (3 J, 3 J), a string's end
#: columns ZE and their inverse's work (6, 6), a column and a correction mu (6,); the addresses of the
#: functions its ops call (``CALLS``)
Group = namedtuple("Group", "settings strings junctions dq leaders at balance scale system ZE work column mu calls")

#: the policy's layers called by address (``cablefem.compiled.calls``: compiled once, not again in each caller):
#: the slot of each in the ``calls`` of the prob the policy steps (a line's ``Problem`` or a ``Group``), and
#: the types of its arguments after the prob: ``newton`` from ``attempt``, ``attempt`` from ``advance`` (and
#: on its own from ``_entry``), ``steps`` from ``_entry``. Only these: a call by address copies the
#: ``Problem``'s array descriptors as arguments (~900 words), here once an attempt; the string's evaluation
#: and Newton increment, once an iteration, are linked into ``newton`` (by address they cost the steps 0.7 %
#: more instructions)
CALLS = {"newton": (0, (types.boolean, types.int64)), "steps": (1, (types.float64[::1], types.float64[:, :, :, ::1])),
         "attempt": (2, (types.float64,))}
#: the layers inlined into their one caller: ``advance`` into ``steps`` (``attempt`` into ``advance`` too would
#: save 0.35 % of the steps' instructions and cost the first run 4 s: ``benchmarks/startup.py``)
INLINED = ("advance",)


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


#: what a string's ``Problem`` calls by address with the arguments it names (``calls.through``): its slot,
#: the types of the arguments, and whether a string needs it (its address is written, and the function
#: compiled, only where one of the group's does)
THROUGH = {"assemble": (3, _assemble_types, None), "assemble_nodes": (4, _nodes_types, _with_nodes),
           "subtract_node_loads": (5, _subtract_types, _with_nodes), "project": (6, _project_types, _on_seabed)}
THROUGH_FUNCTIONS = {"assemble": kernels.assemble, "assemble_nodes": kernels.assemble_nodes,
                     "subtract_node_loads": kernels.subtract_node_loads, "project": project}
SLOTS = len(CALLS) + len(THROUGH)

_assemble_kernel = calls.through(kernels.assemble, _assemble_types, THROUGH["assemble"][0])
_nodes_kernel = calls.through(kernels.assemble_nodes, _nodes_types, THROUGH["assemble_nodes"][0], types.none)
_subtract_kernel = calls.through(kernels.subtract_node_loads, _subtract_types, THROUGH["subtract_node_loads"][0],
                                 types.none)
_project_kernel = calls.through(project, _project_types, THROUGH["project"][0], types.int64)


@njit(cache=True)
def _new_strings(first):
    strings = List()
    strings.append(first)
    return strings


@njit(cache=True)
def _append_string(strings, p):
    strings.append(p)


def strings_list(problems):
    """The ``Problem`` of each string of a group in numba's typed List (their arrays shared, not
    copied), made and filled by compiled functions cached on disk (a List's own methods compile in
    every process)."""
    strings = _new_strings(problems[0])
    for p in problems[1:]:
        _append_string(strings, p)
    return strings


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


# ------------------------------------------------------------------ the policy's ops on a group
# (strings that meet at junctions: ``prob`` is a ``Group``; each op one compiled function, looping
# over the strings with the string ops above)
@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_evaluate(g, tangent, held):
    for k in range(len(g.strings)):
        lost = evaluate(g.strings[k], tangent, held)
        if lost != 0:
            return lost
    return 0


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_finish(g):
    for k in range(len(g.strings)):
        lost = finish(g.strings[k])
        if lost != 0:
            return lost
    return 0


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_norm(g):
    """The group's relative residual: every string's rows at its free nodes that are no junction
    end, and each junction's balance, the sum of its string ends' rows."""
    total = 0.0
    for k in range(len(g.strings)):
        total += _sum_squares(g.strings[k])
    balance = g.balance
    balance[:] = 0.0
    for k in range(len(g.strings)):
        p = g.strings[k]
        for s in range(2):
            if p.junction_ends[s, 0] >= 0:
                for a in range(3):
                    balance[p.junction_ends[s, 1], a] += p.rows[p.junction_ends[s, 2], a]
    for j in range(g.junctions):
        for a in range(3):
            total += balance[j, a] * balance[j, a]
    return np.sqrt(total) / g.scale


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _junction_step(g):
    """g.dq (3 J) from sum over strings of S_k (dq_E - y_E,k) = 0 at every junction; False if singular."""
    n = 3 * g.junctions
    A, b = g.system, g.dq
    A[:] = 0.0
    b[:] = 0.0
    for k in range(len(g.strings)):
        p = g.strings[k]
        ends, S, yE = p.junction_ends, p.S, p.yE
        a = 0
        for s in range(2):
            if ends[s, 0] < 0:
                continue
            bb = 0
            for t in range(2):
                if ends[t, 0] < 0:
                    continue
                for c in range(3):
                    for d in range(3):
                        value = S[3 * a + c, 3 * bb + d]
                        A[3 * ends[s, 1] + c, 3 * ends[t, 1] + d] += value
                        b[3 * ends[s, 1] + c] += value * yE[3 * bb + d]
                bb += 1
            a += 1
    return _solve_small(A, b, n)


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _condense(g):
    """Every string's step y + Z S (dq_E - y_E) at its junctions' step dq; its largest scaled entry."""
    size = 0.0
    for k in range(len(g.strings)):
        p = g.strings[k]
        ends, mu = p.junction_ends, g.mu
        m = 0
        for s in range(2):
            if ends[s, 0] >= 0:
                for c in range(3):
                    mu[m] = g.dq[3 * ends[s, 1] + c] - p.yE[m]
                    m += 1
        for i in range(p.step.shape[0]):
            for j in range(m):
                for l in range(m):
                    p.step[i] += p.Z[i, j] * p.S[j, l] * mu[l]
        size = max(size, _largest(p.step) * p.increment_scale)
    return size


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_increment(g, refactor):
    """Every string's Newton increment (``_increment``), each condensed onto its junction ends and
    the junctions' step solved (``_junction_step``); the largest entry, each string's scaled to the
    group's increment tolerance (NaN: singular)."""
    for k in range(len(g.strings)):
        p = g.strings[k]
        largest = _increment(p, refactor)
        if largest != largest:
            return largest
        if _joined(p):
            if refactor and not _columns(p, g):
                return np.nan
            j = 0
            for s in range(2):
                if p.junction_ends[s, 0] >= 0:
                    for c in range(3):
                        p.yE[j] = p.step[3 * p.junction_ends[s, 0] + c]
                        j += 1
    if not _junction_step(g):
        return np.nan
    return _condense(g)


@njit(cache=True, inline="always")
def group_factors_current(g):
    return factors_current(g.strings[0])


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_forget_factors(g):
    for k in range(len(g.strings)):
        forget_factors(g.strings[k])


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_take_step(g, fraction):
    for k in range(len(g.strings)):
        take_step(g.strings[k], fraction)


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_set_base(g):
    for k in range(len(g.strings)):
        set_base(g.strings[k])


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_restore_base(g):
    for k in range(len(g.strings)):
        restore_base(g.strings[k])


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_hold(g, again):
    held = False
    for k in range(len(g.strings)):
        held = hold(g.strings[k], again) or held
    return held


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_save_original(g):
    for k in range(len(g.strings)):
        save_original(g.strings[k])


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_restore_original(g):
    size = 0.0
    for k in range(len(g.strings)):
        p = g.strings[k]
        largest = restore_original(p)
        if largest != largest:
            return largest
        size = max(size, largest * p.increment_scale)
    return size


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_begin(g, h):
    """Every string's step of h; each junction where its leader string predicts it."""
    for k in range(len(g.strings)):
        begin(g.strings[k], h)
    for j in range(g.junctions):
        leader = g.strings[g.leaders[j, 0]]
        for a in range(3):
            g.at[j, a] = leader.guess[g.leaders[j, 1], a]
    for k in range(len(g.strings)):
        p = g.strings[k]
        for s in range(2):
            if p.junction_ends[s, 0] >= 0:
                for a in range(3):
                    p.guess[p.junction_ends[s, 2], a] = g.at[p.junction_ends[s, 1], a]


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_restart(g):
    for k in range(len(g.strings)):
        restart(g.strings[k])


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_accept(g, h):
    for k in range(len(g.strings)):
        accept(g.strings[k], h)


@njit(cache=True, inline="always")
def group_auto_left(g):
    return auto_left(g.strings[0])


@njit(cache=True, inline="always")
def group_set_auto_left(g, value):
    set_auto_left(g.strings[0], value)


@njit(cache=True, inline="always")
def group_contraction(g):
    return contraction(g.strings[0])


@njit(cache=True, inline="always")
def group_set_contraction(g, value):
    set_contraction(g.strings[0], value)


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_count(g, counter, amount):
    for k in range(len(g.strings)):
        count(g.strings[k], counter, amount)
    return g.strings[0].counters[counter]


@njit(cache=True, inline="always")
def group_time(g):
    return time(g.strings[0])


@njit(cache=True, inline="always")
def group_last_step(g):
    return last_step(g.strings[0])


@njit(cache=True, inline="always")
def group_record_residual(g, value):
    record_residual(g.strings[0], value)


@njit(cache=True, inline="always")
def group_record_stop(g, h):
    record_stop(g.strings[0], h)


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_place_ends(g, k, j, h):
    for s in range(len(g.strings)):
        place_ends(g.strings[s], k, j, h)
    return True


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_error(g):
    worst = -1.0
    for k in range(len(g.strings)):
        e = error(g.strings[k])
        if e < 0.0:
            return -1.0
        worst = max(worst, e)
    return worst


@njit(cache=True, inline="always")
def group_last_error(g):
    return last_error(g.strings[0])


@njit(cache=True, inline="always")
def group_record_error(g, value):
    record_error(g.strings[0], value)


@njit(cache=True, inline="always")
def group_proposal(g):
    return proposal(g.strings[0])


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_set_proposal(g, value):
    for k in range(len(g.strings)):
        set_proposal(g.strings[k], value)


@njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def group_reactions(g, forces, k):
    """Every string's forces after step k into forces[k, string] (``_forces``)."""
    for s in range(len(g.strings)):
        lost = _forces(g.strings[s], forces[k, s])
        if lost != 0:
            return lost
    return 0


# ------------------------------------------------------------------------ bound per scheme
#: the ops the policy calls (``cablefem.dynamics.policy``'s docstring), besides ``attempt``: on a
#: string these names, on a group ``group_`` and these names
OPS = ("evaluate", "norm", "increment", "factors_current", "forget_factors", "take_step", "set_base",
       "restore_base", "hold", "save_original", "restore_original", "finish", "begin", "restart", "accept",
       "auto_left", "set_auto_left", "contraction", "set_contraction", "count", "time", "last_step",
       "record_residual", "record_stop", "place_ends", "reactions", "error", "last_error", "record_error",
       "proposal", "set_proposal")
#: the functions that read the scheme, directly or through another: copied per scheme by ``bound``
#: (each one's callees before it)
SCHEMED = ("_assemble", "evaluate", "finish", "begin", "accept", "_forces", "reactions", "error", "group_evaluate",
           "group_finish", "group_begin", "group_accept", "group_reactions", "group_error")
_BOUND = {}


def _tag(scheme):
    """The scheme's name and a hash of its functions' code: the bound functions' cache names."""
    digest = hashlib.sha256(scheme.parameters.str.encode() + str(scheme.memory).encode()
                            + str(scheme.rows_at_state).encode())
    for function in (scheme.begin, scheme.point, scheme.accept, scheme.error):
        code = function.py_func.__code__
        digest.update(code.co_code + repr(code.co_consts).encode() + repr(code.co_names).encode())
    return "".join(c if c.isalnum() else "_" for c in scheme.name) + "_" + digest.hexdigest()[:10]


_attempt_call = _steps_call = None  # bound per scheme and kind (``bound``)


def _entry(prob, times, forces, h):
    """Python's one way into the compiled policy: with h > 0 one attempt of size h (``policy.attempt``;
    its outcome, 0), else steps to ``times`` (``policy.steps``). One function with numba's Python
    wrapper, whose unboxing of the ``Problem`` or ``Group`` is as large as a layer: it was compiled
    for ``attempt`` and ``steps`` each."""
    if h > 0.0:
        return _attempt_call(prob, h), 0
    return _steps_call(prob, times, forces)


def _compiler(kind):
    """numba's njit for the policy's functions on a ``kind`` ("line", "group"): numba's runtime only
    on a group (its strings' typed List; a line's ``Problem`` holds arrays Python owns, and with the
    runtime every op copying it counts references to its ~50 arrays: 15 s more compilation of the
    first run), no Python wrapper (Python calls them through ``_entry``), no C wrapper (the
    module's docstring, "Compile time"), and ``INLINED`` into their caller."""
    def compile(function):
        return njit(cache=True, _nrt=kind == "group", no_cpython_wrapper=True, no_cfunc_wrapper=True,
                    inline="always" if function.__name__ in INLINED else "never")(function)
    return compile


def bound(scheme):
    """The policy's functions (``policy.FUNCTIONS``: newton, attempt, advance, steps) bound to the ops
    here and to ``scheme``'s arithmetic, compiled: {"line": on a string's ``Problem``, "group": on a
    ``Group``}; one pair per scheme, made on first use (each compiled on its first call)."""
    tag = _tag(scheme)
    if tag in _BOUND:
        return _BOUND[tag]
    module = sys.modules[__name__]
    namespace = dict(vars(module))
    namespace.update(scheme_begin=scheme.begin, scheme_point=scheme.point, scheme_accept=scheme.accept,
                     scheme_error=scheme.error, ROWS_AT_STATE=scheme.rows_at_state)
    for name in SCHEMED:  # in this order: each one's callees first
        original = getattr(module, name)
        function = FunctionType(original.py_func.__code__, namespace, name, original.py_func.__defaults__)
        function.__qualname__ = f"{tag}.{name}"
        options = {key: value for key, value in original.targetoptions.items() if key != "nopython"}
        namespace[name] = njit(cache=True, **options)(function)
    functions = {}
    for kind, prefix in (("line", ""), ("group", "group_")):
        ops = ModuleType(f"{__name__}.{tag}.{kind}")
        for name in OPS:
            setattr(ops, name, namespace[prefix + name])
        functions[kind] = policy.bind(ops, compile=_compiler(kind), name=f"{kind}_{tag}", link=_link)
        ops.attempt = _link("attempt", functions[kind]["attempt"])
        slot, rest = CALLS["attempt"]  # compiled on its own only where Python takes one attempt (``fill_calls``)
        entry = {"_attempt_call": calls.by_address(functions[kind]["attempt"], rest, slot, types.int64),
                 "_steps_call": _link("steps", functions[kind]["steps"])}
        function = FunctionType(_entry.__code__, dict(vars(module), **entry), "entry")
        function.__qualname__ = f"{kind}_{tag}.entry"
        functions[kind]["entry"] = njit(cache=True, _nrt=kind == "group", no_cfunc_wrapper=True)(function)
    _BOUND[tag] = functions
    return functions


def _link(name, function):
    """What the policy's functions call in place of its layer ``name`` (``policy.bind``): ``function``
    by address (``CALLS``), or itself where it is inlined (``INLINED``)."""
    if name in INLINED:
        return function
    slot, rest = CALLS[name]
    return calls.by_address(function, rest, slot)


def fill_calls(functions, prob, strings, table, attempt=False):
    """Write into ``table`` (the ``calls`` of ``prob`` and of its strings) the addresses of the policy's
    layers of ``functions`` (a kind's of ``bound``; ``CALLS``) for ``prob`` (a line's ``Problem`` or a
    ``Group``), and of what the ``strings`` (their ``Problem``s, one type) call with the arguments it
    names (``THROUGH``) where one needs it, each compiled or loaded for those types; ``attempt``: only
    the address of ``attempt`` on its own (for ``_entry``'s single attempts)."""
    string = calls.type_of(strings[0])
    whole = calls.type_of(prob) if prob is not strings[0] else string
    if attempt:
        slot, rest = CALLS["attempt"]
        table[slot] = calls.address(functions["attempt"], (whole,) + rest, types.int64)
        return
    for name in CALLS:
        if name != "attempt" or name not in INLINED:  # inlined, the attempt on its own only where asked
            slot, rest = CALLS[name]
            table[slot] = calls.address(functions[name], (whole,) + rest, types.int64 if name == "attempt" else None)
    for name, (slot, types_of, needed) in THROUGH.items():
        if needed is None or any(needed(p) for p in strings):
            table[slot] = calls.address(THROUGH_FUNCTIONS[name], types_of(string))
