"""The adaptive step control's sequence of steps (``policy.advance``), on stub ops whose attempts
converge or fail by rule: two even steps to an output time rather than a step and a sliver, and no
growth right after a rejected attempt (Hairer, Norsett & Wanner II.4). Both faces of the steps run
this one function (``policy.bind``), so the rules hold compiled too."""

import sys
import types

import numpy as np
import pytest

from cablefem.dynamics import policy

TOLERANCE = 1e-2


def stub_ops(rule):
    """An ops module for ``policy.advance`` whose ``attempt(prob, h)`` returns ``rule(t, h)``'s
    (outcome, local error) and moves the clock on CONVERGED; ``prob.attempts`` logs (t, h, outcome)."""
    ops = types.ModuleType("stub_ops")

    def attempt(prob, h):
        outcome, error = rule(prob.t, h)
        prob.attempts.append((prob.t, h, outcome))
        if outcome == policy.CONVERGED:
            prob.error = error
            prob.t += h
            prob.last = h
        elif outcome == policy.INACCURATE:
            prob.error = error
        return outcome

    ops.attempt = attempt
    ops.proposal = lambda prob: prob.proposal
    ops.set_proposal = lambda prob, h: setattr(prob, "proposal", h)
    ops.last_step = lambda prob: prob.last
    ops.last_error = lambda prob: prob.error
    ops.place_ends = lambda prob, k, j, h: True
    ops.record_stop = lambda prob, h: None
    ops.count = lambda prob, counter, amount: 0
    ops.time = lambda prob: prob.t
    return ops


def problem(max_step):
    settings = policy.Settings(1e-8, 1e-9, 12, 2.0, policy.FULL, 0.3, 1 / 16, 1e-6, 20.0, 1e-3, 2, 0, 1.0,
                               TOLERANCE, max_step)
    return types.SimpleNamespace(settings=settings, t=0.0, last=0.0, error=-1.0, proposal=max_step, attempts=[])


def advance(rule, prob, targets):
    bound = policy.bind(stub_ops(rule))
    for k, target in enumerate(targets):
        assert bound["advance"](prob, k, target - prob.t, 0.0) == policy.DONE
    return [(t, h, outcome) for t, h, outcome in prob.attempts]


def test_steps_end_on_an_output_time_in_two_even_steps_not_a_sliver():
    """Steps of 0.3 s (the largest, the error far below its tolerance) to an output time 1 s away:
    0.3, 0.3, then the 0.4 s left in two steps of 0.2 s (a step of 0.3 and a sliver of 0.1 tied the
    next interval's first step to twice the sliver: OC4's chains took 2-3 extra steps a second)."""
    prob = problem(0.3)
    attempts = advance(lambda t, h: (policy.CONVERGED, 1e-6), prob, [1.0])
    assert [h for _, h, _ in attempts] == pytest.approx([0.3, 0.3, 0.2, 0.2])
    attempts = advance(lambda t, h: (policy.CONVERGED, 1e-6), prob, [2.0])
    assert min(h for _, h, _ in attempts[4:]) >= 0.2 - 1e-12


def test_no_step_grows_right_after_a_rejected_attempt():
    """Newton fails above 0.2 s between t = 1 and 3 s, with errors far below the tolerance: the
    error alone would double the step after each halving and fail again (OC4's line 2 in its slack
    phase, BDF2 at h = 0.5 s, 0.25 s, 0.5 s, ...). After a rejected attempt, the next proposal is at
    most the accepted step."""
    def rule(t, h):
        return (policy.DIVERGED if 1.0 <= t < 3.0 and h > 0.2 else policy.CONVERGED), 1e-6

    prob = problem(0.5)
    attempts = advance(rule, prob, np.arange(1.0, 5.0))
    failed = [k for k, (_, _, outcome) in enumerate(attempts) if outcome == policy.DIVERGED]
    assert failed
    for k in failed:
        accepted = next(j for j in range(k + 1, len(attempts)) if attempts[j][2] == policy.CONVERGED)
        if accepted + 1 < len(attempts):
            assert attempts[accepted + 1][1] <= attempts[accepted][1] * (1 + 1e-12), attempts[k:accepted + 2]
    # where Newton converges again the steps grow past where it failed
    assert max(h for t, h, _ in attempts if t >= 3.0) > 0.2 * 1.5


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-q"]))
