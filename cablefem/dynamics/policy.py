"""The Newton policy of a time step, written once: Newton's iterations with the residual line search
and the branch corrections, the retries of an attempt, the halving and growth of steps.

The functions here are plain Python in numba's subset and are never called from this module:
``bind(ops)`` makes a set of them whose calls into the physics go to an ``ops`` module. Two such
sets run the solver (docs/architecture.md, "The compiled path"):

- ``cablefem.compiled.steps`` binds them to the compiled ops (``line_ops``, ``group_ops``) and compiles
  them with numba (the BDF2 and generalised-alpha steps of a line on the compiled kernel, many steps in
  one call);
- ``cablefem.dynamics.integrator`` binds them to Python ops (``cablefem.dynamics.python_ops``) for any integrator and
  either assembly (the compiled kernel per evaluation, or the numpy loads).

A change to the policy is a change to this file, and both paths have it; ``tests/test_march.py``
holds them equal (the same iterations, halvings and numbers to round-off). ``prob`` is whatever
the ops take (a named tuple of arrays when compiled, the integrator in Python); the policy reads
only ``prob.settings`` (a ``Settings``) and calls ops for everything else:

    evaluate(prob, tangent, held) -> int   the step residual (and tangent) at the trial positions,
                                           on the held branches; != 0: the seabed walk lost a point
    norm(prob) -> float                    its relative residual on the free rows
    increment(prob, refactor) -> float     the Newton step into the step buffer (fresh LU factors
                                           or the kept ones); its largest entry, NaN when singular
    factors_current(prob), forget_factors(prob)   modified Newton's kept factors
    take_step(prob, fraction)              trial = base + fraction step
    set_base(prob)                         base = trial, and its branch state for the holds
    restore_base(prob)                     trial = base
    hold(prob, again) -> bool              hold the branches the trial reached (``kernels.hold_points``)
    save_original(prob), restore_original(prob) -> float   Newton's own step around corrections
    finish(prob) -> int                    the rows the reactions need at a converged point
    error(prob) -> float                   the converged trial's local error in tension relative to
                                           the largest tension (the scheme's ``error``; < 0: none)
    last_error(prob), record_error(prob, e)   that error, kept for ``advance``
    proposal(prob), set_proposal(prob, h)  the next step the error control proposes (0: none yet)
    begin(prob, h), restart(prob), accept(prob, h)   the scheme: predictor, guess, state update
    auto_left(prob) -> float, set_auto_left(prob, value)   "auto" Newton's full-Newton attempts
    contraction(prob) -> float, set_contraction(prob, value)   the kept factors' contraction of the
                                           residual, theta (< 0: not known), carried across steps
    count(prob, counter, amount), time(prob), last_step(prob), record_residual(prob, norm)
    attempt(prob, h) -> int                ``attempt`` below, bound to the same ops (the Python ops
                                           go through the integrator, where it can be watched)
    place_ends(prob, k, j, h) -> bool      the prescribed ends at the end of the attempt of h that
                                           ends at the j-th of ``settings.parts`` parts of step k;
                                           False if this path cannot place them there
    record_stop(prob, h)
    reactions(prob, forces, k) -> int      the line's forces on fairlead and anchor after step k into
                                           forces[k]; != 0: the seabed walk lost a point
"""

import math
from collections import namedtuple
from types import FunctionType

import numpy as np

#: counters (``count``): steps, Newton iterations, residual evaluations, tangents, LU factorisations,
#: failed attempts, branch corrections
STEPS, ITERATIONS, NFEV, NJEV, NLU, REJECTED, CORRECTIONS = 0, 1, 2, 3, 4, 5, 6
COUNTERS = ("steps", "newton_iterations", "nfev", "njev", "nlu", "rejected", "corrections")
#: what ``newton`` and ``attempt`` return (``attempt``: INACCURATE, converged but its local error above
#: the tolerance of adaptive steps)
CONVERGED, DIVERGED, LOST, INACCURATE = 0, 1, 2, 3
#: what ``advance`` and ``steps`` return: all taken; Newton failed with the step at its smallest;
#: an attempt would end where this path cannot place the fairlead; the seabed walk lost a point;
#: (``steps`` only) the step was taken but the walk lost a point in evaluating its reactions
DONE, FAILED, SPLIT, PROJECTION, REACTIONS = 0, 1, 2, 3, 4
#: ``Settings.newton``: full Newton, modified (factors kept), "auto" (modified, full after trouble)
FULL, MODIFIED, SWITCHING = 0, 1, 2

