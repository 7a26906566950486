"""Implicit time integrators with Newton per step: BDF2 and generalised-alpha.

The semi-discrete equation of motion (desire2023 Eq. 1 after the FEM in s) is

    M A + G(X, V, A, t) = 0,

with M the consistent (or lumped) mass and G the loads (tension with
internal damping, weight, drag, added mass, seabed contact and friction).
The anchor row is fixed and the fairlead row follows its prescribed motion.
Each integrator writes X_{n+1} as the unknown, V and A as affine functions
of it, and solves the step's residual by Newton with the analytic tangent

    K = a_x M + dG/dX + v_x dG/dV + a_x dG/dA,   v_x = dV/dX, a_x = dA/dX.

Like scipy.integrate's solvers, an integrator has a ``step()`` and counters
(``nfev`` residual evaluations, ``njev`` tangents, ``nlu`` factorisations,
``newton_iterations``, ``steps``, ``rejected``). A step whose Newton does not
converge is retried with half the step; the caller sees a
``ConvergenceError`` only when the step falls below ``min_dt``.
"""

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .branches import hold_branches
from .errors import ConvergenceError
from .march import DONE, FAILED, FRACTIONS, PROJECTION, Marcher


class Integrator:
    """Common machinery: state, boundary rows, mass, Newton, retries, counters.

    system: a ``LineSystem``; X0, V0: (N, 3) initial state [m, m/s]; ``boundary(t)`` gives
    the fairlead's position, velocity and acceleration (3,) at time t; dt [s]; tolerance:
    relative residual or relative increment, as in statics. ``compiled`` evaluates steps with
    ``cablefem.fused`` when the system's loads allow it (the same equations, compiled);
    ``newton`` is "full", "modified" (LU factors kept across iterations and steps) or "auto":
    modified on the numpy path; with the compiled kernel, modified Newton step by step until
    a step's kept factors have to be rebuilt (they contract slower than ``CONTRACTION``) or the
    step fails, then full Newton for the next ``AUTO_FULL_STEPS`` attempts.
    """

    name = "integrator"

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
    #: contact and tension branches its trial point reached (``_newton``; 0: never). Snap loads
    #: on the flume chain, P1 x 14 at dt 0.16 s: 13 failed attempts and 1306 evaluations
    #: without, none and 882 with (verification/work_precision/README.md); an attempt that
    #: fails with corrections is tried once more without
    MAX_CORRECTIONS = 2
    #: largest ratio of a step to the one before: variable-step BDF2 is zero-stable for ratios
    #: below 1 + sqrt(2) (Grigorieff 1983); halved steps grow back by doubling
    MAX_GROWTH = 2.0
    #: a step stretches by up to this fraction rather than leave a sliver to the end of dt
    STRETCH = 1e-3

    def __init__(self, system, X0, boundary, V0=None, t0=0.0, dt=0.01, tolerance=1e-8,
                 max_iterations=12, lumped=False, min_dt=None, newton="auto", compiled=True):
        self.system = system
        fem = system.fem
        self.fem = fem
        self.boundary = boundary
        self.t = float(t0)
        self.X = np.array(X0, dtype=float)
        self.V = np.zeros_like(self.X) if V0 is None else np.array(V0, dtype=float)
        self.dt = float(dt)
        self.nominal_dt = float(dt)
        self.min_dt = float(min_dt) if min_dt else self.dt / 1024.0
        self.tolerance = tolerance
        self.max_iterations = max_iterations
        self.M = fem.vector_mass(system.props["mass"], free_only=False)
        if lumped:
            if fem.order != 1:
                raise ValueError("a lumped mass needs order 1 elements")
            self.M = sp.diags(np.asarray(self.M.sum(axis=1)).ravel()).tocsr()
        free = fem.free_vector_dofs
        self.M_free = self.M[free][:, free].tocsr()
        self.length = system.line.unstretched_length
        self.scale = float(np.linalg.norm(system.weight_vector()[fem.free_dofs])) or 1.0
        self.nfev = self.njev = self.nlu = 0
        self.last_h = None  # the last accepted step [s]
        self.newton_iterations = self.steps = self.rejected = self.corrections = 0
        self.last_residual = float("nan")  # the final relative residual of the last failed attempt
        self.residual_rows = None  # M A + G at the current state, (N, 3); compiled steps may fill only
        # the anchor and fairlead rows (the reactions), leaving the others zero
        self._lu, self._lu_factors = None, None
        self.fused = None
        if compiled and not lumped:
            from .fused import FusedEvaluator

            self.fused = FusedEvaluator.for_system(system, system.props["mass"])
        # a compiled tangent costs about a residual and its banded LU a few microseconds, so full
        # Newton (fewer iterations) wins; on the numpy path kept factors save more than they cost
        if newton not in ("auto", "full", "modified"):
            raise ValueError(f"newton must be auto, full or modified, got {newton!r}")
        self.reuse_jacobian = newton == "modified" or (newton == "auto" and self.fused is None)
        self.switching = newton == "auto" and self.fused is not None
        self.full_steps_left = 0  # "auto": attempts still to run in full Newton
        # positions converge when the force their error makes, EA / h * dx, is below the
        # tolerance times the weight of an element: dx <= tol w h^2 / EA (floored at round-off)
        h = float(np.min(np.diff(fem.mesh.p[0])))
        weight = float(np.max(np.abs(system.weight.dry - system.weight.buoyancy)))
        extent = float(np.max(np.abs(self.X))) + self.length
        self.increment_tolerance = max(tolerance * weight * h * h / float(np.max(system.props["EA"])),
                                       1e3 * np.finfo(float).eps * extent)
        self.A = self.initial_acceleration()

    # ------------------------------------------------------------ helpers
    def set_boundary(self, X, V, A, t):
        """Put the anchor and fairlead rows of X, V, A at their prescribed values at time t."""
        fem = self.fem
        X[fem.anchor_dof] = self.system.line.anchor
        V[fem.anchor_dof] = 0.0
        A[fem.anchor_dof] = 0.0
        X[fem.fairlead_dof], V[fem.fairlead_dof], A[fem.fairlead_dof] = self.boundary(t)

    def inertia(self, A):
        """Rows (N, 3) of M A."""
        return (self.M @ A.ravel()).reshape(A.shape)

    def initial_acceleration(self):
        """A0 from (M + added mass) A0 = -G(X0, V0) on the free rows (zero at rest in equilibrium)."""
        fem, system = self.fem, self.system
        A = np.zeros_like(self.X)
        X, V = self.X.copy(), self.V.copy()
        self.set_boundary(X, V, A, self.t)
        if self.fused is not None:  # the same, compiled: the mass is the tangent's a_x part
            rows, with_mass = self.fused.evaluate(X, V, A, 0.0, 1.0)
            if np.linalg.norm(rows[fem.free_dofs]) > 1e-12 * self.scale:
                mass = with_mass - self.fused.evaluate(X, V, A, 0.0, 0.0)[1]
                factors = self.fused.factorize(mass)
                if factors is None:
                    raise ConvergenceError(f"{self.name}: the mass matrix is singular at t = {self.t:.6g} s "
                                           "(check the line's mass and added-mass coefficients)")
                A[fem.free_dofs] = self.fused.solve(factors, rows)
            return A
        residual, blocks = system.evaluate(system.state(X, V, A, self.t), jacobian=True,
                                           velocity_factor=0.0, acceleration_factor=1.0)
        rhs = -(residual + self.inertia(A))[fem.free_dofs].ravel()
        if np.linalg.norm(rhs) <= 1e-12 * self.scale:
            return A
        # d(G + M A)/dA restricted to the free rows: the acceleration blocks only
        rate_only = system.evaluate(system.state(X, V, A, self.t), jacobian=True,
                                    velocity_factor=0.0, acceleration_factor=1.0)[1]
        static = system.evaluate(system.state(X, V, A, self.t), jacobian=True)[1]
        K = system.matrix(rate_only) - system.matrix(static) + self.M_free
        A[fem.free_dofs] = spla.spsolve(K.tocsc(), rhs).reshape(-1, 3)
        return A

    def newton(self, X1, point, factors, t_eval):
        """Newton on one attempted step (``_newton``), full or modified as ``newton`` says;
        "auto" with the compiled kernel chooses here, attempt by attempt (see the class)."""
        reuse = self.reuse_jacobian or (self.switching and self.full_steps_left <= 0)
        corrected = self.corrections
        X, rows, ok, trouble = self._newton(X1, point, factors, t_eval, reuse, self.MAX_CORRECTIONS)
        if reuse and not ok:  # once more from the start: modified with a fresh tangent, or (auto) full
            trouble = True
            self._lu = None
            X, rows, ok, _ = self._newton(X1, point, factors, t_eval, self.reuse_jacobian, self.MAX_CORRECTIONS)
        if not ok and self.corrections > corrected:  # corrected and failed: once more without
            self._lu = None
            X, rows, ok, _ = self._newton(X1, point, factors, t_eval, self.reuse_jacobian, 0)
        if self.switching:
            if reuse and trouble:
                self.full_steps_left = self.AUTO_FULL_STEPS
            elif not reuse:
                self.full_steps_left -= 1
        return X, rows, ok

    def _newton(self, X1, point, factors, t_eval, reuse, max_corrections):
        """Solve the step residual M A + G = 0 on the free rows for the new positions X1 (N, 3).

        point(X1) -> (X, V, A) where the loads are evaluated; factors = (v_x, a_x, g_x) with
        d(X, V, A)/dX1 = g_x (1, v_x, a_x). Returns (X1, rows, ok, refreshed), rows = M A + G
        (N, 3), refreshed: kept factors were rebuilt for slow contraction.

        With ``reuse`` the LU factors of the tangent are kept across iterations and
        steps (modified Newton) and rebuilt when the step size changes, when the iteration
        contracts slower than ``CONTRACTION`` or when it fails; an iteration converges when
        the residual is below the tolerance or when the increment, extrapolated by the
        observed contraction (rho / (1 - rho), Hairer & Wanner IV.8), is below the increment
        tolerance. A fresh tangent gives Newton's quadratic convergence. When the last residual
        was below sqrt(tolerance), so that this one should converge, the residual is evaluated
        alone and the tangent only if it has not (the tangent costs about twice the residual in
        the compiled kernel).

        A Newton step that does not reduce the residual norm (Armijo's test, Kelley 2003 Sec.
        8.1) is halved, down to ``MIN_DAMPING``: seabed friction and contact switch between
        regimes, and undamped Newton can cycle between two states (measured on the snap-load
        flume case: residuals alternating 0.43, 0.39, 0.43, ... until the step was halved).

        Most of those rejections are a branch switch that the tangent at the base cannot see:
        seabed friction is a ramp of slope mu N / v_c up to the slip speed v_c and constant
        beyond (housner2022 Eq. 5-13), so at a sliding point Newton sees no friction stiffness
        along the slip and overshoots through the sticking branch; a slack element has no axial
        stiffness and Newton overshoots it into a large tension; a point just above a stiff
        seabed has no contact stiffness and Newton drives it deep into the seabed. Before
        halving a rejected full step, the step is solved again from its base (up to
        ``max_corrections`` times) with the points it took from sliding into the ramp or
        against their slip held on the ramp, those it put on the seabed or lifted off held on
        the trial's contact branch (spring and damper) and those it pulled taut held on the
        taut branch (value and slope of that branch at the base: the semismooth Newton step of
        the branch the trial revealed, ``cablefem.branches``), and the new trial point faces the same
        Armijo test against the true residual; if no correction passes, the line search halves
        Newton's own step. The solution is that of the true residual; only the path to it
        changes. ``newton`` tries an attempt that failed with corrections once more without.
        """
        free = self.fem.free_dofs
        v_x, a_x, _ = factors
        rows = None
        fresh = not reuse or self._lu is None or self._lu_factors != factors
        previous, refreshed = None, False
        base, damping = None, 1.0  # (X1, norm, dX) of the last Newton step taken, its damping
        damped = False  # the point that step started from was reached by a damped step
        branches, corrected = None, 0  # the base's branches (slip, taut, contact); its step's corrections
        original = None  # Newton's own step from the base, when corrected
        for _ in range(self.max_iterations):
            X, V, A = point(X1)
            # the tangent comes with the residual unless Newton's quadratic convergence from the
            # last residual promises that this one converges, or the step starts from a damped
            # point (regimes switching: its full step is mostly rejected); it is evaluated then
            # if the point is taken and has not converged
            with_tangent = fresh and damping == 1.0 and not damped and (
                base is None or base[1] > np.sqrt(self.tolerance))
            rows, tangent = self.rows_and_tangent(X, V, A, t_eval, v_x, a_x, with_tangent)
            norm = np.linalg.norm(rows[free]) / self.scale
            if norm <= self.tolerance and previous is not None:
                return X1, rows, True, refreshed
            if base is not None and damping > self.MIN_DAMPING and not norm <= (1 - 1e-4 * damping) * base[1]:
                if damping == 1.0 and corrected < max_corrections and branches is not None and fresh \
                        and hold_branches(self.fused, branches, corrected > 0):  # Newton again from the base on the new branches
                    corrected += 1
                    self.corrections += 1
                    X, V, A = point(base[0])
                    model, tangent = self.rows_and_tangent(X, V, A, t_eval, v_x, a_x, True, stick=True)
                    dX = self._increment(tangent, model, factors, True)
                    if dX is None:
                        break
                    original = original if corrected > 1 else base[2]
                    base = (base[0], base[1], dX)
                    X1 = base[0].copy()
                    X1[free] += dX
                    self.newton_iterations += 1
                    previous = float(np.max(np.abs(dX)))
                    continue
                if damping == 1.0 and corrected:  # no correction passed: the line search halves Newton's step
                    base = (base[0], base[1], original)
                    previous = float(np.max(np.abs(original)))
                damping *= 0.5
                X1 = base[0].copy()
                X1[free] += damping * base[2]
                continue
            if not np.isfinite(norm):
                break
            if fresh and not with_tangent:
                rows, tangent = self.rows_and_tangent(X, V, A, t_eval, v_x, a_x, True)
            dX = self._increment(tangent, rows, factors, fresh)
            if dX is None:
                break
            base, damping, damped = (X1, norm, dX), 1.0, damping < 1.0
            if self.fused is not None:
                branches, corrected = (self.fused.slip.copy(), self.fused.taut.copy(), self.fused.contact.copy()), 0
            X1 = X1.copy()
            X1[free] += dX
            self.newton_iterations += 1
            size = float(np.max(np.abs(dX)))
            rho = size / previous if previous else None
            if (fresh and size <= self.increment_tolerance) or (
                    rho is not None and rho < 1 and size * rho / (1 - rho) <= self.increment_tolerance):
                X, V, A = point(X1)
                rows, _ = self.rows_and_tangent(X, V, A, t_eval, v_x, a_x, False)
                return X1, rows, True, refreshed
            fresh = not reuse or (rho is not None and rho > self.CONTRACTION)
            refreshed = refreshed or (reuse and fresh)
            previous = size
        self._lu = None
        self.last_residual = norm
        return X1, rows, False, refreshed

    def _increment(self, tangent, rows, factors, refactor):
        """The Newton increment (N_free, 3) for residual ``rows``, with ``refactor`` from fresh LU
        factors of ``tangent`` (counted, kept in ``self._lu``), else from the kept ones; None
        if the tangent is singular or the increment not finite."""
        if refactor:
            _, a_x, g_x = factors
            self.njev += 1
            self._lu = self.factorize(tangent, g_x, a_x)
            if self._lu is None:
                return None
            self.nlu += 1
            self._lu_factors = factors
        dX = self.solve(self._lu, rows)
        return dX if np.all(np.isfinite(dX)) else None

    def rows_and_tangent(self, X, V, A, t, v_x, a_x, jacobian, stick=False):
        """Rows M A + G (N, 3) at the evaluation point and, with ``jacobian``, the tangent of the
        loads and mass in the representation ``factorize`` takes (``stick``: see ``_newton``)."""
        if self.fused is not None:
            self.nfev += 1
            return self.fused.evaluate(X, V, A, v_x, a_x, jacobian, stick)
        residual, blocks = self.evaluate(X, V, A, t, v_x, a_x, jacobian)
        return residual + self.inertia(A), blocks

    def factorize(self, tangent, g_x, a_x):
        """LU factors of g_x (K + a_x M), or None when singular."""
        if self.fused is not None:
            return self.fused.factorize(tangent, g_x)
        try:
            return spla.splu((g_x * (self.system.matrix(tangent) + a_x * self.M_free)).tocsc())
        except RuntimeError:
            return None

    def solve(self, factors, rows):
        """Newton increment (N_free, 3) of the free DOFs for residual rows (N, 3)."""
        if self.fused is not None:
            return self.fused.solve(factors, rows)
        return factors.solve(-rows[self.fem.free_dofs].ravel()).reshape(-1, 3)

    def evaluate(self, X, V, A, t, v_x, a_x, jacobian=True):
        """Load residual rows and tangent blocks at the step's evaluation point."""
        self.nfev += 1
        return self.system.evaluate(self.system.state(X, V, A, t), jacobian, v_x, a_x)

    # --------------------------------------------------------------- step
    def step(self, dt=None, first=None):
        """Advance exactly by dt (default: the current step) [s]. A step whose Newton fails is
        halved, down to ``min_dt``; no step is longer than ``MAX_GROWTH`` times the step before,
        so after a failure (or a short step that landed on an output time) the steps grow back
        to dt by doubling. ``first``: the first attempt's size, when a caller has seen a longer
        one fail. Returns dt."""
        target = float(dt or self.dt)
        done, h = 0.0, float(first or target)
        while target - done > 1e-9 * target:
            remaining = target - done
            h = min(h, remaining)
            if self.last_h is not None:
                h = min(h, self.MAX_GROWTH * self.last_h)
            if remaining - h <= self.STRETCH * h:  # land on the end, never leave a sliver of it
                h = remaining
            if not self.attempt(h):
                self.rejected += 1
                if h / 2 < self.min_dt:
                    raise self.too_small(h)
                h /= 2
                continue
            self.steps += 1
            self.last_h = h
            done += h
            h = target
        return target

    def too_small(self, h):
        """The error of a step of size h whose Newton failed when half of it is below ``min_dt``."""
        return ConvergenceError(
            f"{self.name}: Newton did not converge at t = {self.t:.6g} s even with "
            f"dt = {h:.3g} s (relative residual {self.last_residual:.3g}, tolerance "
            f"{self.tolerance:g}); try a smaller dt, more elements or a softer seabed",
            residual=self.last_residual, iterations=self.newton_iterations)

    def march(self, times):
        """Step to each of ``times`` (ascending, after t) in turn, each as ``step`` does; returns
        the forces (m, 2, 3) the line exerts on its fairlead and anchor after each step."""
        forces = np.empty((len(times), 2, 3))
        for k, t in enumerate(times):
            try:
                self.step(t - self.t)
            except ConvergenceError as error:
                error.forces = forces[:k]  # the steps taken, for a caller writing them out
                raise
            forces[k] = self.reactions()
        return forces

    def fairlead_positions(self, times):
        """The prescribed fairlead positions (m, 3) at ``times`` (m,): one vectorised call when the
        boundary offers ``positions`` (``cablefem.run.FairleadPath``), else one call per time."""
        positions = getattr(self.boundary, "positions", None)
        if positions is not None:
            return positions(np.asarray(times, dtype=float))
        return np.array([self.boundary(t)[0] for t in times], dtype=float).reshape(-1, 3)

    def snapshot(self):
        """The state needed to undo steps (see ``restore``)."""
        return (self.t, self.X, self.V, self.A, self.residual_rows, self.last_h,
                getattr(self, "previous", None))

    def restore(self, snapshot):
        """Go back to a ``snapshot``."""
        self.t, self.X, self.V, self.A, self.residual_rows, self.last_h, previous = snapshot
        if hasattr(self, "previous"):
            self.previous = previous

    def tension_error(self, X_low):
        """Estimated local error of the last step as a fraction of the line's largest tension:
        EA |d(dX)/ds| at the axial quadrature points for dX = X - X_low, the difference between
        the step and a solution of lower order."""
        fem = self.fem
        _, d_diff = fem.at_quadrature(self.X - X_low, fem.reduced)
        _, dr = fem.at_quadrature(self.X, fem.reduced)
        EA = self.system.props["EA"][:, None]
        error = EA * np.linalg.norm(d_diff, axis=0)
        tension = EA * np.maximum(np.linalg.norm(dr, axis=0) - 1.0, 0.0)
        return float(error.max() / max(tension.max(), 1e-12 * EA.max()))

    def attempt(self, h):
        """Try one step of size h; update the state and return True on success."""
        raise NotImplementedError

    def predict(self, h, t1):
        """Taylor predictor of the positions at t1 = t + h with the boundary rows in place."""
        guess = self.X + h * self.V + 0.5 * h * h * self.A
        guess[self.fem.fairlead_dof] = self.boundary(t1)[0]
        guess[self.fem.anchor_dof] = self.system.line.anchor
        return guess

    def reactions(self):
        """Forces (3,) the line exerts on its fairlead and anchor at the current state [N]."""
        rows = self.residual_rows
        if rows is None:
            residual, _ = self.evaluate(self.X, self.V, self.A, self.t, 0.0, 0.0, jacobian=False)
            rows = residual + self.inertia(self.A)
        return -rows[self.fem.fairlead_dof], -rows[self.fem.anchor_dof]

    def statistics(self):
        """Counters as a dict, for summary.json."""
        return {"integrator": self.name, "steps": self.steps, "rejected": self.rejected,
                "newton_iterations": self.newton_iterations, "nfev": self.nfev,
                "njev": self.njev, "nlu": self.nlu, "corrections": self.corrections}


