"""The Python side of the compiled steps (``cablefem.compiled.steps``): a ``Marcher`` packs a ``BDF2`` or
``GeneralizedAlpha`` integrator, its scheme (``CompiledSteps.compiled_scheme``), its compiled kernel
and its seabed into the ``Problem`` the compiled policy runs on, and hands the results back."""

import numpy as np

from cablefem.compiled import kernels
from cablefem.compiled.seabed import GRID, PLANE, TRIANGULATED, Projector
from cablefem.compiled.steps import BDF2, CLOCK, FACTORS, FRACTIONS, SCHEME, STEPS, Problem, attempt
from cablefem.dynamics import policy
from cablefem.geometry import DepthGrid, TriangulatedSurface
from cablefem.geometry import _walk_jit as walk


class Marcher:
    """Runs an integrator's steps through the compiled policy (``STEPS``); built by ``for_integrator``."""

    def __init__(self, integ, kind):
        fem, ev = integ.fem, integ.fused
        self.scheme = np.array([integ.compiled_scheme()], dtype=SCHEME)
        self.seabed, self.kind = integ.system.seabed, kind
        nel, nq = ev.full.dx.shape
        if kind == PLANE:  # the kernel computes the gap itself
            self.bed = kernels.Bed(ev.plane, *ev.unused)
        else:  # written by ``_project`` each evaluation
            self.bed = kernels.Bed(ev.plane, np.zeros((nel, nq)), np.zeros((nel, nq, 3)), np.zeros((nel, nq, 3)),
                                   np.zeros((nel, nq, 3, 3)))
        self.ev = ev
        ends = np.unique(np.flatnonzero(np.isin(ev.mesh.dofs, fem.end_dofs).any(axis=1)))
        self.end_elements = ends.astype(np.int64)
        self.points = nel * nq
        self.rule = fem.full  # positions at its quadrature points: the walk's start
        self.settings = integ.make_settings(FRACTIONS)  # read at construction
        n, N = ev.n, fem.n_dofs
        size = n * (2 * ev.kl + ev.ku + 1)
        self.vectors = tuple(np.zeros(n) for _ in range(3))  # rhs, step, original
        self.bands = (np.zeros(size), np.zeros(size), np.zeros(n, dtype=np.int64), np.empty(ev.kl + 1))
        self.rows = tuple(np.zeros((N, 3)) for _ in range(8))  # X1, V1, A1, X_alpha, guess, x_hist, v_hist, base
        pts = ev.points
        self.keeps = ((kernels.byte_view(ev.base_full), kernels.byte_view(pts.full_state)),
                      (kernels.byte_view(ev.base_reduced), kernels.byte_view(pts.reduced_state)))
        kept, nothing = integ.system.kept_history(), np.zeros(0, dtype=np.uint8)  # commit what a load keeps
        self.commits = tuple((kernels.byte_view(old), kernels.byte_view(new)) if rule in kept else (nothing, nothing)
                             for rule, (old, new) in (("full", (pts.full_old, pts.full_new)),
                                                      ("reduced", (pts.reduced_old, pts.reduced_new))))
        self.factors = np.full(1, np.nan, dtype=FACTORS)  # kept between runs

    @classmethod
    def for_integrator(cls, integ):
        """A marcher for ``integ`` (a ``CompiledSteps``) when it evaluates with the compiled kernel on a
        plane, a depth grid or a triangulated surface with compiled projections; None otherwise (the
        Python ops apply)."""
        ev, seabed = integ.fused, integ.system.seabed
        if ev is None:
            return None
        if ev.plane.size:
            return cls(integ, PLANE)
        if isinstance(seabed, DepthGrid) and seabed.compiled:
            return cls(integ, GRID)
        if isinstance(seabed, TriangulatedSurface) and seabed.compiled:
            return cls(integ, TRIANGULATED)
        return None

    def ends(self, integ, times):
        """The anchor and fairlead at ``times`` (m,) and where the loop may split each step (halved
        on failure), (m, 2, 3) and (m, FRACTIONS - 1, 2, 3)."""
        starts = np.append(integ.t, times[:-1])
        split = np.arange(1, FRACTIONS) / FRACTIONS
        fractions = integ.end_positions((starts[:, None] + split * (times - starts)[:, None]).ravel())
        return integ.end_positions(times), fractions.reshape(len(times), FRACTIONS - 1, 2, 3)

    def projector(self, X):
        """The seabed's ``Projector`` for state X (N, 3): its arrays, the walk's warm start from the
        seabed's last call at these points, and scratch."""
        n = self.points
        zero1, zero2 = np.zeros(1), np.zeros((1, 1))
        grid = (self.seabed.x, self.seabed.y, self.seabed.z) if self.kind == GRID else (zero1, zero1, zero2)
        if self.kind == TRIANGULATED:
            surface, typical, start = self.seabed.walk_start(self.rule.interpolate(X)[0])
        else:  # unused, typed as the walk's own
            surface, typical = walk.Surface(zero2, np.zeros((1, 3), dtype=np.int64), zero1, zero1), 0.0
            start = walk.Start(np.zeros((3, n)), np.zeros(n, dtype=np.int64), np.zeros(n), np.zeros(n, dtype=bool))
        result = walk.Result(np.zeros(n, dtype=np.int64), np.zeros((3, n)), np.zeros((walk.OUTPUTS, n)))
        return Projector(self.kind, *grid, surface, typical, start, result, np.zeros((3, n)))

    def problem(self, integ, ends, fractions):
        """The ``Problem`` of ``integ``'s current state, the anchor and fairlead at the ends of the
        steps to come (m, 2, 3) and at their splits (m, FRACTIONS - 1, 2, 3)."""
        memory = integ.memory()  # BDF2's step before; generalised-alpha has none
        h_before, Xp, Vp = (0.0, integ.X, integ.V) if memory is None else memory
        state = tuple(np.array(x, dtype=float) for x in (integ.X, integ.V, integ.A, Xp, Vp, integ.X))
        clock = np.zeros(1, CLOCK)
        clock[0] = (integ.t, h_before, integ.last_h or 0.0, 0.0, np.nan, np.nan, np.nan, np.nan, np.nan)
        self.factors["auto_left"] = integ.full_steps_left  # "auto" Newton's state, shared with the Python ops
        self.factors["contraction"] = integ.contraction
        ev, fem = self.ev, integ.fem
        return Problem(self.settings, ev.mesh, self.bed, ev.water, ev.points, ev.work, self.projector(integ.X),
                       fem.free_dofs.astype(np.int64), ev.free_order, ev.elements, self.end_elements,
                       int(fem.anchor_dof), int(fem.fairlead_dof), integ.scale, *state, np.zeros_like(integ.X),
                       *self.rows, *self.vectors, *self.bands, ev.base_full, ev.base_reduced, self.keeps,
                       self.commits, clock, self.factors, self.scheme, np.zeros(len(policy.COUNTERS), dtype=np.int64),
                       np.ascontiguousarray(ends, dtype=float), np.ascontiguousarray(fractions, dtype=float),
                       np.zeros((2, 3)))

    def finish(self, integ, prob, count_steps=True):
        """Hand the run's results back to ``integ``: counters, "auto"'s state, the seabed walk's
        last call and, if a step was taken, the state (generalised-alpha's rows are those of the
        balance at t_{n+1-alpha_f}: its reactions are evaluated again at the state)."""
        counters, clock = prob.counters, prob.clock[0]
        integ.full_steps_left = float(self.factors["auto_left"][0])
        integ.contraction = float(self.factors["contraction"][0])
        if self.kind == TRIANGULATED and counters[policy.NFEV]:  # the walk's last call: the next one starts there
            self.seabed.walk_end(prob.projector.start)
        integ.counters += counters
        integ.last_residual = float(clock["residual"])
        if clock["t"] != integ.t:
            integ.X, integ.V, integ.A, integ.prediction = prob.X, prob.V, prob.A, prob.prediction
            integ.residual_rows = prob.rows if self.scheme[0]["kind"] == BDF2 else None
            integ.set_memory((float(clock["h_before"]), prob.Xp, prob.Vp))
            integ.t, integ.last_h = float(clock["t"]), float(clock["last_h"])

    def run(self, integ, times, ends, fractions, forces):
        """Steps of ``integ`` to ``times`` (m,) with the ends at ``ends`` (m, 2, 3) and at the
        splits ``fractions``, as ``policy.steps`` takes them, the line's forces into ``forces``
        (m, 2, 3). Returns (status, k, the size of the attempt that stopped the loop)."""
        prob = self.problem(integ, ends, fractions)
        status, k = STEPS(prob, np.asarray(times, dtype=float), forces)
        self.finish(integ, prob)
        return status, k, float(prob.clock[0]["stopped"])

    def attempt(self, integ, h):
        """One attempt of size h of ``integ`` (``policy.attempt``), the ends at t + h; its
        outcome (policy.CONVERGED, DIVERGED or LOST). The attempt's arithmetic is that of a run of
        steps to the time t + h: its size is (t + h) - t."""
        t1 = integ.t + h
        prob = self.problem(integ, integ.ends_at(t1)[None], np.zeros((0, FRACTIONS - 1, 2, 3)))
        prob.target[:] = prob.ends[0]
        outcome = attempt(prob, t1 - integ.t)
        self.finish(integ, prob)
        return outcome
