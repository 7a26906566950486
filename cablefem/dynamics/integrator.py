"""The integrator of one line: its state, boundary, evaluator and counters, and the scheme's Python face.

The semi-discrete equation of motion (desire2023 Eq. 1 after the FEM in s) is

    M A + G(X, V, A, t) = 0,

with M the consistent (or lumped) mass and G the loads. The anchor row is fixed and the fairlead
row follows its prescribed motion (an end that is not prescribed, ``Line.prescribed``, is an
unknown). A scheme (``cablefem.dynamics.scheme``: BDF2, generalised-alpha) writes X_{n+1} as the
unknown and the point where the loads are evaluated as affine functions of it, so that Newton's
tangent is g_x (K + v_x C + a_x M). ``Integrator`` is what every scheme shares; a scheme's file
subclasses it and names its arithmetic (``scheme``), which this class calls for its Python face
and the compiled steps call for theirs.

Steps are taken by the line's ``Group`` (``cablefem.dynamics.group``): the Newton policy
(``cablefem.dynamics.policy``: iterations, line search, branch corrections, retries, halving and
growth), compiled where the line evaluates with the compiled kernel on a seabed projected in the
loop, on the Python ops (``cablefem.dynamics.python_ops``) elsewhere. A line whose end is a junction
steps in its junction's group. Like scipy.integrate's solvers, an integrator has a ``step()`` and
counters (``nfev`` residual evaluations, ``njev`` tangents, ``nlu`` factorisations,
``newton_iterations``, ``steps``, ``rejected``). A step that fails at ``min_dt`` raises a
``ConvergenceError`` with its residual.
"""

import numpy as np

from cablefem.dynamics import policy
from cablefem.errors import ConvergenceError
from cablefem.fem import clamp
from cablefem.fem.forms import mass_matrix


def _counter(index):
    """A property reading and writing ``counters[index]`` (``policy.COUNTERS``)."""
    return property(lambda self: int(self.counters[index]),
                    lambda self, value: self.counters.__setitem__(index, value))


