"""The junction steps of ``cablefem.dynamics.junctions``, compiled: runs of BDF2 steps of every string
that meets at junctions in one numba call, on the strings' ``march.Problem``s and their compiled ops.

The arithmetic is ``JunctionSteps.attempt``'s (the Python version, which stays the reference and
takes over a step the compiled loop cannot finish): per Newton iteration each string evaluates its
step residual and banded tangent, factorises it and solves for its own step y and the columns Z of
its junction ends; S = (Z_E)^-1 condenses it onto them; one small solve gives the junctions' step
dq; each string takes y + Z S (dq - y_E). A step converges when every string's increment is below
its increment tolerance; a step that does not is halved at the splits where the prescribed ends are
known (``march.FRACTIONS``), and the loop stops where that is not enough (the Python steps go on).

Compile time. The strings' Problems have one numba type (the catalog's records and the seabed's
projector are the same for every line; only sizes differ), so they come in a homogeneous tuple
indexed by a loop counter, and every function here is compiled once, for that type (the two loops
once more for another number of strings). ``numba.literal_unroll`` over them (the first version)
versioned each loop body per element and took more than five CPU-minutes. A function numba can
call from Python carries a wrapper that unboxes every array of its arguments, ~1.6 s of compile
per Problem and ~7 s per tuple of three: only ``group_steps`` has one. No numba runtime (the
small solves' scratch is in the ``Group``), and no literal arguments (each compiles a callee
once more).
"""

from collections import namedtuple

import numpy as np
from numba import njit

from cablefem.compiled import kernels
from cablefem.dynamics import policy
from cablefem.compiled.banded import lu_solve
from cablefem.compiled.steps import (FRACTIONS, _copy_rows, accept, begin, evaluate, increment, place_ends,
    set_base, take_step)

#: what ``group_steps`` returns: every step taken, or the loop stopped at a step (Python goes on)
DONE, STOPPED = 0, 1

#: the junctions of a group and the scratch of its steps: per string and each of its junction ends
#: (two slots, -1 where unused) the end's row in the band order, its junction and its node,
#: ``ends`` (strings, 2, 3); the number of junctions; the columns Z (strings, n, 6) of K^-1 at each
#: string's junction ends, their end stiffness S (strings, 6, 6) and the string's own step there
#: yE (strings, 6); the junctions' step dq (3 junctions,); the string and node whose predictor
#: places each junction at the start of a step, ``leaders`` (junctions, 2), and that place ``at``
#: (junctions, 3); Newton's iterations per attempt and the growth of a step; scratch of the small
#: solves: the junctions' system (3 J, 3 J), a string's end columns ZE and their inverse's work
#: (6, 6), a column and its correction mu (6,)
Group = namedtuple("Group", "ends junctions Z S yE dq leaders at max_iterations growth "
                            "system ZE work column mu")