#: tolerance: relative residual; increment_tolerance [m]; max_iterations of Newton; growth: the
#: largest ratio of a step to the last; newton (FULL, MODIFIED, SWITCHING); contraction above which
#: modified Newton rebuilds its factors; min_damping of the line search; min_dt [s]; auto_full_steps:
#: full-Newton attempts after trouble; stretch: a step stretches by this fraction rather than leave a
#: sliver; max_corrections of a Newton step on new branches; parts: the splits of a step at which
#: ``place_ends`` can place the prescribed ends (0: anywhere); adaptive (1: steps from the error
#: control, 0: fixed), error_tolerance (the local tension error a step may make, relative to the
#: largest tension) and max_step [s] of adaptive steps
#: the ops a bound set calls (``bind``)
ops = None
#: False and True, and small whole numbers, as run-time values for the ops' arguments: numba compiles
#: a callee once more for every literal argument (``evaluate(prob, True, False)`` was compiled four
#: times, each with the whole kernel, and the first run's compilation took 2.5 min instead of ~1)
FLAG = np.array([False, True])
NUMBER = np.arange(8)

#: the least contraction modified Newton's first-iteration stop assumes (``newton``): a smaller ratio
#: of residuals is round-off's as much as the factors' (a residual 1e-2 of the last one and below
#: differs between two orders of the same arithmetic by more than the decisions it feeds can bear:
#: the compiled and Python steps took different iterations on a snap case, tests/test_march.py)
THETA_FLOOR = 1e-2
#: the first-iteration stop asks the predicted residual to be below this fraction of the tolerance:
#: the prediction is an estimate (Hairer & Wanner stop simplified Newton at kappa Tol, kappa 1e-2 to
#: 1e-1, for the same reason); a contact switching in the step makes the true ratio up to ~3.5x the
#: one predicted. Measured with the residual evaluated after every stop (generalised-alpha 0.7, P1 x
#: 80, tolerance 1e-3, scratch of tests/test_march_alpha.py): on the aligned slow surge (dt 0.0125
#: s, 20 s) with 1 it ended above the tolerance after 2 of 1014 stops (1.14x at most), with 0.5
#: after 2 of 820 (1.26x), with 0.25 after none of 673 (0.74x at most); on the flume's slow surge
#: with friction, 13 of 1007 (2.37x), 1 of 837 (1.31x), none of 652 (0.65x); on the snap with
#: friction (dt 0.005 s) none of 637 at 0.25 (0.52x). tests/test_march_alpha.py holds 0.25
STOP_SAFETY = 0.25

#: a step's clock (one record, per string): t [s], the step before (0 before the first), the last step
#: (0 if none), the attempt that stopped a run, the last attempt's final relative residual, the
#: attempt's factors (v_x, a_x, g_x) with d(X, V, A)/dX_{n+1} = g_x (1, v_x, a_x), its size h [s] and
#: the time t_eval [s] at which the scheme evaluates the loads; the last converged attempt's local
#: error (relative tension, < 0: none), the step the error control proposes next [s] (0: none yet),
#: the least tension the error is relative to [N] (the line's largest at the start) and the time [s]
#: of the last accepted step's balance (its t_eval; NaN before the first: ``balance_rows``)
CLOCK = np.dtype([("t", "f8"), ("h_before", "f8"), ("last_h", "f8"), ("stopped", "f8"), ("residual", "f8"),
                  ("v_x", "f8"), ("a_x", "f8"), ("g_x", "f8"), ("h", "f8"), ("t_eval", "f8"), ("error", "f8"),
                  ("proposal", "f8"), ("tension_scale", "f8"), ("t_balance", "f8")])