class BDF2(Integrator):
    """Variable-step BDF2 on X and V (desire2023 Sec. 2.1.2), started by one backward-Euler step.

    With the fused kernel on a plane, a depth grid or a triangulated surface, steps run
    compiled, Newton iterations and seabed projections included (``cablefem.march``): ``march``
    takes runs of steps in one call and ``attempt`` one step; the numbers are those of the
    Python path to round-off."""

    name = "bdf2"

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.previous = None  # (h, X, V) of the step before
        self.marcher = Marcher.for_integrator(self)

    def march(self, times):
        if self.marcher is None:
            return super().march(times)
        times = np.asarray(times, dtype=float)
        fairlead = self.fairlead_positions(times)
        # the fairlead where the compiled loop may split each step (halved on failure)
        starts = np.append(self.t, times[:-1])
        split = np.arange(1, FRACTIONS) / FRACTIONS
        fractions = self.fairlead_positions((starts[:, None] + split * (times - starts)[:, None]).ravel())
        fractions = fractions.reshape(len(times), FRACTIONS - 1, 3)
        forces = np.empty((len(times), 2, 3))
        k = 0
        while k < len(times):
            status, done, forces[k:], stopped = self.marcher.run(self, times[k:], fairlead[k:], fractions[k:])
            k += done
            if status == DONE:
                break
            # a halving would go deeper than the loop's split points (``step`` halves on), an
            # attempt would not end on one of them (a step growing back after a short step to
            # another output time) or the walk lost a point (``attempt`` projects it in
            # Python): this step goes on through ``step``, the rest resume here
            first = {FAILED: 0.5 * stopped, PROJECTION: stopped}.get(status)
            try:
                if first is not None and first < self.min_dt:
                    raise self.too_small(2 * first)
                self.step(times[k] - self.t, first=first)
            except ConvergenceError as error:
                error.forces = forces[:k]
                raise
            forces[k] = self.reactions()
            k += 1
        return forces

    def error_estimate(self):
        """Relative tension error of the last step by Milne's device: the Taylor predictor P
        and BDF2 have local errors h^3 X^(3) / 6 and -2 h^3 X^(3) / 9, so LTE = 4/7 (X - P)."""
        return self.tension_error(self.X - 4.0 / 7.0 * (self.X - self.prediction))

    def coefficients(self, h):
        """(c0, c1, c2) with y' ~ c0 y_{n+1} + c1 y_n + c2 y_{n-1}; backward Euler at the start."""
        if self.previous is None:
            return 1.0 / h, -1.0 / h, 0.0
        w = h / self.previous[0]
        return (1 + 2 * w) / ((1 + w) * h), -(1 + w) / h, w * w / ((1 + w) * h)

    def attempt(self, h):
        if self.marcher is not None:
            t1 = self.t + h
            status, done, _, _ = self.marcher.run(self, [t1], self.boundary(t1)[0][None])
            if status != PROJECTION:
                return done == 1
            # the compiled walk lost a point: this attempt projects in Python (with its search)
        c0, c1, c2 = self.coefficients(h)
        t1 = self.t + h
        Xp, Vp = (self.X, self.V) if self.previous is None else self.previous[1:]
        x_hist = c1 * self.X + c2 * Xp
        v_hist = c1 * self.V + c2 * Vp

        def point(X):
            V = c0 * X + x_hist
            return X, V, c0 * V + v_hist

        prediction = self.predict(h, t1)
        X, rows, ok = self.newton(prediction, point, (c0, c0 * c0, 1.0), t1)
        if not ok:
            return False
        self.prediction = prediction
        self.previous = (h, self.X, self.V)
        _, self.V, self.A = point(X)
        self.X, self.t, self.residual_rows = X, t1, rows
        return True