class Integrator:
    """Common machinery: state, boundary rows, evaluator, counters and the scheme's Python face.

    system: a ``LineSystem``; X0, V0: (N, 3) initial state [m, m/s]; ``boundary(t)`` gives the
    fairlead's position, velocity and acceleration (3,) at time t, ``anchor(t)`` the anchor's (None:
    fixed where the line has it); an end that is not prescribed (``Line.prescribed``) is an unknown
    and its path is not used; dt [s]; tolerance: relative
    residual or relative increment, as in statics. ``compiled`` evaluates with ``cablefem.compiled.evaluator``
    (every load in the catalog has a compiled face); ``newton`` is "full", "modified" (LU factors
    kept across iterations and steps) or "auto": modified on the numpy path; with the compiled
    kernel modified Newton attempt by attempt until a step's kept factors have to be rebuilt (they
    contract slower than ``CONTRACTION``) or the step fails, then full Newton for the next
    ``AUTO_FULL_STEPS`` attempts. ``parameters``: the values of the scheme's record. Subclasses name
    the scheme (``scheme``, a ``cablefem.dynamics.scheme.Scheme``) and the [solver] keys it reads
    (``options``).
    """

    name = "integrator"
    scheme = None  # the ``Scheme`` of a subclass

    #: contraction factor of modified Newton above which the tangent is rebuilt
    CONTRACTION = 0.3
    #: "auto" Newton with the compiled kernel: attempts in full Newton after a modified one had
    #: to rebuild its factors or failed. Modified Newton saves the tangent and its LU where the
    #: tangent changes slowly (work-precision slow surge: 0.81x full Newton's time) and costs
    #: where friction, contact and slack switch (snap: 1.36x). With 20, against full Newton:
    #: coarse snap runs (dt 0.16 s) the same time, P2 x 40 snap at dt 0.04 s 1.01x, slow surge
    #: 0.83-0.88x, the scenes' defaults (P1 x 40, dt 0.01 s, tolerance 1e-8) 0.88x in snap and
    #: 0.64x in slow surge; with 5, slow surge 0.78x but snap 1.07-1.15x; switching only after
    #: failures (not rebuilds) cost coarse snap runs 10-13 %. A failed modified attempt is
    #: redone in full Newton: "auto" halves a step only where full Newton fails from its start
    AUTO_FULL_STEPS = 20
    #: smallest fraction of a Newton step the residual line search tries
    MIN_DAMPING = 1.0 / 16.0
    #: times a rejected full Newton step is solved again from its base with the friction,
    #: contact and tension branches its trial point reached (``policy.newton``; 0: never). Snap
    #: loads on the flume chain, P1 x 14 at dt 0.16 s: 13 failed attempts and 1306 evaluations
    #: without, none and 882 with (verification/work_precision/README.md)
    MAX_CORRECTIONS = 2
    #: largest ratio of a step to the one before: variable-step BDF2 is zero-stable for ratios
    #: below 1 + sqrt(2) (Grigorieff 1983); halved steps grow back by doubling
    MAX_GROWTH = 2.0
    #: a step stretches by up to this fraction rather than leave a sliver to the end of dt
    STRETCH = 1e-3

    def __init__(self, system, X0, boundary, V0=None, t0=0.0, dt=0.01, tolerance=1e-8,
                 max_iterations=12, lumped=False, min_dt=None, newton="auto", compiled=True, anchor=None,
                 parameters=None, adaptive=False, error_tolerance=3e-4):
        self.system = system
        fem = system.fem
        self.fem = fem
        self.boundary = boundary
        self.anchor_path = anchor
        self.t = float(t0)
        self.X = np.array(X0, dtype=float)
        self.V = np.zeros_like(self.X) if V0 is None else np.array(V0, dtype=float)
        self.dt = float(dt)
        self.min_dt = float(min_dt) if min_dt else self.dt / 1024.0
        self.tolerance = tolerance
        self.max_iterations = max_iterations
        self.length = system.line.unstretched_length
        self.end_points = system.points_at_ends  # a point's load rides on an end: ``reactions`` leave it out
        self.scale = float(np.linalg.norm(system.weight_vector()[fem.free_dofs])) or 1.0
        self.counters = np.zeros(len(policy.COUNTERS), dtype=np.int64)
        self.parameters = np.zeros(1, self.scheme.parameters)
        if parameters is not None:
            self.parameters[0] = tuple(parameters)
        self.clock = np.zeros(1, policy.CLOCK)
        self.clock["t"] = self.t
        # adaptive steps: the error control's tolerance and first step, at most dt (``policy.advance``)
        self.adaptive, self.error_tolerance = bool(adaptive), float(error_tolerance)
        self.clock["proposal"] = self.dt / 8 if self.adaptive else 0.0
        self.clock["tension_scale"] = self.largest_tension(self.X)
        self.clock["t_balance"] = np.nan
        # the last accepted step's rows at the fairlead and anchor where it balanced them, and what
        # ``reactions`` adds to them (``policy.balance_lag``), (2, 2, 3)
        self.balance_rows = np.zeros((2, 2, 3))
        self.memory = np.zeros((self.scheme.memory,) + self.X.shape)  # the scheme's rows of earlier steps
        self.group = None  # the ``Group`` that steps this line (a group of one, made on first use)
        self.last_h = None  # the last accepted step [s]
        self.balance = None  # (t, X, V, A, t_eval) of the last step's converged point, where not the state
        self.last_residual = float("nan")  # the final relative residual of the last failed attempt
        self.residual_rows = None  # M A + G at the current state, (N, 3); compiled steps may fill only
        # the anchor and fairlead rows (the reactions), leaving the others zero
        self.lu, self.lu_factors = None, None
        # the compiled kernel, or the numpy loads with their sparse LU (a lumped mass, compiled=False,
        # a line without unknowns)
        self.evaluator = system.evaluator(compiled, lumped)
        # "auto": full Newton where a tangent costs about a residual (fewer iterations win), else kept factors
        if newton not in ("auto", "full", "modified"):
            raise ValueError(f"newton must be auto, full or modified, got {newton!r}")
        self.newton_mode = {"full": policy.FULL, "modified": policy.MODIFIED}.get(
            newton, policy.SWITCHING if self.evaluator.full_newton_pays else policy.MODIFIED)
        if not fem.free_dofs.size:  # one element between prescribed ends: each step one evaluation
            self.newton_mode = policy.FULL
        self.full_steps_left = 0  # "auto": attempts still to run in full Newton
        self.contraction = -1.0  # the kept factors' contraction estimate (policy.newton), < 0: none
        # positions converge when the force their error makes, EA / h * dx, is below the
        # tolerance times the weight of an element: dx <= tol w h^2 / EA (floored at round-off)
        h = float(np.min(np.diff(fem.mesh.p[0])))
        weight = float(np.max(np.abs(system.weight.dry - system.weight.buoyancy)))
        extent = float(np.max(np.abs(self.X))) + self.length
        self.increment_tolerance = max(tolerance * weight * h * h / float(np.max(system.props["EA"])),
                                       1e3 * np.finfo(float).eps * extent)
        self.A = self.initial_acceleration()

    # ------------------------------------------------------------------ counters
    steps, newton_iterations, nfev, njev, nlu, rejected, corrections = map(_counter, range(len(policy.COUNTERS)))

    @property
    def settings(self):
        """The policy's ``Settings`` of the Python ops, from this integrator's attributes."""
        return self.make_settings(0)

    def make_settings(self, parts):
        """The policy's ``Settings`` from this integrator's attributes (``parts``: see ``policy``)."""
        return policy.Settings(self.tolerance, self.increment_tolerance, self.max_iterations, self.MAX_GROWTH,
                               self.newton_mode, self.CONTRACTION, self.MIN_DAMPING, self.min_dt,
                               float(self.AUTO_FULL_STEPS), self.STRETCH, self.MAX_CORRECTIONS, parts,
                               float(self.adaptive), self.error_tolerance, self.dt)

    # ------------------------------------------------------------ helpers
    def set_boundary(self, X, V, A, t):
        """Put the prescribed anchor and fairlead rows of X, V, A at their values at time t."""
        fem = self.fem
        if fem.prescribed[0]:
            if self.anchor_path is None:
                X[fem.anchor_dof] = self.system.line.anchor
                V[fem.anchor_dof] = 0.0
                A[fem.anchor_dof] = 0.0
            else:
                X[fem.anchor_dof], V[fem.anchor_dof], A[fem.anchor_dof] = self.anchor_path(t)
        if fem.prescribed[1]:
            X[fem.fairlead_dof], V[fem.fairlead_dof], A[fem.fairlead_dof] = self.boundary(t)

    def ends_at(self, t):
        """Positions (2, 3) of the anchor and the fairlead end where their paths have them at t."""
        anchor = self.system.line.anchor if self.anchor_path is None else self.anchor_path(t)[0]
        return np.array([anchor, self.boundary(t)[0]], dtype=float)

    def end_positions(self, times):
        """Positions (m, 2, 3) of the anchor and fairlead ends at ``times`` (m,)."""
        times = np.asarray(times, dtype=float)
        ends = np.empty((len(times), 2, 3))
        ends[:, 1] = self.fairlead_positions(times)
        if self.anchor_path is None:
            ends[:, 0] = self.system.line.anchor
        else:
            positions = getattr(self.anchor_path, "positions", None)
            ends[:, 0] = positions(times) if positions is not None else [self.anchor_path(t)[0] for t in times]
        return ends

    @property
    def M(self):
        """The mass matrix (N 3, N 3), CSR (``cablefem.fem.forms.mass_matrix``), assembled on first use."""
        return self.evaluator.M

    def inertia(self, A):
        """Rows (N, 3) of M A (zeros, without assembling M, at A = 0: a start at rest)."""
        return self.evaluator.inertia(A)

    def initial_acceleration(self):
        """A0 from (M + added mass) A0 = -G(X0, V0) on the free rows (zero at rest in equilibrium)."""
        fem, ev = self.fem, self.evaluator
        A = np.zeros_like(self.X)
        X, V = self.X.copy(), self.V.copy()
        self.set_boundary(X, V, A, self.t)
        rows, with_mass = ev.evaluate(X, V, A, 0.0, 1.0, t=self.t)
        if np.linalg.norm(rows[fem.free_dofs]) <= 1e-12 * self.scale:
            return A
        factors = ev.mass_factors(X, V, A, with_mass, self.t)
        if factors is None:
            raise ConvergenceError(f"{self.name}: the mass matrix is singular at t = {self.t:.6g} s "
                                   "(check the line's mass and added-mass coefficients)")
        A[fem.free_dofs] = ev.solve(factors, rows)
        return A

    # ------------------------------------------------------------ the policy's Python ops
    def rows_and_tangent(self, X, V, A, t, v_x, a_x, jacobian, held=False):
        """Rows M A + G (N, 3) at the evaluation point and, with ``jacobian``, the tangent of the
        loads and mass in the representation ``increment`` factors (``held``: held branches); the
        step's size h from the clock, for the loads whose history evolves in time (``loads.rope``)."""
        self.nfev += 1
        return self.evaluator.evaluate(X, V, A, v_x, a_x, jacobian, held, t, h=float(self.clock["h"][0]))

    def evaluate(self, X, V, A, t, v_x, a_x, jacobian=True, h=0.0):
        """Load residual rows and tangent blocks (the numpy loads) at an evaluation point of a step
        of h [s]."""
        self.nfev += 1
        state = self.system.state(X, V, A, t, inv_h=1.0 / h if h > 0.0 else 0.0)
        return self.system.evaluate(state, jacobian, v_x, a_x)

    def increment(self, tangent, rows, refactor):
        """The Newton increment (N_free, 3) for residual ``rows``, with ``refactor`` from fresh LU
        factors of ``tangent`` (counted, kept), else from the kept ones; None if the tangent is
        singular or the increment not finite."""
        if refactor:
            g_x = self.factors[2]
            self.njev += 1
            self.lu = self.evaluator.factorize(tangent, g_x)
            if self.lu is None:
                return None
            self.nlu += 1
            self.lu_factors = self.factors
        dX = self.solve(self.lu, rows)
        return dX if np.all(np.isfinite(dX)) else None

    def solve(self, factors, rows):
        """Newton increment (N_free, 3) of the free DOFs for residual rows (N, 3)."""
        return self.evaluator.solve(factors, rows)

    # --------------------------------------------------------------- the scheme, Python face
    def begin(self, h):
        """A step of h from the state (the scheme's ``begin``): the factors (v_x, a_x, g_x), the time
        of the loads ``t_eval``, and the predictor ``guess`` with the prescribed ends at
        ``self.targets``."""
        fem, clock = self.fem, self.clock
        clock["t"] = self.t
        guess = np.empty_like(self.X)
        self.scheme.begin(self.parameters, clock, self.X, self.V, self.A, self.memory, guess, h)
        if fem.prescribed[1]:
            guess[fem.fairlead_dof] = self.targets[1]
        if fem.prescribed[0]:
            guess[fem.anchor_dof] = self.targets[0]
        self.guess = guess
        self.factors = (float(clock["v_x"][0]), float(clock["a_x"][0]), float(clock["g_x"][0]))
        self.t_eval = float(clock["t_eval"][0])

    def point(self, X1):
        """The evaluation point (X, V, A), each (N, 3), of trial positions X1 (the scheme's ``point``)."""
        Xe, Ve, Ae = np.empty_like(X1), np.empty_like(X1), np.empty_like(X1)
        self.scheme.point(self.parameters, self.clock, self.X, self.V, self.A, self.memory, X1, Xe, Ve, Ae)
        return Xe, Ve, Ae

    def accept(self, h):
        """The state at t + h from the converged ``X1`` (the scheme's ``accept``)."""
        self.prediction = self.guess
        if self.system.clamps and self.scheme.rows_at_state and self.t_eval != self.t + h:
            # a balance off the state (generalised-alpha): ``clamp_moments`` reads the clamps' rows there
            self.balance = (self.t + h, *self.point(self.X1), self.t_eval)
        X, V, A, memory = self.X.copy(), self.V.copy(), self.A.copy(), self.memory.copy()
        self.scheme.accept(self.parameters, self.clock, X, V, A, memory, self.X1)
        self.X, self.V, self.A, self.memory = X, V, A, memory
        self.t, self.last_h = self.t + h, h
        self.clock["t"], self.clock["h_before"], self.clock["last_h"] = self.t, h, h
        # the rows of the converged point are where the scheme balances them (BDF2: the state), or the
        # reactions evaluate again at the state
        self.residual_rows = self.rows if self.scheme.rows_at_state else None
        if self.scheme.rows_at_state:
            ends = self.rows[[self.fem.fairlead_dof, self.fem.anchor_dof]]
            lag = policy.balance_lag(self.t, self.t_eval, float(self.clock["t_balance"][0]))
            self.balance_rows = np.stack([ends, lag * (ends - self.balance_rows[0]) if lag != 0.0 else np.zeros((2, 3))])
            self.clock["t_balance"] = self.t_eval

    def error(self):
        """The local tension error of the converged trial ``X1`` relative to the largest tension
        (``tension_error`` of the scheme's solution of lower order), or -1 where the scheme has none."""
        low = np.empty_like(self.X1)
        if not self.scheme.error(self.parameters, self.clock, self.X, self.V, self.A, self.memory, self.X1,
                                 self.guess, low):
            return -1.0
        return self.tension_error(low, self.X1)

    @staticmethod
    def options(solver):
        """The scheme's keyword arguments from a scene's [solver] (none but the common ones)."""
        return {}

    # --------------------------------------------------------------- step
    def stepper(self):
        """The ``Group`` that steps this line: its junction's, or a group of one, made on first use."""
        if self.group is None:
            from cablefem.dynamics.group import Group  # the group module builds on this one

            self.group = Group([self])
        return self.group

    def attempt(self, h):
        """Try one step of size h (``policy.attempt``); update the state and return True on success."""
        return self.stepper().attempt(h) == policy.CONVERGED

    def step(self, dt=None, first=None):
        """Advance exactly by dt (default: the current step) [s], as ``policy.advance`` does: a
        failed attempt is halved (to ``min_dt``), the steps grow back by at most ``MAX_GROWTH``;
        ``first``: the first attempt's size, when a caller has seen a longer one fail. Returns dt."""
        target = float(dt or self.dt)
        self.stepper().step(target, first)
        return target

    def too_small(self, h):
        """The error of a step of size h whose Newton failed when half of it is below ``min_dt``, or
        whose local error stayed above the tolerance down to ``min_dt`` (its Newton converged)."""
        if self.adaptive and self.last_residual <= self.tolerance:
            return ConvergenceError(
                f"{self.name}: the step's local tension error stayed above error_tolerance = "
                f"{self.error_tolerance:g} at t = {self.t:.6g} s down to dt = {h:.3g} s; try a larger "
                "error_tolerance, fixed steps (adaptive = false) or a ramp on the motion",
                residual=self.last_residual, iterations=self.newton_iterations)
        return ConvergenceError(
            f"{self.name}: Newton did not converge at t = {self.t:.6g} s even with "
            f"dt = {h:.3g} s (relative residual {self.last_residual:.3g}, tolerance "
            f"{self.tolerance:g}); try a smaller dt, more elements or a softer seabed",
            residual=self.last_residual, iterations=self.newton_iterations)

    def march(self, times):
        """Step to each of ``times`` (ascending, after t) in turn, each as ``step`` does; returns
        the forces (m, 2, 3) the line exerts on its fairlead and anchor after each step."""
        return self.stepper().member_forces(self, times)

    def fairlead_positions(self, times):
        """The prescribed fairlead positions (m, 3) at ``times`` (m,): one vectorised call when the
        boundary offers ``positions`` (``cablefem.model.motion.FairleadPath``), else one call per time."""
        positions = getattr(self.boundary, "positions", None)
        if positions is not None:
            return positions(np.asarray(times, dtype=float))
        return np.array([self.boundary(t)[0] for t in times], dtype=float).reshape(-1, 3)

    def snapshot(self):
        """The state needed to undo steps (see ``restore``): the state, the scheme's memory, the clock
        and the committed history of the points."""
        history = {rule: old.copy() for rule, (old, _) in self.system.history.items()}
        return (self.t, self.X, self.V, self.A, self.residual_rows, self.last_h, self.memory.copy(),
                self.clock.copy(), history, self.balance_rows.copy())

    def restore(self, snapshot):
        """Go back to a ``snapshot``."""
        self.t, self.X, self.V, self.A, self.residual_rows, self.last_h, memory, clock, history, balance = snapshot
        self.balance_rows = balance.copy()
        self.memory, self.clock = memory.copy(), clock.copy()
        for rule, old in history.items():
            self.system.history[rule][0][...] = old

    def largest_tension(self, X):
        """The line's largest tension [N] at positions X (N, 3): EA max(|dX/ds| - 1, 0) over the axial
        quadrature points."""
        _, dr = self.fem.at_quadrature(X, self.fem.reduced)
        return float(np.max(self.system.props["EA"][:, None] * np.maximum(np.linalg.norm(dr, axis=0) - 1.0, 0.0)))

    def tension_error(self, X_low, X=None):
        """Estimated local error of a step as a fraction of the line's largest tension, or of its
        largest at the start where that is larger (``clock["tension_scale"]``): EA |d(dX)/ds|
        at the axial quadrature points for dX = X - X_low, the difference between the step's
        positions X (default: the state) and a solution of lower order."""
        fem, X = self.fem, self.X if X is None else X
        _, d_diff = fem.at_quadrature(X - X_low, fem.reduced)
        _, dr = fem.at_quadrature(X, fem.reduced)
        EA = self.system.props["EA"][:, None]
        stretch = np.linalg.norm(dr, axis=0)
        # the strain's part of the difference: its component along the tangent dr / |dr|
        error = EA * np.abs(np.einsum("ceq,ceq->eq", dr, d_diff)) / np.where(stretch > 0.0, stretch, 1.0)
        tension = EA * np.maximum(stretch - 1.0, 0.0)
        return float(error.max() / max(tension.max(), float(self.clock["tension_scale"][0]), 1e-12 * EA.max()))

    def reactions(self):
        """Forces (3,) the line exerts on its fairlead and anchor at the current state [N]: minus
        the rows there, less the load of a point riding on that end (the line's own force,
        ``LineSystem.end_point_loads``). Where the scheme balanced the last step before the state's
        time (generalised-alpha), the rows there carried on to it along the line through the last
        two balances (``policy.balance_lag``)."""
        rows = self.residual_rows
        lag = np.zeros((2, 3))
        if rows is None:
            residual, _ = self.system.evaluate(self.system.state(self.X, self.V, self.A, self.t), jacobian=False)
            rows = residual + self.inertia(self.A)
        elif self.clock["t_balance"][0] == self.t_eval:  # the rows are the last accepted step's balance
            lag = self.balance_rows[1]
        fairlead, anchor = -rows[self.fem.fairlead_dof] - lag[0], -rows[self.fem.anchor_dof] - lag[1]
        if self.end_points:
            points = self.system.end_point_loads(self.X, self.V, self.A, self.t)
            fairlead, anchor = fairlead - points[0], anchor - points[1]
        return fairlead, anchor

    def clamp_moments(self):
        """Moments (2, 3) [N m] the anchor's and the fairlead's clamp exert on the line at the current
        state (``clamp.reaction_moments``; zero at an end that is not clamped), from the clamps' rows
        where the scheme balances the loads, as the reactions (generalised-alpha: at t_{n+1-alpha_f}).
        Compiled: the rows the last evaluation of the end elements kept, which an accepted step made
        at its converged point; numpy: evaluated there (``accept`` keeps it where it is not the state)."""
        system = self.system
        if not system.clamps:
            return np.zeros((2, 3))
        if self.evaluator.compiled:
            from cablefem.compiled.hermite import CLAMP_ROWS

            return clamp.reaction_moments(system, self.X, self.evaluator.points.clamp[:, CLAMP_ROWS:])
        X, V, A, t = self.X, self.V, self.A, self.t
        if self.balance is not None and self.balance[0] == self.t:
            _, X, V, A, t = self.balance
        rows = system.evaluate(system.state(X, V, A, t), jacobian=False, constrained=False)[0]
        rows = rows + (mass_matrix(system, self.evaluator.lumped) @ A.ravel()).reshape(A.shape)
        return clamp.reaction_moments(system, self.X, rows[list(self.fem.tangent_dofs)])

    def statistics(self):
        """Counters as a dict, for summary.json."""
        return {"integrator": self.name, **{name: int(value) for name, value in zip(policy.COUNTERS, self.counters)}}