def balance_lag(t, t_eval, t_balance):
    """The factor c of the reported end forces F(t) = F_b + c (F_b - F_b') of a scheme that balances the
    loads before the state's time t (generalised-alpha at t_eval = t_{n+1-alpha_f}): the line through
    the last two balances, F_b at t_eval and F_b' at t_balance, carried on to t; 0 where the balance is
    the state's (BDF2) or there is no earlier one. Second order, where the balance alone lags by
    t - t_eval (first order)."""
    if t_eval == t or not t_balance < t_eval:  # (NaN: no balance before)
        return 0.0
    return (t - t_eval) / (t_eval - t_balance)
#: what modified Newton's kept factors belong to (one record, kept between runs): the v_x of the
#: factors (NaN: none; a_x and g_x follow from it), "auto"'s full-Newton attempts still to run and the
#: kept factors' contraction of the residual (< 0: not known)
FACTORS = np.dtype([("v_x", "f8"), ("auto_left", "f8"), ("contraction", "f8")])

Settings = namedtuple("Settings", "tolerance increment_tolerance max_iterations growth newton contraction "
                                  "min_damping min_dt auto_full_steps stretch max_corrections parts adaptive "
                                  "error_tolerance max_step")


def newton(prob, reuse, max_corrections):
    """Newton on the step residual from the trial positions (updated in place): full (a fresh
    tangent each iteration) or, with ``reuse``, modified (LU factors kept across iterations and
    steps, rebuilt when the iteration contracts slower than ``settings.contraction``). Returns
    (outcome, refreshed: kept factors were rebuilt for slow contraction, the last relative residual).

    An iteration converges when the residual is below the tolerance or when the increment,
    extrapolated by the observed contraction (rho / (1 - rho), Hairer & Wanner IV.8), is below the
    increment tolerance. With kept factors, the first iteration of a step may stop without the
    residual at its end: the factors' contraction of the residual, theta = |r_1| / |r_0|, seen the
    last time a second residual was evaluated with them and carried across steps, predicts
    |r_1| ~ theta |r_0| (theta >= ``THETA_FLOOR``); below ``STOP_SAFETY`` times the tolerance, the
    step is converged. As Hairer & Wanner's stopping criterion of simplified Newton (IV.8, in
    RADAU5) starts a step from max(eta_old, uround)^0.8, theta grows to theta^0.8 with every step
    that stops so, until a residual is evaluated again and measures it. Only a step solved with
    kept factors measures it (right after new ones the ratio is exact Newton's, often at the floor,
    and predicted a tenth of the next step's); new factors forget it, and so does a step that did
    not reduce the residual. The guarantee is measured, not proven: see ``STOP_SAFETY``.
    When the last residual was below sqrt(tolerance), so that this one should
    converge, the residual is evaluated alone and the tangent only if it has not; a point reached
    by a damped step is evaluated without a tangent too (regimes switching: its full step is mostly
    rejected). A Newton step that does not reduce the residual norm (Armijo, Kelley 2003 Sec. 8.1)
    is halved, down to ``settings.min_damping``: seabed friction and contact switch between regimes,
    and undamped Newton cycles between two states. Most rejections are a branch switch the tangent
    at the base cannot see (friction's ramp, a slack element pulled taut, a point put on the seabed
    or lifted off): before halving a rejected full step, it is solved again from its base with the
    points held on the branches the trial reached (``hold``: the semismooth step on those branches),
    up to ``max_corrections`` times, each facing the same test against the true residual; if none
    passes, the line search halves Newton's own step."""
    settings = prob.settings
    tolerance = settings.tolerance
    fresh = not reuse or not ops.factors_current(prob)
    # kept factors: their contraction of the residual in earlier steps, grown (see above), predicts
    # the residual after the first iteration
    kept = ops.contraction(prob) if reuse and not fresh else -1.0
    if kept >= 0.0:
        kept = kept ** 0.8
    previous, refreshed, norm = -1.0, False, math.inf  # no increment yet
    base_norm, damping = -1.0, 1.0  # base_norm < 0: no step taken yet
    damped = False  # the step taken started from a point a damped step reached
    corrections = 0  # of the step from the base
    kept_step = False  # the step taken was solved with kept factors (not new ones)
    for _ in range(int(settings.max_iterations)):
        with_tangent = fresh and damping == 1.0 and not damped and (
            base_norm < 0.0 or base_norm > math.sqrt(tolerance))
        if ops.evaluate(prob, with_tangent, FLAG[0]) != 0:
            return LOST, refreshed, norm
        norm = ops.norm(prob)
        reduced = norm <= (1 - 1e-4 * damping) * base_norm  # Armijo's test of the step taken
        if kept_step and damping == 1.0 and not damped and corrections == 0:
            # the kept factors' contraction, seen in the residual (none if the step did not reduce it)
            ops.set_contraction(prob, max(norm / base_norm, THETA_FLOOR) if reduced else -1.0)
        if norm <= tolerance and previous >= 0.0:
            return CONVERGED, refreshed, norm
        if base_norm >= 0.0 and damping > settings.min_damping and not reduced:
            if damping == 1.0 and corrections < max_corrections and fresh and ops.hold(prob, corrections > 0):
                if corrections == 0:
                    ops.save_original(prob)
                corrections += 1
                ops.count(prob, NUMBER[CORRECTIONS], NUMBER[1])
                ops.restore_base(prob)
                ops.evaluate(prob, FLAG[1], FLAG[1])  # Newton again from the base on the new branches
                size = ops.increment(prob, FLAG[1])
                if not math.isfinite(size):
                    break
                ops.set_contraction(prob, -1.0)  # new factors
                kept_step = False
                ops.take_step(prob, 1.0)
                ops.count(prob, NUMBER[ITERATIONS], NUMBER[1])
                previous = size
                continue
            if damping == 1.0 and corrections > 0:  # no correction passed: the line search halves Newton's step
                previous = ops.restore_original(prob)
            damping *= 0.5
            ops.restore_base(prob)
            ops.take_step(prob, damping)
            continue
        if not math.isfinite(norm):
            break
        if fresh and not with_tangent:  # the same point again, with the tangent
            ops.evaluate(prob, FLAG[1], FLAG[0])
        size = ops.increment(prob, fresh)
        if not math.isfinite(size):
            break
        if fresh:
            ops.set_contraction(prob, -1.0)  # new factors: their contraction is not known yet
        kept_step = not fresh
        ops.set_base(prob)
        base_norm, damping, damped = norm, 1.0, damping < 1.0
        corrections = 0
        ops.take_step(prob, 1.0)
        ops.count(prob, NUMBER[ITERATIONS], NUMBER[1])
        rho = size / previous if previous > 0.0 else -1.0
        first = not fresh and previous < 0.0 and 0.0 <= kept < 1.0 and kept * norm <= STOP_SAFETY * tolerance
        # (the first-iteration stop: kept * norm predicts the residual at the new trial point)
        if (fresh and size <= settings.increment_tolerance) or first or (
                0.0 <= rho < 1.0 and size * rho / (1 - rho) <= settings.increment_tolerance):
            if first:
                ops.set_contraction(prob, kept)
            if ops.finish(prob) != 0:
                return LOST, refreshed, norm
            return CONVERGED, refreshed, norm
        fresh = not reuse or rho > settings.contraction
        refreshed = refreshed or (reuse and fresh)
        previous = size
    ops.forget_factors(prob)
    return DIVERGED, refreshed, norm


