"""The Newton policy's ops in Python (``cablefem.dynamics.policy``): ``prob`` is an ``Integrator``.

They evaluate through the integrator: the compiled kernel per evaluation with its banded LU
(``cablefem.compiled.evaluator``), or the numpy loads and a sparse LU (``compiled=False``, a lumped mass), at
the evaluation point of the integrator's scheme (``Integrator.point``). The same policy bound to
``cablefem.compiled.steps``'s compiled ops runs BDF2 and generalised-alpha steps in numba; the two give the
same numbers.
"""

import numpy as np

from cablefem.dynamics import policy


def evaluate(prob, tangent, held):
    X, V, A = prob.point(prob.X1)
    prob.rows, prob.tangent = prob.rows_and_tangent(X, V, A, prob.t_eval, prob.factors[0], prob.factors[1],
                                                    tangent, held)
    return 0


def finish(prob):
    """The rows at a point Newton accepted without evaluating it: for the reactions at the state
    (BDF2) and for the history the loads commit; neither needed (generalised-alpha's reactions
    evaluate at the state, ``GeneralizedAlpha.accept``), nothing is evaluated."""
    if not prob.rows_at_state and not prob.system.kept_history():
        return 0
    return evaluate(prob, False, False)


def norm(prob):
    return float(np.linalg.norm(prob.rows[prob.fem.free_dofs]) / prob.scale)


def increment(prob, refactor):
    """The Newton step (N_free, 3) into ``prob.newton_step``; its largest entry, NaN when the tangent
    is singular or the step not finite."""
    step = prob.increment(prob.tangent, prob.rows, refactor)
    if step is None:
        return float("nan")
    prob.newton_step = step
    return float(np.max(np.abs(step), initial=0.0))  # 0: a line with no unknowns


def factors_current(prob):
    return prob.lu is not None and prob.lu_factors == prob.factors


def forget_factors(prob):
    prob.lu = None


def take_step(prob, fraction):
    X1 = prob.base.copy()
    X1[prob.fem.free_dofs] += fraction * prob.newton_step
    prob.X1 = X1


def set_base(prob):
    prob.base = prob.X1
    prob.evaluator.keep()


def restore_base(prob):
    prob.X1 = prob.base.copy()


def hold(prob, again):
    """The branch holds of the evaluator (the compiled kernel's per-point state; none with the numpy loads)."""
    return prob.evaluator.hold(again)


def save_original(prob):
    prob.original_step = prob.newton_step


def restore_original(prob):
    prob.newton_step = prob.original_step
    return float(np.max(np.abs(prob.original_step)))


def attempt(prob, h):
    """The integrator's ``attempt`` (the policy's, on these ops)."""
    return policy.CONVERGED if prob.attempt(h) else policy.DIVERGED


def begin(prob, h):
    prob.begin(h)


def restart(prob):
    prob.X1 = prob.guess.copy()


def accept(prob, h):
    prob.accept(h)
    prob.system.commit_history()  # the compiled kernel's records are the same arrays


def auto_left(prob):
    return prob.full_steps_left


def set_auto_left(prob, value):
    prob.full_steps_left = value


def contraction(prob):
    return prob.contraction


def set_contraction(prob, value):
    prob.contraction = value


def count(prob, counter, amount):
    prob.counters[counter] += amount
    return int(prob.counters[counter])


def time(prob):
    return prob.t


def last_step(prob):
    return prob.last_h or 0.0


def record_residual(prob, value):
    prob.last_residual = value


def record_stop(prob, h):
    prob.stopped = h


def place_ends(prob, k, j, h):
    """The prescribed ends where their paths have them at the end of an attempt of h [s]."""
    prob.targets = prob.ends_at(prob.t + h)
    return True


def reactions(prob, forces, k):
    forces[k] = prob.reactions()
    return 0
