"""The Newton policy's ops in Python (``cablefem.dynamics.policy``): ``prob`` is a ``Group`` of strings
(``cablefem.dynamics.group``: a line alone, or the strings that meet at junctions).

They evaluate through each string's integrator and evaluator (``cablefem.fem.evaluator``: the
compiled kernel per evaluation with its banded LU, or the numpy loads and a sparse LU) at the
evaluation point of its scheme (``Integrator.point``). The same policy bound to the compiled ops
(``cablefem.compiled.steps``) steps the strings in numba; the two give the same numbers to round-off.
"""

import numpy as np



def evaluate(g, tangent, held):
    for m in g.members:
        X, V, A = m.point(m.X1)
        m.rows, m.tangent = m.rows_and_tangent(X, V, A, m.t_eval, m.factors[0], m.factors[1], tangent, held)
    return 0


def finish(g):
    """The rows at a point Newton accepted without evaluating it: for the reactions, the rows of the
    converged point (``Scheme.rows_at_state``), and for the history the loads commit; neither
    needed, nothing is evaluated."""
    for m in g.members:
        if m.scheme.rows_at_state or m.system.kept_history():
            X, V, A = m.point(m.X1)
            m.rows, m.tangent = m.rows_and_tangent(X, V, A, m.t_eval, m.factors[0], m.factors[1], False, False)
    return 0


def norm(g):
    """The group's relative residual: the strings' rows at their free nodes that are no junction end,
    and each junction's balance (the sum of its string ends' rows)."""
    if not g.junctions and len(g.members) == 1:
        m = g.members[0]
        return float(np.linalg.norm(m.rows[m.fem.free_dofs]) / m.scale)
    total = sum(float(np.sum(m.rows[interior] ** 2)) for m, interior in zip(g.members, g.interior))
    balance = np.zeros((len(g.names), 3))
    for m, ends in zip(g.members, g.ends):
        for _, _, j, dof in ends:
            balance[j] += m.rows[dof]
    return float(np.sqrt(total + np.sum(balance ** 2)) / g.scale)


def _size(g, steps):
    """The largest entry of the strings' steps, each in the first string's increment tolerance."""
    return max(float(np.max(np.abs(step), initial=0.0)) * scale  # 0: a line with no unknowns
               for step, scale in zip(steps, g.increment_scale))


def member_steps(g, refactor):
    """Every string's own Newton step y (its coupling ends free) and, with ``refactor``, its columns
    at its coupling ends (``Group.columns``); None when a tangent is singular or a step not finite."""
    steps = []
    for k, m in enumerate(g.members):
        step = m.increment(m.tangent, m.rows, refactor)
        if step is None:
            return None
        if refactor and g.ends[k]:
            m.junction_columns = g.columns(k)
            if m.junction_columns is None:
                return None
        steps.append(step)
    return steps


def increment(g, refactor):
    """Every string's Newton step into its ``newton_step`` (condensed onto the junctions); the largest
    entry (``_size``), NaN when a tangent is singular or a step not finite (``Group.singular``)."""
    steps = member_steps(g, refactor)
    if steps is None:
        return not_finite(g)
    if g.junctions:
        steps = g.condense(steps)
        if steps is None or not all(np.all(np.isfinite(step)) for step in steps):
            return not_finite(g)
    for m, step in zip(g.members, steps):
        m.newton_step = step
    return _size(g, steps)


def not_finite(g):
    """NaN, the increment of a Newton that cannot go on, marked on the group for its error
    (``Group.too_small``): a smaller step may still help, a singular system is no residual to report."""
    g.singular = True
    return float("nan")


def factors_current(g):
    return all(m.lu is not None and m.lu_factors == m.factors for m in g.members)


def forget_factors(g):
    for m in g.members:
        m.lu = None


def take_step(g, fraction):
    for m in g.members:
        X1 = m.base.copy()
        X1[m.fem.free_dofs] += fraction * m.newton_step
        m.X1 = X1


def set_base(g):
    for m in g.members:
        m.base = m.X1
        m.evaluator.keep()


def restore_base(g):
    for m in g.members:
        m.X1 = m.base.copy()


def hold(g, again):
    """The branch holds of every string's evaluator (the compiled kernel's per-point state; none with
    the numpy loads)."""
    held = [m.evaluator.hold(again) for m in g.members]
    return any(held)


def save_original(g):
    for m in g.members:
        m.original_step = m.newton_step


def restore_original(g):
    for m in g.members:
        m.newton_step = m.original_step
    return _size(g, [m.original_step for m in g.members])


def attempt(g, h):
    """The group's ``attempt`` (the policy's, on these ops, or compiled)."""
    return g.attempt(h)


def error(g):
    """The largest of the strings' local tension errors (``Integrator.error``); -1 where one has none."""
    errors = [m.error() for m in g.members]
    return -1.0 if min(errors) < 0.0 else max(errors)


def last_error(g):
    return float(g.members[0].clock["error"][0])


def record_error(g, value):
    g.members[0].clock["error"] = value


def proposal(g):
    return float(g.members[0].clock["proposal"][0])


def set_proposal(g, value):
    for m in g.members:
        m.clock["proposal"] = value


def begin(g, h):
    """Every string's step of h (its scheme's ``begin``); each junction where its first string's
    predictor puts it."""
    for m in g.members:
        m.begin(h)
    for name, j in zip(g.names, range(len(g.names))):
        k, end = g.junctions[name][0]
        at = g.members[k].guess[g.members[k].fem.end_dofs[end]].copy()
        for k, end in g.junctions[name][1:]:
            g.members[k].guess[g.members[k].fem.end_dofs[end]] = at


def restart(g):
    g.singular = False  # a Newton from the guess
    for m in g.members:
        m.X1 = m.guess.copy()


def accept(g, h):
    for m in g.members:
        m.accept(h)
        m.system.commit_history()  # the compiled kernel's records are the same arrays


def auto_left(g):
    return g.members[0].full_steps_left


def set_auto_left(g, value):
    g.members[0].full_steps_left = value


def contraction(g):
    return g.members[0].contraction


def set_contraction(g, value):
    g.members[0].contraction = value


def count(g, counter, amount):
    for m in g.members:
        m.counters[counter] += amount
    return int(g.members[0].counters[counter])


def time(g):
    return g.members[0].t


def last_step(g):
    return g.members[0].last_h or 0.0


def record_residual(g, value):
    for m in g.members:
        m.last_residual = value


def record_stop(g, h):
    g.stopped = h


def place_ends(g, k, j, h):
    """Every string's prescribed ends where their paths have them at the end of an attempt of h [s]."""
    for m in g.members:
        m.targets = m.ends_at(m.t + h)
    return True


def reactions(g, forces, k):
    forces[k] = g.reactions()
    return 0