def attempt(prob, h):
    """One step of size h from the current state (``ops.begin``: the scheme's coefficients and
    predictor): Newton, full or modified as ``settings.newton`` says ("auto": modified until a
    step's kept factors have to be rebuilt or the step fails, then full Newton for the next
    ``settings.auto_full_steps`` attempts); an attempt whose modified Newton fails is redone from
    its start with a fresh tangent ("auto": in full Newton), one that failed with branch
    corrections is tried once more without. With adaptive steps, a converged attempt whose local
    error (``ops.error``) is above ``settings.error_tolerance`` is INACCURATE (unless half of it is
    below ``min_dt``). On CONVERGED the state moves on to t + h."""
    settings = prob.settings
    mode = settings.newton
    ops.begin(prob, h)
    reuse = mode == MODIFIED or (mode == SWITCHING and ops.auto_left(prob) <= 0.0)
    ops.restart(prob)
    corrected = ops.count(prob, NUMBER[CORRECTIONS], NUMBER[0])
    outcome, trouble, last = newton(prob, reuse, settings.max_corrections)
    if reuse and outcome == DIVERGED:  # once more from the start: modified with a fresh tangent, or full
        trouble = True
        ops.restart(prob)
        outcome, _, last = newton(prob, mode == MODIFIED, settings.max_corrections)
    if outcome == DIVERGED and ops.count(prob, NUMBER[CORRECTIONS], NUMBER[0]) > corrected:  # corrected and failed: once more without
        ops.restart(prob)
        ops.forget_factors(prob)
        outcome, _, last = newton(prob, mode == MODIFIED, NUMBER[0])
    ops.record_residual(prob, last)
    if mode == SWITCHING and outcome != LOST:
        if reuse and trouble:
            ops.set_auto_left(prob, settings.auto_full_steps)
        elif not reuse:
            ops.set_auto_left(prob, ops.auto_left(prob) - 1.0)
    if outcome == CONVERGED and settings.adaptive > 0.0:
        error = ops.error(prob)
        ops.record_error(prob, error)
        if error > settings.error_tolerance and 0.5 * h >= settings.min_dt:
            return INACCURATE
    if outcome == CONVERGED:
        ops.accept(prob, h)
    return outcome


