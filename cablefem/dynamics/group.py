"""Strings stepped together by one Newton policy: a line alone, or the strings that meet at junctions.

A junction is a free point where three or more string ends meet (``cablefem.model.network``). Each
string keeps its own integrator with the junction end as one of its unknowns (``Line.prescribed``
False there), its own banded tangent and LU; the junction's mass, added mass, weight, buoyancy and
drag ride on one of its strings as a ``Joint`` at that end vertex. A Newton iteration of the group
is one over all of its strings at once, with the strings condensed onto the junctions:

- each string factorises its tangent K and solves K y = -r for its own Newton step and
  K Z = P_E for the columns of its junction ends E;
- the end stiffness of the string is S = (Z_E)^-1 = K_EE - K_Ei K_ii^-1 K_iE (the Schur
  complement, without forming K_ii), and its end rows condensed onto E give -S y_E;
- at a junction the ends move together: (sum_k S_k) dq = sum_k S_k y_E,k, a 3 x 3 solve;
- each string then takes dX = y + Z S (dq - y_E), its interior's Newton step with its end at
  the junction's.

So an iteration costs what the lines cost alone plus three more banded back-substitutions per
junction end and a 3 x 3 solve per junction. The group's residual is every string's rows at its
free nodes that are no junction end and each junction's balance (the sum of its string ends' rows);
its increments are each string's, scaled to the first string's increment tolerance. Everything else
(the line search, branch corrections, modified Newton, retries, halving and growth, any scheme) is
the policy's (``cablefem.dynamics.policy``), compiled (``cablefem.compiled.steps``) where every
string evaluates with the compiled kernel on a seabed the loop projects, on the Python ops
(``cablefem.dynamics.python_ops``) elsewhere and where the compiled loop stops.
"""

import numpy as np

from cablefem.dynamics import policy, python_ops
from cablefem.errors import ConvergenceError
from cablefem.model.network import junction_ends

#: the policy on the Python ops
PYTHON = policy.bind(python_ops)


