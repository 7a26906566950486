"""What a time integrator (a scheme) is: one file, one registry entry (``cablefem.dynamics.registry``).

The semi-discrete equation of motion (desire2023 Eq. 1 after the FEM in s) is M A + G(X, V, A, t) = 0.
A scheme writes the positions X_{n+1} as the unknown of a step and the point where the loads are
evaluated, (X, V, A), as affine functions of it, so that Newton's tangent is

    g_x (K + v_x C + a_x (M + added mass)),   d(X, V, A)/dX_{n+1} = g_x (1, v_x, a_x).

Everything else (Newton, the line search, branch corrections, retries, halving and growth, for a
line alone and for strings that meet at junctions, on the numpy and the compiled face) is shared
(``cablefem.dynamics.policy``). A scheme's module holds its arithmetic once, as compiled functions
in numba's subset that both faces call, and its ``Integrator`` subclass naming it:

    PARAMETERS     the dtype of its record of parameters (one record per run)
    MEMORY         how many (N, 3) rows of earlier steps it keeps (``memory``, (MEMORY, N, 3))
    ROWS_AT_STATE  whether the end forces of an accepted step are its rows at the converged point,
                   where the scheme balances the loads (BDF2: the state; generalised-alpha:
                   t_{n+1-alpha_f}, carried on to t_{n+1} through the last two balances:
                   ``policy.balance_lag``), or are evaluated again at the state after the step
    begin(scheme, clock, X, V, A, memory, guess, h)
                   a step of h from the state: clock.v_x, a_x, g_x, h, t_eval, and the predictor
                   into ``guess`` (the prescribed ends are put there afterwards)
    point(scheme, clock, X, V, A, memory, X1, Xe, Ve, Ae)
                   the evaluation point (Xe, Ve, Ae) of the trial positions X1
    accept(scheme, clock, X, V, A, memory, X1)
                   the state (and memory) at t + h from the converged X1, in place
    error(scheme, clock, X, V, A, memory, X1, guess, out) -> bool
                   a solution of lower order at the converged trial X1 into ``out`` (its difference
                   from X1 is the step's local error, which the adaptive step control holds to a
                   tolerance in tension), from the step's predictor ``guess``; False where the
                   scheme has none for this step

``scheme`` is the one-record array of PARAMETERS, ``clock`` the one-record array of
``policy.CLOCK``; X, V, A, X1, guess, Xe, Ve, Ae are (N, 3). The compiled steps bind the shared
policy and ops to these functions (``cablefem.compiled.steps.bound``), so a new scheme runs compiled
too, without an edit elsewhere (tests/toy_integrator.py).
"""

from collections import namedtuple

#: a scheme: its name (the registry's key), PARAMETERS, MEMORY, ROWS_AT_STATE and its compiled
#: begin, point, accept and error
Scheme = namedtuple("Scheme", "name parameters memory rows_at_state begin point accept error")
