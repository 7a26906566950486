"""Free rigid bodies stepped in the same Newton as the strings that hang from them.

A ``BodyGroup`` is a ``Group`` (``cablefem.dynamics.group``) whose coupling unknowns are junctions
(3 each: a point) and rigid bodies (6 each: a ``RigidBody``'s pose, reference point r and angles
theta). Every string keeps its own integrator, banded tangent and LU, its ends on the body's points
unknowns of its own (``Line.prescribed`` False there). A Newton iteration condenses each string onto
its coupling ends as the junctions' group does (K y = -r, K Z = P_E, S = Z_E^-1) and solves the
coupling unknowns' step dQ from their linearised balance, the network statics' balance
(``cablefem.statics.network``) with the body's inertia and hydrodynamics in it:

    (J_body + G + sum_k T_row,k S_k T_col,k) dQ = -r_body + sum_k T_row,k S_k y_E,k

where an end at a body's point p moves as dx = T_col dq = dr + dR/dtheta p dtheta, its rows
enter the body's force and moment about r as T_row = [I; [R p]x], G is the moment's geometric term
-[r_E]x dR/dtheta p (the lever arm turning under the end's force) and J_body the body's own tangent
(``RigidBody.rows_and_tangent``: inertia, added mass, hydrostatics, drag). Each string then takes
y + Z S (T_col dQ - y_E), and the ends on a body are put where its new pose has its points
(x = r + R p exactly: the condensation is Newton's on the nonlinear constraint). The body's rows are
evaluated at the scheme's evaluation point (the loads of generalised-alpha at t_{n+1-alpha_f}), its
balance with the strings' end rows: r_body + sum_ends [r_E; (R p) x r_E].

The policy (``cablefem.dynamics.policy``) steps a body group on the Python ops (the strings'
evaluations compiled where their evaluators are), ``BODY_OPS``: the junctions' ops with the bodies
added to evaluation, norm, increment, trial, base, predictor and acceptance.
"""

from types import SimpleNamespace

import numpy as np

from cablefem.dynamics import policy, python_ops
from cablefem.dynamics.group import Group
from cablefem.dynamics.rigid_body import RigidBody
from cablefem.loads.rod_body import body_loads
from cablefem.model.network import coupling, junction_ends
from cablefem.statics.network import _cross


