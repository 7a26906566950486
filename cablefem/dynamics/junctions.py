"""BDF2 steps of the strings that meet at junction points, solved together (issue 18).

A junction is a free point where three or more string ends meet (``cablefem.model.network``). Each
string keeps its own BDF2 integrator with the junction end as one of its unknowns (``Line.
prescribed`` False there), its own banded tangent and LU; the junction's mass, added mass,
weight, buoyancy and drag ride on one of its strings as a ``Joint`` at that end vertex. A step is
one Newton iteration over all of them at once, with the strings condensed onto the junctions:

- each string factorises its band K (as a line alone does) and solves K y = -r for its own
  Newton step and K Z = P_E for the columns of its junction ends E;
- the end stiffness of the string is S = (Z_E)^-1 = K_EE - K_Ei K_ii^-1 K_iE (the Schur
  complement, without forming K_ii), and its end rows condensed onto E give -S y_E;
- at a junction the ends move together: (sum_k S_k) dq = sum_k S_k y_E,k, a 3 x 3 solve;
- each string then takes dX = y + Z S (dq - y_E), its interior's Newton step with its end at
  the junction's.

So each Newton iteration costs what the lines cost alone plus three more banded back-
substitutions per junction end and a 3 x 3 solve per junction; nothing dense or sparse over the
whole network. Steps that do not converge are halved, as for one line.
"""

import warnings

import numpy as np

from cablefem.dynamics import policy
from cablefem.errors import ConvergenceError
from cablefem.model.network import junction_ends


