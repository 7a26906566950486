"""The junction steps of ``cablefem.coupled_steps``, compiled: runs of BDF2 steps of every string
that meets at junctions in one numba call, on the strings' ``march.Problem``s and their compiled ops.

The arithmetic is ``JunctionSteps.attempt``'s (the Python version, which stays the reference and
takes over a step the compiled loop cannot finish): per Newton iteration each string evaluates its
step residual and banded tangent, factorises it and solves for its own step y and the columns Z of
its junction ends; S = (Z_E)^-1 condenses it onto them; one small solve gives the junctions' step
dq; each string takes y + Z S (dq - y_E). A step converges when every string's increment is below
its increment tolerance; a step that does not is halved at the splits where the prescribed ends are
known (``march.FRACTIONS``), and the loop stops where that is not enough (the Python steps go on).

The strings' Problems differ in type where their loads do (a string carrying the junction's point
has the node load), so the loops over them are unrolled (``numba.literal_unroll``).
"""

import numpy as np
from numba import literal_unroll, njit

from . import policy
from .banded import lu_solve
from .march import FRACTIONS, accept, begin, evaluate, increment, place_ends, set_base, take_step

#: what ``group_steps`` returns: every step taken, or the loop stopped at a step (Python goes on)
DONE, STOPPED = 0, 1


@njit(cache=True)
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


@njit(cache=True)
def _inverse(M, out, n):
    """out = M^-1 (n x n) column by column; False if singular."""
    work, column = np.empty((n, n)), np.empty(n)
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


@njit(cache=True)
def _linearise(p, k, ends, Z, S, yE, scratch):
    """String k at its trial: residual and tangent, its own step (p.step, band order), the columns
    Z[k] of its junction ends and their end stiffness S[k]; False if its tangent is singular."""
    if evaluate(p, policy.FLAG[1], policy.FLAG[0]) != 0:
        return False
    if np.isnan(increment(p, policy.FLAG[1])):
        return False
    m = 0
    for s in range(2):
        row = ends[k, s, 0]
        if row < 0:
            continue
        for c in range(3):
            scratch[:] = 0.0
            scratch[3 * row + c] = 1.0
            lu_solve(p.lu, scratch.shape[0], p.mesh.kl, p.mesh.ku, p.ipiv, scratch)
            for i in range(scratch.shape[0]):
                Z[k, i, m] = scratch[i]
            yE[k, m] = p.step[3 * row + c]
            m += 1
    if m:
        ZE = np.empty((m, m))
        i = 0
        for s in range(2):
            row = ends[k, s, 0]
            if row < 0:
                continue
            for c in range(3):
                for j in range(m):
                    ZE[i, j] = Z[k, 3 * row + c, j]
                i += 1
        if not _inverse(ZE, S[k], m):
            return False
    return True


@njit(cache=True)
def _junction_step(ends, S, yE, junctions, dq):
    """dq (3 J) from sum over strings of S_k (dq_E - y_E,k) = 0 at every junction."""
    n = 3 * junctions
    A, b = np.zeros((n, n)), np.zeros(n)
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
    ok = _solve_small(A, b, n)
    dq[:n] = b
    return ok


@njit(cache=True)
def _agree(probs, ends, junctions):
    """Every string end at a junction where the junction's first string predicts it."""
    at, seen = np.zeros((junctions, 3)), np.zeros(junctions, dtype=np.bool_)
    k = 0
    for p in literal_unroll(probs):
        for s in range(2):
            j, node = ends[k, s, 1], ends[k, s, 2]
            if ends[k, s, 0] < 0:
                continue
            if not seen[j]:
                seen[j] = True
                for c in range(3):
                    at[j, c] = p.X1[node, c]
            else:
                for c in range(3):
                    p.X1[node, c] = at[j, c]
        k += 1


@njit(cache=True)
def _begin(p, h):
    """BDF2's start of a step of h, the trial at the predictor (a helper of its own: numba unrolls
    the loops over the strings only around calls, not inlined bodies)."""
    begin(p, h)
    p.X1[:] = p.guess


@njit(cache=True)
def _place(p, k, j, h):
    place_ends(p, k, j, h)


@njit(cache=True)
def _update(p, k, ends, Z, S, yE, dq):
    """String k's step y + Z S (dq_E - y_E) taken from its trial; True if its increment is below
    its increment tolerance."""
    m = 0
    mu = np.zeros(6)
    for s in range(2):
        if ends[k, s, 0] >= 0:
            for c in range(3):
                mu[m] = dq[3 * ends[k, s, 1] + c] - yE[k, m]
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


@njit(cache=True)
def _rows(p):
    """The step residual at the converged trial (the reactions read it)."""
    evaluate(p, policy.FLAG[0], policy.FLAG[0])


@njit(cache=True)
def _accept(p, h):
    accept(p, h)
    p.counters[policy.STEPS] += 1


@njit(cache=True)
def _count(p, counter):
    p.counters[counter] += 1


@njit(cache=True)
def _forces(p, forces, i, k):
    for a in range(3):
        forces[i, k, 0, a] = -p.rows[p.fairlead_node, a]
        forces[i, k, 1, a] = -p.rows[p.anchor_node, a]


@njit(cache=True)
def group_attempt(probs, ends, junctions, h, Z, S, yE, dq, max_iterations):
    """One BDF2 step of h of every string (the ends placed: ``place_ends``); True if it converged."""
    for p in literal_unroll(probs):
        _begin(p, h)
    _agree(probs, ends, junctions)
    for _ in range(max_iterations):
        k, ok = 0, True
        for p in literal_unroll(probs):
            _count(p, policy.ITERATIONS)
            ok = ok and _linearise(p, k, ends, Z, S, yE, p.original)
            k += 1
        if not ok or not _junction_step(ends, S, yE, junctions, dq):
            return False
        converged, k = True, 0
        for p in literal_unroll(probs):
            converged = _update(p, k, ends, Z, S, yE, dq) and converged
            k += 1
        if converged:
            for p in literal_unroll(probs):
                _rows(p)
            for p in literal_unroll(probs):
                _accept(p, h)
            return True
    return False


@njit(cache=True)
def group_steps(probs, ends, junctions, times, forces, Z, S, yE, dq, max_iterations, growth):
    """Steps of every string to ``times`` (m,), each halved at the splits of ``march.FRACTIONS``
    when Newton fails; each string's (fairlead, anchor) forces into forces[k] (m, 2, 3).
    Returns (DONE or STOPPED, the steps taken)."""
    for k in range(times.shape[0]):
        start = probs[0].clock[0].t
        span = times[k] - start
        done, parts = 0, FRACTIONS
        last = probs[0].clock[0].last_h
        while last > 0.0 and parts > 1 and span * parts / FRACTIONS > growth * last:
            parts //= 2
        while done < FRACTIONS:
            parts = min(parts, FRACTIONS - done)
            h = span * parts / FRACTIONS
            for p in literal_unroll(probs):
                _place(p, k, done + parts, h)
            if group_attempt(probs, ends, junctions, h, Z, S, yE, dq, max_iterations):
                done += parts
                parts = min(2 * parts, FRACTIONS)
            elif parts == 1:
                return STOPPED, k
            else:
                for p in literal_unroll(probs):
                    _count(p, policy.REJECTED)
                parts //= 2
        i = 0
        for p in literal_unroll(probs):
            _forces(p, forces, i, k)
            i += 1
    return DONE, times.shape[0]