class BodyGroup(Group):
    """The integrators of the strings ``members`` stepped with ``bodies`` (``RigidBody``, whose
    ``links`` name member indices) and ``junctions`` {name: [(member index, end)]}."""

    def __init__(self, members, junctions=None, bodies=()):
        self.bodies = list(bodies)
        super().__init__(members, junctions)
        # every coupling end of a member as (end, row among its free DOFs, link, dof); link indexes
        # ``self.links``: (offset of its unknowns in Q, body or None, local (3,))
        self.links = []
        ends = [[] for _ in self.members]
        for j, name in enumerate(self.names):
            for k, end in self.junctions[name]:
                ends[k].append((end, 3 * j, None, None))
        offset = 3 * len(self.names)
        self.offsets = []
        for body in self.bodies:
            self.offsets.append(offset)
            for k, end, local in body.links:
                ends[k].append((end, offset, body, local))
            offset += 6
        self.size = offset
        self.ends = [[] for _ in self.members]
        for k, pairs in enumerate(ends):
            fem = self.members[k].fem
            linked = [end for end, _, _, _ in pairs]
            if len(set(linked)) < len(linked):  # its end stiffness would be singular (``Group.columns``)
                raise ValueError(f"string {k}'s ends {linked} are linked to more than one coupling unknown")
            for end, at, body, local in pairs:
                dof = fem.end_dofs[end]
                self.ends[k].append((end, int(np.searchsorted(fem.free_dofs, dof)), len(self.links), dof))
                self.links.append((at, body, local))
        self.interior = [np.setdiff1d(m.fem.free_dofs, [dof for _, _, _, dof in self.ends[k]])
                         for k, m in enumerate(self.members)]
        self.scale += sum(body.loads.weight for body in self.bodies)
        for m in self.members:  # the start is the network's statics (``Group``)
            m.A[...] = 0.0
            m.residual_rows = None
        self.start_bodies()

    def make_packer(self):
        return None  # the bodies step on the Python ops

    def remade(self, members):
        """The same group over ``members``, its bodies' states kept."""
        kept = [body.A.copy() for body in self.bodies]
        group = BodyGroup(members, self.junctions, self.bodies)
        for body, A in zip(self.bodies, kept):
            body.A = A
        return group

    def start_bodies(self):
        """Each body's acceleration at the start from its balance with the strings' pull, and its
        points' string ends where its pose puts them."""
        for body in self.bodies:
            body.X1 = body.X
            self.place(body, [m.X for m in self.members])
            rows = np.zeros(6)
            for k, end, local in body.links:
                m = self.members[k]
                line_rows, _ = m.evaluator.evaluate(m.X, m.V, m.A, 0.0, 1.0, t=m.t)
                r_E = line_rows[m.fem.end_dofs[end]]
                rows += np.concatenate([r_E, np.cross(body.rotation(body.X[1]) @ local, r_E)])
            body.A = body.initial_acceleration(rows)

    def set_velocity(self, body, V):
        """Start ``body`` with rates V (2, 3) (velocity [m/s], angle rates [rad/s]): its points' string
        ends move with it, its acceleration from its balance."""
        from cablefem.model.network import rotation_rates

        body.V = np.asarray(V, dtype=float).reshape(2, 3).copy()
        dR = body.frame @ rotation_rates(body.X[1], body.V[1], np.zeros(3))[1]
        for k, end, local in body.links:
            self.members[k].V[self.members[k].fem.end_dofs[end]] = body.V[0] + dR @ local
        self.start_bodies()

    def place(self, body, states):
        """Put the string ends on ``body``'s points where its trial pose X1 has them, in ``states``
        (one (N, 3) array per member)."""
        R = body.rotation(body.X1[1])
        for k, end, local in body.links:
            states[k][self.members[k].fem.end_dofs[end]] = body.X1[0] + R @ local

    # ------------------------------------------------------------------ stepping
    def attempt(self, h):
        return BODY["attempt"](self, h)

    def step(self, target, first=None):
        status = BODY["advance"](self, 0, float(target), float(first or 0.0))
        if status == policy.FAILED:
            raise self.too_small(self.stopped)

    # ------------------------------------------------------------------ the balance
    def balance(self):
        """The coupling unknowns' residual (size,): each junction's ends' rows summed, each body's own
        rows and its ends' force and moment about its reference point (at the evaluation point)."""
        out = np.zeros(self.size)
        for body, o in zip(self.bodies, self.offsets):
            out[o:o + 6] = body.rows
        for k, ends in enumerate(self.ends):
            rows = self.members[k].rows
            for _, _, link, dof in ends:
                at, body, local = self.links[link]
                out[at:at + 3] += rows[dof]
                if body is not None:
                    out[at + 3:at + 6] += np.cross(body.arm(local), rows[dof])
        return out

    def condense(self, steps):
        """Every string's step y + Z S (T_col dQ - y_E) at the coupling unknowns' step dQ (module
        docstring); the bodies' steps into their ``newton_step``; None if the system is singular."""
        n = self.size
        A, b = np.zeros((n, n)), np.zeros(n)
        columns, turning = {}, {}
        for body, o in zip(self.bodies, self.offsets):
            A[o:o + 6, o:o + 6] += body.tangent
            b[o:o + 6] -= body.rows
            R, dR = body.rotation_derivatives(body.X1[1])
            turning[id(body)] = (R, dR)
        for link, (at, body, local) in enumerate(self.links):
            T = np.zeros((3, n))
            T[:, at:at + 3] = np.eye(3)
            if body is not None:
                T[:, at + 3:at + 6] = turning[id(body)][1].transpose(0, 2, 1) @ local
            columns[link] = T
        for k, ends in enumerate(self.ends):
            if not ends:
                continue
            y, (_, S) = steps[k], self.members[k].junction_columns
            rows = self.members[k].rows
            for i, (_, _, link_i, dof_i) in enumerate(ends):
                at, body, local = self.links[link_i]
                T_row = columns[link_i].T.copy() if body is None else self._row_map(body, local, at)
                for j, (_, row_j, link_j, _) in enumerate(ends):
                    block = T_row @ S[3 * i:3 * i + 3, 3 * j:3 * j + 3]
                    A += block @ columns[link_j]
                    b += block @ y[row_j]
                if body is not None:  # the lever arm turning under the end's rows
                    arm_rate = body.factors[2] * (body.turn.transpose(0, 2, 1) @ local)
                    A[at + 3:at + 6, at + 3:at + 6] -= _cross(rows[dof_i]) @ arm_rate
        try:
            dQ = np.linalg.solve(A, b)
        except np.linalg.LinAlgError:
            return None
        for body, o in zip(self.bodies, self.offsets):
            body.newton_step = dQ[o:o + 6].reshape(2, 3)
        out = []
        for k, (y, ends) in enumerate(zip(steps, self.ends)):
            if ends:
                Z, S = self.members[k].junction_columns
                target = np.concatenate([columns[link] @ dQ for _, _, link, _ in ends])
                yE = np.concatenate([y[row] for _, row, _, _ in ends])
                y = y + (Z @ (S @ (target - yE))).reshape(-1, 3)
            out.append(y)
        return out

    def _row_map(self, body, local, at):
        """(size, 3): where an end's rows on ``body``'s point at ``local`` enter the balance: its force
        and its moment about the reference point at the evaluation point."""
        out = np.zeros((self.size, 3))
        out[at:at + 3] = np.eye(3)
        out[at + 3:at + 6] = _cross(body.arm(local))
        return out

    # ------------------------------------------------------------------ undo
    def snapshot(self):
        return [m.snapshot() for m in self.members] + [body.snapshot() for body in self.bodies]

    def restore(self, snapshot):
        n = len(self.members)
        for m, each in zip(self.members, snapshot[:n]):
            m.restore(each)
        for body, each in zip(self.bodies, snapshot[n:]):
            body.restore(each)