class GeneralizedAlpha(Integrator):
    """Generalised-alpha (Chung & Hulbert 1993) with spectral radius ``rho_inf`` at infinite
    frequency: second order, unconditionally stable for linear problems, tunable
    high-frequency damping.

    Unconditional stability does not carry over to the nonlinear, tension-only axial
    stiffness of a line (Kuhl & Crisfield 1999; Erlicher et al. 2002): on a stiff chain
    (EA 5e11 N) pulled taut with omega dt ~ 1e2, rho_inf <= 0.5 stays bounded and rho_inf >=
    0.6 pumps energy until the tension reaches 1e11 N (verification/stability, case 7b).
    Hence the default 0.5; BDF2 has no such limit."""

    name = "generalized-alpha"

    def __init__(self, *args, rho_inf=0.5, **kwargs):
        self.rho_inf = float(rho_inf)
        r = self.rho_inf
        self.alpha_m = (2 * r - 1) / (r + 1)
        self.alpha_f = r / (r + 1)
        self.gamma = 0.5 - self.alpha_m + self.alpha_f
        self.beta = 0.25 * (1 - self.alpha_m + self.alpha_f) ** 2
        super().__init__(*args, **kwargs)

    def attempt(self, h):
        am, af, g, b = self.alpha_m, self.alpha_f, self.gamma, self.beta
        t1 = self.t + h
        X0, V0, A0 = self.X, self.V, self.A

        def newmark(X1):
            A1 = (X1 - X0 - h * V0) / (b * h * h) - (0.5 / b - 1.0) * A0
            return V0 + h * ((1 - g) * A0 + g * A1), A1

        def point(X1):  # loads at t_{n+1-af}, inertia at n+1-am
            V1, A1 = newmark(X1)
            return (1 - af) * X1 + af * X0, (1 - af) * V1 + af * V0, (1 - am) * A1 + am * A0

        factors = (g / (b * h), (1 - am) / ((1 - af) * b * h * h), 1 - af)
        X1, _, ok = self.newton(self.predict(h, t1), point, factors, t1 - af * h)
        if not ok:
            return False
        self.V, self.A = newmark(X1)
        self.X, self.t = X1, t1
        self.residual_rows = None  # the balance holds at n+1-af; reactions re-evaluate at n+1
        return True


INTEGRATORS = {"bdf2": BDF2, "generalized-alpha": GeneralizedAlpha}