def group(ends, leaders, n, max_iterations, growth):
    """A ``Group`` for ``ends`` (strings, 2, 3) and ``leaders`` (junctions, 2), the strings'
    bands n unknowns at most."""
    m, junctions = ends.shape[0], leaders.shape[0]
    return Group(np.ascontiguousarray(ends, dtype=np.int64), junctions, np.zeros((m, n, 6)),
                 np.zeros((m, 6, 6)), np.zeros((m, 6)), np.zeros(3 * junctions),
                 np.ascontiguousarray(leaders, dtype=np.int64), np.zeros((junctions, 3)), int(max_iterations),
                 float(growth), np.zeros((3 * junctions, 3 * junctions)), np.zeros((6, 6)), np.zeros((6, 6)),
                 np.zeros(6), np.zeros(6))


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


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _linearise(p, k, g):
    """String k at its trial: residual and tangent, its own step (p.step, band order), the columns
    Z[k] of its junction ends and their end stiffness S[k]; False if its tangent is singular."""
    if evaluate(p, policy.FLAG[1], policy.FLAG[0]) != 0:
        return False
    if np.isnan(increment(p, policy.FLAG[1])):
        return False
    ends, Z, scratch = g.ends, g.Z, p.original  # ``original`` is the policy's, unused here
    m = np.int64(0)  # not literal: numba would compile ``_inverse`` once more for a literal 0
    for s in range(2):
        if ends[k, s, 0] >= 0:
            m += 3
    if m == 0:
        return True
    ZE, j = g.ZE, 0
    for s in range(2):
        row = ends[k, s, 0]
        if row < 0:
            continue
        for c in range(3):
            scratch[:] = 0.0
            scratch[3 * row + c] = 1.0
            lu_solve(p.lu, scratch.shape[0], p.mesh.kl, p.mesh.ku, p.ipiv, scratch)
            for i in range(scratch.shape[0]):
                Z[k, i, j] = scratch[i]
            g.yE[k, j] = p.step[3 * row + c]
            i = 0
            for t in range(2):  # column j of ZE: Z's rows at the junction ends
                if ends[k, t, 0] >= 0:
                    for d in range(3):
                        ZE[i, j] = scratch[3 * ends[k, t, 0] + d]
                        i += 1
            j += 1
    return _inverse(ZE, g.S[k], m, g.work, g.column)


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _junction_step(g):
    """g.dq (3 J) from sum over strings of S_k (dq_E - y_E,k) = 0 at every junction."""
    ends, S, yE = g.ends, g.S, g.yE
    n = 3 * g.junctions
    A, b = g.system, g.dq
    A[:] = 0.0
    b[:] = 0.0
    for k in range(ends.shape[0]):
        a = 0
        for s in range(2):
            if ends[k, s, 0] < 0:
                continue
            bb = 0
            for t in range(2):
                if ends[k, t, 0] < 0:
                    continue
                for c in range(3):
                    for d in range(3):
                        value = S[k, 3 * a + c, 3 * bb + d]
                        A[3 * ends[k, s, 1] + c, 3 * ends[k, t, 1] + d] += value
                        b[3 * ends[k, s, 1] + c] += value * yE[k, 3 * bb + d]
                bb += 1
            a += 1
    return _solve_small(A, b, n)


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _begin(p, h):
    """BDF2's start of a step of h, the trial at the predictor."""
    begin(p, h)
    _copy_rows(p.X1, p.guess)


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _lead(p, j, g):
    """Junction j where its leader (this string, at node g.leaders[j, 1]) predicts it."""
    for a in range(3):
        g.at[j, a] = p.X1[g.leaders[j, 1], a]


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _agree(p, k, g):
    """String k's junction ends where their junctions' leaders predict them (``g.at``)."""
    for s in range(2):
        if g.ends[k, s, 0] >= 0:
            for a in range(3):
                p.X1[g.ends[k, s, 2], a] = g.at[g.ends[k, s, 1], a]


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _update(p, k, g):
    """String k's step y + Z S (dq_E - y_E) taken from its trial; True if its increment is below
    its increment tolerance."""
    ends, Z, S = g.ends, g.Z, g.S
    m = 0
    mu = g.mu
    for s in range(2):
        if ends[k, s, 0] >= 0:
            for c in range(3):
                mu[m] = g.dq[3 * ends[k, s, 1] + c] - g.yE[k, m]
                m += 1
    largest = 0.0
    for i in range(p.step.shape[0]):
        for j in range(m):
            for l in range(m):
                p.step[i] += Z[k, i, j] * S[k, j, l] * mu[l]
        largest = max(largest, abs(p.step[i]))
    set_base(p)
    take_step(p, 1.0)
    return largest <= p.settings.increment_tolerance


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _rows(p, k, g):
    """The step residual at the converged trial into p.rows (the reactions read it), and the
    string's own rows at its junction ends into p.base (Newton's base, free once converged): its
    elements without the node loads there, the junction's own point riding on it as a joint
    (``JunctionSteps.reactions``). False if a row is not finite."""
    evaluate(p, policy.FLAG[0], policy.FLAG[0])
    for i in range(p.rows.shape[0]):
        for a in range(3):
            if not np.isfinite(p.rows[i, a]):
                return False
    if g.ends[k, 0, 0] < 0 and g.ends[k, 1, 0] < 0:
        return True
    clock = p.clock[0]
    nb = p.rhs.shape[0]
    band2 = p.band.reshape((nb, 2 * p.mesh.kl + p.mesh.ku + 1)).T  # unused without a tangent
    p.base[:] = 0.0
    kernels.assemble(p.mesh, p.bed, p.water, p.pts, p.work, (p.X1, p.V1, p.A1, clock.t + clock.h),
                     (clock.v_x, clock.a_x), policy.FLAG[0], policy.FLAG[0], p.base, band2, p.end_elements)
    return True


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _forces(p, k, g, forces, i):
    """String k's forces on its fairlead and anchor after step i into forces[k, i] (2, 3): minus
    its rows there, at a junction end its own (``_rows``)."""
    for e in range(2):
        node = p.fairlead_node if e == 0 else p.anchor_node
        own = False
        for s in range(2):
            own = own or (g.ends[k, s, 0] >= 0 and g.ends[k, s, 2] == node)
        for a in range(3):
            forces[k, i, e, a] = -(p.base[node, a] if own else p.rows[node, a])


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def group_attempt(probs, g, h):
    """One BDF2 step of h of every string (the ends placed: ``place_ends``); True if it converged."""
    for k in range(len(probs)):
        _begin(probs[k], h)
    for j in range(g.junctions):
        _lead(probs[g.leaders[j, 0]], j, g)
    for k in range(len(probs)):
        _agree(probs[k], k, g)
    for _ in range(g.max_iterations):
        ok = True
        for k in range(len(probs)):
            probs[k].counters[policy.ITERATIONS] += 1
            ok = ok and _linearise(probs[k], k, g)
        if not ok or not _junction_step(g):
            return False
        converged = True
        for k in range(len(probs)):
            converged = _update(probs[k], k, g) and converged
        if converged:
            for k in range(len(probs)):
                if not _rows(probs[k], k, g):
                    return False
            for k in range(len(probs)):
                accept(probs[k], h)
                probs[k].counters[policy.STEPS] += 1
            return True
    return False


@njit(cache=True, _nrt=False)
def group_steps(probs, g, times, forces):
    """Steps of every string to ``times`` (m,), each halved at the splits of ``march.FRACTIONS``
    when Newton fails; string k's (fairlead, anchor) forces into forces[k] (m, 2, 3).
    Returns (DONE or STOPPED, the steps taken)."""
    for i in range(times.shape[0]):
        start = probs[0].clock[0].t
        span = times[i] - start
        done, parts = 0, FRACTIONS
        last = probs[0].clock[0].last_h
        while last > 0.0 and parts > 1 and span * parts / FRACTIONS > g.growth * last:
            parts //= 2
        while done < FRACTIONS:
            parts = min(parts, FRACTIONS - done)
            h = span * parts / FRACTIONS
            for k in range(len(probs)):
                place_ends(probs[k], i, done + parts, h)
            if group_attempt(probs, g, h):
                done += parts
                parts = min(2 * parts, FRACTIONS)
            elif parts == 1:
                return STOPPED, i
            else:
                for k in range(len(probs)):
                    probs[k].counters[policy.REJECTED] += 1
                parts //= 2
        for k in range(len(probs)):
            _forces(probs[k], k, g, forces, i)
    return DONE, times.shape[0]