def _evaluate_bodies(g, tangent):
    for body in g.bodies:
        body.evaluate(tangent)


def _evaluate(g, tangent, held):
    python_ops.evaluate(g, tangent, held)
    _evaluate_bodies(g, tangent)
    return 0


def _finish(g):
    return python_ops.finish(g)


def _norm(g):
    """The strings' interior rows and the coupling unknowns' balance (a body's moments over its
    lever arm), relative to the group's weight."""
    total = sum(float(np.sum(m.rows[interior] ** 2)) for m, interior in zip(g.members, g.interior))
    balance = g.balance()
    for body, o in zip(g.bodies, g.offsets):
        balance[o + 3:o + 6] /= body.length
    return float(np.sqrt(total + np.sum(balance ** 2)) / g.scale)


def _size(g, steps):
    """The largest entry of the strings' steps in the first string's increment tolerance, and of the
    bodies' (their angles times their lever arm)."""
    size = max(float(np.max(np.abs(step), initial=0.0)) * scale for step, scale in zip(steps, g.increment_scale))
    for body in g.bodies:
        step = body.newton_step
        size = max(size, float(np.max(np.abs(step[0]))), float(np.max(np.abs(step[1]))) * body.length)
    return size


def _increment(g, refactor):
    steps = python_ops.member_steps(g, refactor)
    if steps is None:
        return python_ops.not_finite(g)
    if g.bodies and any(body.tangent is None for body in g.bodies):
        _evaluate_bodies(g, True)  # modified Newton keeps the strings' factors; a body's are cheap
    steps = g.condense(steps)
    if steps is None or not all(np.all(np.isfinite(step)) for step in steps):
        return python_ops.not_finite(g)
    for m, step in zip(g.members, steps):
        m.newton_step = step
    return _size(g, steps)


def _take_step(g, fraction):
    python_ops.take_step(g, fraction)
    for body in g.bodies:
        body.X1 = body.base + fraction * body.newton_step
        g.place(body, [m.X1 for m in g.members])


def _set_base(g):
    python_ops.set_base(g)
    for body in g.bodies:
        body.base = body.X1


def _restore_base(g):
    python_ops.restore_base(g)
    for body in g.bodies:
        body.X1 = body.base.copy()
        g.place(body, [m.X1 for m in g.members])


def _save_original(g):
    python_ops.save_original(g)
    for body in g.bodies:
        body.original_step = body.newton_step


def _restore_original(g):
    for m in g.members:
        m.newton_step = m.original_step
    for body in g.bodies:
        body.newton_step = body.original_step
    return _size(g, [m.original_step for m in g.members])


def _begin(g, h):
    python_ops.begin(g, h)
    for body in g.bodies:
        body.begin(h)
        body.X1 = body.guess
        g.place(body, [m.guess for m in g.members])


def _restart(g):
    python_ops.restart(g)
    for body in g.bodies:
        body.X1 = body.guess.copy()


def _accept(g, h):
    python_ops.accept(g, h)
    for body in g.bodies:
        body.accept(h)


#: the Python ops of a body group: the junctions' with the bodies added
BODY_OPS = SimpleNamespace(**{name: getattr(python_ops, name) for name in dir(python_ops)
                              if not name.startswith("_") and name not in ("np", "member_steps", "not_finite")})
BODY_OPS.__dict__.update(evaluate=_evaluate, finish=_finish, norm=_norm, increment=_increment, take_step=_take_step,
                         set_base=_set_base, restore_base=_restore_base, save_original=_save_original,
                         restore_original=_restore_original, begin=_begin, restart=_restart, accept=_accept)
#: the policy on those ops
BODY = policy.bind(BODY_OPS)


def body_groups(scene, integrators, poses):
    """The group of the strings that meet at junctions and free bodies, with a ``RigidBody`` per
    free body at its statics' pose ``poses`` {name: (6,)}; [] without free bodies."""
    _, free = coupling(scene.lines, scene.points, scene.bodies)
    if not free:
        return []
    ends = junction_ends(scene.lines, scene.points, scene.bodies)
    links = {name: [] for name in free}
    for k, line in enumerate(scene.lines):
        for end, name in enumerate(line.ends):
            point = scene.points.get(name) if name is not None else None
            if point is not None and point.body in links and not line.prescribed[end]:
                links[point.body].append((k, end, point.position))
    members = sorted({k for pairs in ends.values() for k, _ in pairs} | {k for each in links.values() for k, _, _ in each})
    index = {k: i for i, k in enumerate(members)}
    first = integrators[members[0]]
    bodies = [RigidBody(name, body_loads(scene.bodies[name], scene.environment), poses[name], first.scheme,
                        first.parameters, [(index[k], end, local) for k, end, local in links[name]], t0=first.t)
              for name in free]
    return [BodyGroup([integrators[k] for k in members],
                      {name: [(index[k], end) for k, end in pairs] for name, pairs in ends.items()}, bodies)]