def advance(prob, k, target, first):
    """Step k of a run: advance exactly by ``target`` [s], in attempts that are halved when Newton
    fails (down to ``settings.min_dt``), never longer than ``settings.growth`` times the last step
    (variable-step BDF2 is zero-stable below 1 + sqrt(2), Grigorieff 1983) and never leaving a
    sliver of less than ``settings.stretch`` of an attempt to the end; ``first``: the first
    attempt's size (0: target), when a longer one was seen to fail.

    With adaptive steps (``settings.adaptive``) the steps come from the error control, the one step
    control of fixed and adaptive runs alike: a step whose local tension error e (``ops.error``) is
    above the tolerance tol is rejected and tried again at h max(0.2, 0.9 (tol / e)^(1/3)) (the
    error is O(h^3) for the second-order schemes); an accepted one proposes the next, h min(2,
    max(0.5, 0.9 (tol / e)^(1/3))), at most ``settings.max_step``, kept across calls
    (``ops.proposal``), and right after a rejected attempt (inaccurate or failed) no longer than
    itself; a step shortened to land on ``target`` or on a split only grows it, and what is left to
    ``target`` under twice the step is taken in two even steps. Where ``parts`` > 0
    (the compiled steps, which know the prescribed ends at ``parts`` splits of the target) a step
    ends on a split: an adaptive one is cut back to the split before it.

    Returns DONE, FAILED (a halving, or an inaccurate step's reduction, would go below ``min_dt``), SPLIT (the ends cannot be placed
    where an attempt would end: ``place_ends``) or PROJECTION; the size of the attempt that stopped
    is recorded."""
    settings = prob.settings
    adaptive = settings.adaptive > 0.0
    done, h = 0.0, first if first > 0.0 else target
    if adaptive and first <= 0.0 and ops.proposal(prob) > 0.0:
        h = ops.proposal(prob)
    parts = settings.parts
    rejected = False  # since the last accepted step
    while target - done > 1e-9 * target:
        remaining = target - done
        h = min(h, remaining)
        if ops.last_step(prob) > 0.0:
            h = min(h, settings.growth * ops.last_step(prob))
        if adaptive and h < remaining < 2.0 * h:  # two even steps to the end, not a step and a sliver
            h = 0.5 * remaining
        if remaining - h <= settings.stretch * h:  # land on the end, never leave a sliver of it
            h = remaining
        planned = h
        j = parts
        if parts > 0:
            share = (done + h) / target * parts  # where the attempt ends, in 1/parts of the step
            j = int(round(share))
            if adaptive and abs(share - j) > 1e-6:  # cut back to the split before
                j = int(math.floor(share + 1e-6))
                h = j * target / parts - done
            if abs((done + h) / target * parts - j) > 1e-6 or j < 1 or h <= 0.0:
                ops.record_stop(prob, planned)
                return SPLIT
        if not ops.place_ends(prob, k, j, h):
            ops.record_stop(prob, h)
            return SPLIT
        outcome = ops.attempt(prob, h)
        if outcome == LOST:
            ops.record_stop(prob, h)
            return PROJECTION
        if outcome == DIVERGED:
            ops.count(prob, NUMBER[REJECTED], NUMBER[1])
            if 0.5 * h < settings.min_dt:
                ops.record_stop(prob, h)
                return FAILED
            h *= 0.5
            rejected = True
            continue
        if outcome == INACCURATE:  # converged, its error too large: smaller, as the error says
            ops.count(prob, NUMBER[REJECTED], NUMBER[1])
            rejected = True
            smaller = h * max(0.2, 0.9 * (settings.error_tolerance / ops.last_error(prob)) ** (1.0 / 3.0))
            if smaller < settings.min_dt:  # the error does not fall with the step: stop, as a halving does
                ops.record_stop(prob, h)
                return FAILED
            h = smaller
            ops.set_proposal(prob, h)
            continue
        ops.count(prob, NUMBER[STEPS], NUMBER[1])
        done += h
        if adaptive:
            error = ops.last_error(prob)
            if error >= 0.0:  # propose the next; a step cut to land on the end or a split only grows it
                factor = 0.9 * (settings.error_tolerance / error) ** (1.0 / 3.0) if error > 0.0 else 2.0
                # no growth right after a rejection (Hairer, Norsett & Wanner II.4): it would be rejected again
                proposal = min(settings.max_step, h * min(1.0 if rejected else 2.0, max(0.5, factor)))
                if rejected or h >= ops.proposal(prob) * (1 - 1e-12) or proposal > ops.proposal(prob):
                    ops.set_proposal(prob, proposal)
            rejected = False
            h = ops.proposal(prob) if ops.proposal(prob) > 0.0 else target
        else:
            h = target
    return DONE