class JunctionSteps:
    """The integrators of the strings that end at junctions (BDF2, with the junction ends among
    their unknowns), stepped together; ``junctions`` {name: [(integrator index, end)]}."""

    def __init__(self, integrators, junctions, tolerance, max_iterations=12):
        self.integrators = integrators
        self.junctions = junctions
        self.tolerance = tolerance
        self.max_iterations = max_iterations
        self.scale = sum(integ.scale for integ in integrators)
        self.newton_iterations = 0
        self.halvings = 0
        self.cache = {}  # times[-1] -> forces per integrator, for ``march`` of each member
        # the compiled loop (``cablefem.compiled.junctions``, BDF2) where every member marches compiled
        self.compiled = all(getattr(integ, "marcher", None) is not None and integ.name == "bdf2"
                            for integ in integrators)
        self.group = None  # its ``junction_march.Group``, built at the first march
        # per integrator: its junction ends as (end, row of the end in the free DOFs, junction)
        self.ends = [[] for _ in integrators]
        for name, members in junctions.items():
            for k, end in members:
                fem = integrators[k].fem
                dof = fem.end_dofs[end]
                self.ends[k].append((end, int(np.searchsorted(fem.free_dofs, dof)), name, dof))
        self.own_reactions = [integ.reactions for integ in integrators]
        for k, integ in enumerate(integrators):  # each member marches and reports through the group
            integ.march = (lambda times, k=k: self.march_member(k, times))
            integ.reactions = (lambda k=k: self.reactions(k))
            # the start is the network's static equilibrium at rest: every string's interior and
            # each junction's balance hold, so nothing accelerates. A member's own initial
            # acceleration solved its junction end's share of the balance (the other strings'
            # pull, the junction's own load) for an acceleration of that end and, through the
            # consistent mass's coupling, of its interior too (bug: ~13 % of a leg's junction-end
            # force at t = 0 in the crowfoot of validation/junction)
            integ.A[...] = 0.0
            integ.residual_rows = None

    # ------------------------------------------------------------------ marching
    def march_member(self, k, times):
        """Member k's forces (m, 2, 3) on its fairlead and anchor at ``times``: the group marches
        all members there on the first member's call."""
        key = float(times[-1])
        if key not in self.cache:
            self.cache = {key: self.march(times)}
        return self.cache[key][k]

    def march(self, times):
        """Step every member to each of ``times`` in turn; forces (members, m, 2, 3). Compiled
        (``cablefem.compiled.junctions``) when every member marches compiled; a step the compiled loop
        stops at goes on here."""
        times = np.asarray(times, dtype=float)
        forces = np.empty((len(self.integrators), len(times), 2, 3))
        i = 0
        while i < len(times):
            if self.compiled:
                i += self._march_compiled(times[i:], forces[:, i:])
                if i == len(times):
                    break
            try:
                self.advance(times[i] - self.integrators[0].t)
            except ConvergenceError as error:
                error.forces = forces[0, :i]
                raise
            for k in range(len(self.integrators)):
                forces[k, i] = self.reactions(k)
            i += 1
        return forces

    def reactions(self, k):
        """Forces (2, 3) [N] member k's string exerts on its fairlead and anchor; at a junction end
        the string's own, without the junction's weight, buoyancy, drag and inertia that ride on
        that end as a joint (``network.dynamic_lines``)."""
        return np.array(self.own_reactions[k]())  # ``Integrator.reactions`` leaves the joint out

    def _march_compiled(self, times, forces):
        """Compiled steps (``junction_march.group_steps``) to ``times`` until done or stopped, the
        forces into ``forces`` (members, m, 2, 3); the steps taken."""
        from cablefem.compiled import junctions as junction_march

        members = self.integrators
        problems = tuple(integ.marcher.problem(integ, *integ.marcher.ends(integ, times)) for integ in members)
        if self.group is None:
            self.group = self._group(problems)
            if self.group is None:
                self.compiled = False
                return 0
        status, taken = junction_march.group_steps(problems, self.group, times, forces)
        for integ, prob in zip(members, problems):
            integ.marcher.finish(integ, prob)
            if status == junction_march.DONE:  # BDF2's factors of the last step, as the Python steps leave them
                c0 = float(prob.clock[0]["v_x"])
                integ.c0, integ.t_eval, integ.factors = c0, integ.t, (c0, c0 * c0, 1.0)
                integ.x_hist, integ.v_hist = prob.x_hist.copy(), prob.v_hist.copy()
        self.newton_iterations += int(problems[0].counters[policy.ITERATIONS])
        self.halvings += int(problems[0].counters[policy.REJECTED])
        return int(taken)

    def _group(self, problems):
        """The compiled loop's ``junction_march.Group`` of these members, or None (with a warning)
        where their Problems differ in numba type: one compiled loop serves one type."""
        import numba

        from cablefem.compiled import junctions as junction_march

        types = {numba.typeof(prob) for prob in problems}
        if len(types) > 1:
            warnings.warn("junction steps: the strings' compiled problems differ in type, so their steps run "
                          "in the Python loop around the compiled evaluations (several times slower)",
                          RuntimeWarning, stacklevel=2)
            return None
        names = list(self.junctions)
        ends = np.full((len(self.integrators), 2, 3), -1, dtype=np.int64)
        for k, member in enumerate(self.ends):
            order = list(self.integrators[k].evaluator.free_order)
            for s, (_, _, name, dof) in enumerate(member):
                ends[k, s] = (order.index(dof), names.index(name), dof)
        leaders = np.array([(k, self.integrators[k].fem.end_dofs[end])
                            for k, end in (self.junctions[name][0] for name in names)], dtype=np.int64)
        size = max(integ.evaluator.n for integ in self.integrators)
        return junction_march.group(ends, leaders, size, self.max_iterations, self.integrators[0].MAX_GROWTH)

    def advance(self, target):
        """Advance by ``target`` [s] in attempts of whole eighths (``march.FRACTIONS``) of it, as a
        line's compiled steps do: halved on failure down to one, doubled after a success."""
        from cablefem.compiled.steps import FRACTIONS

        start, done, parts = self.integrators[0].t, 0, FRACTIONS
        last = self.integrators[0].last_h
        while last and parts > 1 and target * parts / FRACTIONS > self.integrators[0].MAX_GROWTH * last:
            parts //= 2
        while done < FRACTIONS:
            parts = min(parts, FRACTIONS - done)
            h = target * parts / FRACTIONS
            if self.attempt(h, start + target * (done + parts) / FRACTIONS):
                done += parts
                parts = min(2 * parts, FRACTIONS)
                continue
            self.halvings += 1
            if parts == 1:
                integ = self.integrators[0]
                raise ConvergenceError(
                    f"junction steps: Newton did not converge at t = {integ.t:.6g} s even with dt = {h:.3g} s "
                    f"(tolerance {self.tolerance:g}); try a smaller dt or more elements",
                    residual=float("nan"), iterations=self.newton_iterations)
            parts //= 2

    # ------------------------------------------------------------------ one step
    def attempt(self, h, t1=None):
        """One BDF2 step of h of every member (its ends where their paths are at ``t1``, default
        t + h), Newton over all at once; True on success."""
        members = self.integrators
        saved = [integ.snapshot() for integ in members]
        for integ in members:
            integ.targets = integ.ends_at(integ.t + h if t1 is None else t1)
            integ.begin(h)
            integ.X1 = integ.guess.copy()
        self._agree()
        for _ in range(self.max_iterations):
            self.newton_iterations += 1
            for integ in members:
                integ.newton_iterations += 1
            parts = [self._linearise(k, integ) for k, integ in enumerate(members)]
            if any(part is None for part in parts):
                break
            dq = self._junction_steps(parts)
            largest = 0.0
            for k, (integ, (y, Z, S, rows)) in enumerate(zip(members, parts)):
                step = y.copy()
                if self.ends[k]:
                    target = np.concatenate([dq[name] for _, _, name, _ in self.ends[k]])
                    yE = np.concatenate([y[row] for _, row, _, _ in self.ends[k]])
                    step += (Z @ (S @ (target - yE))).reshape(-1, 3)
                integ.X1[integ.fem.free_dofs] += step
                largest = max(largest, float(np.max(np.abs(step))) / integ.increment_tolerance)
            if largest <= 1.0:
                if self._finish(h):
                    return True
                break
        for integ, snapshot in zip(members, saved):
            integ.restore(snapshot)
        return False

    def _agree(self):
        """Put every string end at a junction where the junction's first string predicts it."""
        for name, members in self.junctions.items():
            k, end = members[0]
            first = self.integrators[k]
            at = first.X1[first.fem.end_dofs[end]].copy()
            for k, end in members[1:]:
                integ = self.integrators[k]
                integ.X1[integ.fem.end_dofs[end]] = at

    def _linearise(self, k, integ):
        """(y, Z, S, rows) of member k at its trial X1: its own Newton step y (N_free, 3), the
        columns Z (3 N_free, 3 m) of K^-1 at its junction ends, their end stiffness S (3 m, 3 m)
        and its residual rows; None if its tangent is singular."""
        X, V, A = integ.point(integ.X1)
        v_x, a_x, g_x = integ.factors
        rows, tangent = integ.rows_and_tangent(X, V, A, integ.t_eval, v_x, a_x, True)
        integ.njev += 1
        factors = integ.evaluator.factorize(tangent, g_x)
        if factors is None:
            return None
        integ.nlu += 1
        if not self.ends[k]:
            return integ.solve(factors, rows), None, None, rows
        stack = np.zeros((1 + 3 * len(self.ends[k]),) + rows.shape)
        stack[0] = rows
        for i, (_, _, _, dof) in enumerate(self.ends[k]):
            for c in range(3):
                stack[1 + 3 * i + c, dof, c] = -1.0  # the solve gives -K^-1 rows: K^-1 e
        solved = integ.evaluator.solve_many(factors, stack)
        y = solved[0]
        Z = solved[1:].reshape(len(solved) - 1, -1).T  # of the matrix the step factorises (g_x K), as y is
        ZE = np.concatenate([Z[3 * row:3 * row + 3] for _, row, _, _ in self.ends[k]])
        return y, Z, np.linalg.inv(ZE), rows

    def _junction_steps(self, parts):
        """The junctions' Newton steps {name: dq (3,)} from sum_k S_k (dq_E - y_E,k) = 0 over the
        string ends (a string between two junctions couples them: one solve of 3 per junction)."""
        names = list(self.junctions)
        where = {name: 3 * i for i, name in enumerate(names)}
        A, b = np.zeros((3 * len(names),) * 2), np.zeros(3 * len(names))
        for k, ends in enumerate(self.ends):
            if not ends:
                continue
            y, _, S, _ = parts[k]
            for i, (_, _, name_i, _) in enumerate(ends):
                for j, (_, row_j, name_j, _) in enumerate(ends):
                    block = S[3 * i:3 * i + 3, 3 * j:3 * j + 3]
                    A[where[name_i]:where[name_i] + 3, where[name_j]:where[name_j] + 3] += block
                    b[where[name_i]:where[name_i] + 3] += block @ y[row_j]
        dq = np.linalg.solve(A, b)
        return {name: dq[where[name]:where[name] + 3] for name in names}

    def _index(self, k, end):
        return [e for e, _, _, _ in self.ends[k]].index(end)

    def _finish(self, h):
        """Accept the step of every member at its X1 (its rows evaluated there); False if one is
        not finite."""
        for integ in self.integrators:
            X, V, A = integ.point(integ.X1)
            v_x, a_x, _ = integ.factors
            rows, _ = integ.rows_and_tangent(X, V, A, integ.t_eval, v_x, a_x, False)
            if not np.all(np.isfinite(rows)):
                return False
            integ.rows = rows
        for integ in self.integrators:
            integ.accept(h)
            integ.system.commit_history()
            integ.steps += 1
        return True


def junction_steps(scene, integrators):
    """Step the strings that meet at junctions together (``cablefem.dynamics.junctions``): their
    integrators' ``march`` goes through one ``JunctionSteps``; None without junctions."""
    ends = junction_ends(scene.lines, scene.points, scene.bodies)
    if not ends:
        return None
    members = sorted({k for pairs in ends.values() for k, _ in pairs})
    index = {k: i for i, k in enumerate(members)}
    return JunctionSteps([integrators[k] for k in members],
                         {name: [(index[k], end) for k, end in pairs] for name, pairs in ends.items()},
                         scene.solver.tolerance)
