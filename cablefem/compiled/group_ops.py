"""The Newton policy's compiled ops on a ``cablefem.compiled.steps.Group``, ``g``: strings that meet at
junction points, stepped together. Each op is one compiled function that loops over the strings (in
numba's typed List) with the ops of ``cablefem.compiled.line_ops``; the Newton increment condenses each
string onto its junction ends and solves the junctions (``group_increment``). ``cablefem.compiled.steps``
binds them to the policy with a scheme's functions (``steps.bound``).
"""

import numpy as np
from numba import njit

from cablefem.compiled.line_ops import (
    _columns, _forces, _increment, _joined, _largest, _solve_small, _sum_squares, accept, auto_left, begin,
    contraction, count, error, evaluate, factors_current, finish, forget_factors, hold, last_error, last_step,
    place_ends, proposal, record_error, record_residual, record_stop, restart, restore_base, restore_original,
    save_original, set_auto_left, set_base, set_contraction, set_proposal, take_step, time)


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