class Group:
    """The integrators of strings stepped together; ``junctions`` {name: [(member index, end)]}
    (none: a line alone, or strings that share no unknown)."""

    def __init__(self, members, junctions=None):
        self.members = list(members)
        self.junctions = dict(junctions or {})
        self.names = list(self.junctions)
        self.marched = None  # (key, forces) of the last ``march`` asked for by a member (``member_forces``)
        self.singular = False  # the last Newton on the Python ops stopped at a step that was not finite
        first = self.members[0]
        self.scale = sum(m.scale for m in self.members)
        # each string's increments in the first one's increment tolerance (exactly 1 for the first)
        self.increment_scale = [first.increment_tolerance / m.increment_tolerance for m in self.members]
        # per member: its junction ends as (end, row of the end in the free DOFs, junction index, dof)
        self.ends = [[] for _ in self.members]
        for j, name in enumerate(self.names):
            for k, end in self.junctions[name]:
                fem = self.members[k].fem
                dof = fem.end_dofs[end]
                self.ends[k].append((end, int(np.searchsorted(fem.free_dofs, dof)), j, dof))
        self.interior = [np.setdiff1d(m.fem.free_dofs, [dof for _, _, _, dof in self.ends[k]])
                         for k, m in enumerate(self.members)]
        for m in self.members:
            m.group = self
        if self.junctions:
            # the start is the network's static equilibrium at rest: every string's interior and each
            # junction's balance hold, so nothing accelerates. A member's own initial acceleration
            # solved its junction end's share of the balance (the other strings' pull, the junction's
            # own load) for an acceleration of that end and, through the consistent mass's coupling,
            # of its interior too (~13 % of a leg's junction-end force at t = 0 in a crowfoot)
            for m in self.members:
                m.A[...] = 0.0
                m.residual_rows = None
        self.packer = self.make_packer()

    def remade(self, members):
        """The same group over ``members`` (one string made again: a line end let go)."""
        return Group(members, self.junctions)

    def make_packer(self):
        """The compiled steps' ``Packer`` of this group, or None (the Python ops)."""
        from cablefem.compiled.problem import Packer  # numba's kernels only where a line has them

        return Packer.for_group(self)

    @property
    def settings(self):
        """The policy's ``Settings`` of the Python ops: the first string's."""
        return self.members[0].settings

    # ------------------------------------------------------------------ stepping
    def attempt(self, h):
        """One attempt of size h (``policy.attempt``): compiled where it can, on the Python ops where
        the seabed walk lost a point (the Python projection searches); its outcome."""
        if self.packer is not None:
            outcome = self.packer.attempt(h)
            if outcome != policy.LOST:
                return outcome
            # the two paths keep factors of their own: a contraction measured with one set says
            # nothing of the other's (policy.newton's first-iteration stop), on the way in or out
            self.members[0].contraction = -1.0
            outcome = PYTHON["attempt"](self, h)
            self.members[0].contraction = -1.0
            return outcome
        return PYTHON["attempt"](self, h)

    def step(self, target, first=None):
        """Advance every string exactly by ``target`` [s] (``policy.advance``: attempts halved on
        failure to ``min_dt``, grown back by at most ``MAX_GROWTH``); ``first``: the first attempt's
        size, when a longer one was seen to fail."""
        status = PYTHON["advance"](self, 0, float(target), float(first or 0.0))
        if status == policy.FAILED:
            raise self.too_small(self.stopped)

    def too_small(self, h):
        """The error of a step that failed down to ``min_dt``, the last attempt's size h [s]: the first
        member's (``Integrator.too_small``), or, where that attempt's Newton stopped at a step that was
        not finite (a singular tangent or coupling system; ``python_ops.increment``), that."""
        m = self.members[0]
        if not self.singular:
            return m.too_small(h)
        return ConvergenceError(
            f"{m.name}: Newton's step is not finite at t = {m.t:.6g} s even with dt = {h:.3g} s: the tangent "
            f"of {'the strings and their coupling unknowns' if self.junctions or len(self.members) > 1 else 'the line'} "
            f"is singular (relative residual {m.last_residual:.3g} where it stopped)",
            residual=m.last_residual, iterations=m.newton_iterations)

    def march(self, times):
        """Steps of every string to ``times`` (ascending) in turn, each as ``step`` takes it, in
        compiled runs where they can go; the forces (m, members, 2, 3) each string exerts on its
        fairlead and anchor after each step. Where the compiled loop stops (an attempt it cannot
        place the ends for, a point the seabed walk lost) that step goes on in Python."""
        times = np.asarray(times, dtype=float)
        forces = np.empty((len(times), len(self.members), 2, 3))
        k = 0
        while k < len(times):
            status, stopped = None, 0.0
            if self.packer is not None:
                status, done, stopped = self.packer.run(times[k:], forces[k:])
                k += done
                if status == policy.DONE:
                    break
                if status == policy.REACTIONS:  # step k was taken, only its forces are missing
                    forces[k] = self.reactions()  # the Python projection searches where the walk lost a point
                    k += 1
                    continue
            try:
                if status == policy.FAILED:
                    raise self.members[0].too_small(stopped)  # the compiled steps
                self.step(times[k] - self.members[0].t, first=stopped)
            except ConvergenceError as error:
                error.forces = forces[:k]  # the steps taken, for a caller writing them out
                raise
            forces[k] = self.reactions()
            k += 1
        return forces

    def member_forces(self, member, times):
        """``member``'s forces (m, 2, 3) on its fairlead and anchor at ``times``: a group of several
        strings marches all of them there on the first member's call, the others read its forces."""
        key = (float(times[-1]), len(times))
        if len(self.members) == 1 or self.marched is None or self.marched[0] != key:
            self.marched = (key, self.march(times))
        return self.marched[1][:, self.members.index(member)]

    def reactions(self):
        """Forces (members, 2, 3) [N] each string exerts on its fairlead and anchor: at a junction end
        the string's own, without the junction's weight, buoyancy, drag and inertia that ride on that
        end as a joint (``Integrator.reactions``)."""
        return np.array([m.reactions() for m in self.members])

    # ------------------------------------------------------------------ the junctions (Python face)
    def columns(self, k):
        """(Z, S) of member k from its kept LU: the columns Z (3 N_free, 3 m) of K^-1 at its junction
        ends and their end stiffness S = Z_E^-1 (3 m, 3 m); None if singular."""
        m, ends = self.members[k], self.ends[k]
        stack = np.zeros((3 * len(ends),) + m.X.shape)
        for i, (_, _, _, dof) in enumerate(ends):
            for c in range(3):
                stack[3 * i + c, dof, c] = -1.0  # the solve gives -K^-1 rows: K^-1 e
        solved = m.evaluator.solve_many(m.lu, stack)
        Z = solved.reshape(len(solved), -1).T  # of the matrix the step factorises (g_x K), as y is
        ZE = np.concatenate([Z[3 * row:3 * row + 3] for _, row, _, _ in ends])
        try:
            return Z, np.linalg.inv(ZE)
        except np.linalg.LinAlgError:
            return None

    def condense(self, steps):
        """Every string's step y + Z S (dq - y_E) at the junctions' step dq from sum_k S_k (dq_E -
        y_E,k) = 0; None if the junctions' system is singular."""
        J = len(self.names)
        A, b = np.zeros((3 * J, 3 * J)), np.zeros(3 * J)
        for k, ends in enumerate(self.ends):
            if not ends:
                continue
            y, (_, S) = steps[k], self.members[k].junction_columns
            for i, (_, _, ji, _) in enumerate(ends):
                for j, (_, row_j, jj, _) in enumerate(ends):
                    block = S[3 * i:3 * i + 3, 3 * j:3 * j + 3]
                    A[3 * ji:3 * ji + 3, 3 * jj:3 * jj + 3] += block
                    b[3 * ji:3 * ji + 3] += block @ y[row_j]
        try:
            dq = np.linalg.solve(A, b)
        except np.linalg.LinAlgError:
            return None
        out = []
        for k, (y, ends) in enumerate(zip(steps, self.ends)):
            if ends:
                Z, S = self.members[k].junction_columns
                target = np.concatenate([dq[3 * j:3 * j + 3] for _, _, j, _ in ends])
                yE = np.concatenate([y[row] for _, row, _, _ in ends])
                y = y + (Z @ (S @ (target - yE))).reshape(-1, 3)
            out.append(y)
        return out

    # ------------------------------------------------------------------ undo
    def snapshot(self):
        """Every member's ``snapshot``."""
        return [m.snapshot() for m in self.members]

    def restore(self, snapshot):
        for m, each in zip(self.members, snapshot):
            m.restore(each)


def junction_groups(scene, integrators):
    """The groups of the strings that meet at junctions (``cablefem.model.network.junction_ends``),
    each made the stepper of its members; [] without junctions."""
    ends = junction_ends(scene.lines, scene.points, scene.bodies)
    if not ends:
        return []
    members = sorted({k for pairs in ends.values() for k, _ in pairs})
    index = {k: i for i, k in enumerate(members)}
    return [Group([integrators[k] for k in members],
                  {name: [(index[k], end) for k, end in pairs] for name, pairs in ends.items()})]