def steps(prob, times, forces):
    """Steps to ``times`` (m,) in turn (``advance``), the line's forces on fairlead and anchor after
    each into ``forces`` (m, 2, 3) (``ops.reactions``). Returns (status, k): DONE with k = m, the
    status of step k, which stopped, or REACTIONS: step k was taken, its forces were not found."""
    for k in range(times.shape[0]):
        status = advance(prob, k, times[k] - ops.time(prob), 0.0)
        if status != DONE:
            return status, k
        if ops.reactions(prob, forces, k) != 0:
            return REACTIONS, k
    return DONE, times.shape[0]


FUNCTIONS = ("newton", "attempt", "advance", "steps")


def bind(ops_module, compile=None, name="", link=None):
    """The policy's functions (a dict by name) calling ``ops_module``; ``compile``: a decorator to
    apply to each (numba's njit), with ``name`` prefixed to their qualified names so that each
    compiled set has its own on-disk cache; ``link(name, function)``: what the functions after it
    call in place of each (the compiled steps call their layers by address,
    ``cablefem.compiled.calls``), by default the function itself."""
    namespace = dict(globals())
    namespace["ops"] = ops_module
    bound = {}
    for function_name in FUNCTIONS:
        original = globals()[function_name]
        function = FunctionType(original.__code__, namespace, function_name, original.__defaults__)
        function.__qualname__ = f"{name}.{function_name}" if name else function_name
        function.__doc__ = original.__doc__
        bound[function_name] = compile(function) if compile else function
        namespace[function_name] = link(function_name, bound[function_name]) if link else bound[function_name]
    return bound
