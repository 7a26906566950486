"""Statics of a mooring network with coupling unknowns: junction points and free bodies (issue 18).

``cablefem.model.network`` cuts a network into strings, each one banded finite element line. What is
left between them are the *coupling unknowns* q: the position (3) of each free point where three
or more string ends meet (a junction), and the pose (6: reference point r and angles theta, MoorDyn-
C's R = Rx Ry Rz) of each free body. This module finds them in statics by Newton's method on q with
the strings condensed onto their ends:

- inner: each string that ends at a coupling node is solved for its own equilibrium with those
  ends held where q puts them (``cablefem.statics.newton``), from its last solution moved with its
  ends by its tangent's response (``Network.predict``), else from its start shape;
- outer: the residual is the balance at each node: the force of the string ends on a junction
  point plus its own weight and buoyancy; and on a free body, the force and the moment about its
  reference point of its points' string ends, its weight at the centre of gravity, its buoyancy
  at the centre of buoyancy (MoorPy's rM), the waterplane's heave restoring force -rho g A_wp z
  and the steady external force and moment (the offset study of MoorPy's ``System``);
- Jacobian: exact. Each string's end stiffness is the Schur complement of its tangent,
  dF_E/dx_E = -(K_EE - K_EI K_II^-1 K_IE) (one sparse factorisation of its interior, a few
  solves), chained with dx/dq (the identity for a junction; [I, dR/dtheta p] for a body point)
  and the moment's geometric terms -[F]x dR/dtheta p. Only the coupling unknowns (3 per junction,
  6 per body) make a dense system; each string stays its own banded block.
"""

import time
from dataclasses import dataclass, field, replace
from types import SimpleNamespace

import numpy as np
import scipy.sparse.linalg as spla

from cablefem.errors import ConvergenceError
from cablefem.loads.points import PointLoads
from cablefem.model.network import coupling, rotation, rotation_rates
from cablefem.statics.continuation import axial_continuation
from cablefem.statics.hang import free_end
from cablefem.statics.network_relax import NetworkPseudoTransient
from cablefem.statics.newton import Halving, iterate, newton
from cablefem.statics.solve import solve_static

#: a string's Newton from its last equilibrium (``Network.solve_strings``) may take this many times
#: the solver's ``max_iterations``
WARM_ITERATIONS = 4


def _cross(a):
    """The matrix [a]x with [a]x b = a x b."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def rotation_derivatives(angles):
    """R (3, 3) at ``angles`` (3,) and dR/dtheta_j (3, 3, 3), j the last index."""
    R = rotation(angles)
    dR = np.stack([rotation_rates(angles, np.eye(3)[j], np.zeros(3))[1] for j in range(3)], axis=-1)
    return R, dR


@dataclass
class _Node:
    """A coupling node: a junction point (``local`` None: its position is q[offset:offset + 3]) or
    a point of a free body (r + R local, the body's pose at q[offset:offset + 6])."""

    name: str
    offset: int
    local: np.ndarray | None
    loads: PointLoads | None  # the point's own weight and buoyancy (None: massless, no volume)


@dataclass
class NetworkStatics:
    """The static equilibrium of the coupled part of a network: the state of each string that ends
    at a coupling node (None for the others, which ``solve_network`` leaves to their own solves),
    the junctions' positions and the free bodies' poses (x, y, z [m], roll, pitch, yaw [rad])."""

    systems: list
    states: list
    points: dict
    poses: dict
    iterations: int
    residual: float
    history: list = field(default_factory=list)
    wall_time_s: float = 0.0
    solves: list = field(default_factory=list)  # per string: {how its solves converged: how many}
    string_iterations: list = field(default_factory=list)  # per string: its Newton iterations, summed
    outer: str = "halving"  # how the coupling unknowns' Newton converged

    def strategy(self, k):
        """How string k was solved, e.g. 'network (predicted x11, axial continuation x1)'."""
        return "network (" + ", ".join(f"{name} x{n}" for name, n in self.solves[k].items()) + ")"


class Network:
    """The coupling unknowns of ``scene`` and the strings that end at them; ``systems`` are the
    strings' static systems with every coupling end prescribed (``build(line)`` makes one)."""

    def __init__(self, scene, build):
        self.scene = scene
        junctions, bodies = coupling(scene.lines, scene.points, scene.bodies)
        self.junctions, self.bodies = junctions, bodies
        env = scene.environment
        self.rho_g = env.water_density * env.gravity
        self.offsets, size = {}, 0
        for name in junctions:
            self.offsets[name], size = size, size + 3
        for name in bodies:
            self.offsets[name], size = size, size + 6
        self.size = size
        self.nodes, self.ends = {}, []  # ends: (string, end, node name)
        for k, line in enumerate(scene.lines):
            for e, name in enumerate(line.ends):
                node = self._node(name)
                if node is not None and not line.prescribed[e]:
                    self.ends.append((k, e, node.name))
        self.coupled = sorted({k for k, _, _ in self.ends})
        lines = list(scene.lines)
        for k in self.coupled:
            lines[k] = replace(lines[k], prescribed=tuple(
                given or any(kk == k and ee == e for kk, ee, _ in self.ends) for e, given in enumerate(lines[k].prescribed)))
        self.lines = lines
        self.systems = [build(line) for line in lines]
        self.solves = [{} for _ in lines]  # per string: {how a solve converged: how many}
        self.string_iterations = [0] * len(lines)

    def _node(self, name):
        """The coupling node at point ``name`` (made on first use), or None (not a coupling node)."""
        if name is None:
            return None
        if name in self.nodes:
            return self.nodes[name]
        point = self.scene.points[name]
        owner = point.body if point.body in self.bodies else name if name in self.junctions else None
        if owner is None:
            return None
        env = self.scene.environment
        loads = None
        if point.mass > 0.0 or point.volume > 0.0 or np.any(point.force):
            loads = PointLoads([0], [point.joint], env.water_density, env.gravity)
        node = _Node(name, self.offsets[owner], None if point.body is None else point.position, loads)
        self.nodes[name] = node
        return node

    # ---------------------------------------------------------------------- unknowns
    def start(self):
        """q at the points' and bodies' given positions."""
        q = np.zeros(self.size)
        for name in self.junctions:
            q[self.offsets[name]:self.offsets[name] + 3] = self.scene.points[name].position
        for name in self.bodies:
            body = self.scene.bodies[name]
            q[self.offsets[name]:self.offsets[name] + 6] = np.concatenate([body.position, body.rotation])
        return q

    def place(self, q):
        """Each node's position (3,) and dx/dq (3, size) at q."""
        out = {}
        for name, node in self.nodes.items():
            o = node.offset
            T = np.zeros((3, self.size))
            T[:, o:o + 3] = np.eye(3)
            if node.local is None:
                out[name] = (q[o:o + 3].copy(), T)
            else:
                R, dR = rotation_derivatives(q[o + 3:o + 6])
                T[:, o + 3:o + 6] = dR.transpose(0, 2, 1) @ node.local
                out[name] = (q[o:o + 3] + R @ node.local, T)
        return out

    # ---------------------------------------------------------------------- strings
    def solve_strings(self, places, states, tolerance, max_iterations):
        """Each coupled string's equilibrium with its coupling ends at ``places``; the states
        (updated in place, each predicted from its last equilibrium by its tangent before Newton)
        and the Newton iterations."""
        iterations = 0
        for k in self.coupled:
            system = self.systems[k]
            targets = {e: places[name][0] for kk, e, name in self.ends if kk == k}
            X1, its, ok, how = None, 0, False, "predicted"
            if states[k] is not None:
                # from its last equilibrium, moved with its ends, a string converges, if slowly: one far
                # stiffer than its loads, an element taut by micrometres (tripod.txt's float), by a
                # fifth of its residual an iteration
                X1, its, _, _, ok = newton(system, self.predict(k, states[k], targets), tolerance,
                                           WARM_ITERATIONS * max_iterations)
            if not ok:  # from its start shape
                X = _start(system, targets)
                X1, more, _, _, ok = newton(system, X, tolerance, max_iterations)
                its, how = its + more, "newton"
            if not ok:  # a string far stiffer than its loads (tripod.txt's float)
                X1, more, _, _, ok = axial_continuation(system, X, tolerance, max_iterations)
                its, how = its + more, "axial continuation"
            if not ok:
                result = solve_static(system, X, tolerance, max_iterations)
                X1, its, how = result.X, its + result.iterations, result.strategy
            system.commit_history()
            states[k], iterations = X1, iterations + its
            self.solves[k][how] = self.solves[k].get(how, 0) + 1
            self.string_iterations[k] += its
        return iterations

    def predict(self, k, X, targets):
        """String k's state with its coupling ends moved from where X (N, 3), an equilibrium, has
        them to ``targets`` {end: position (3,)}. A string held at both ends: the interior moved by
        the tangent's response to the ends' move, dX_I = -K_II^-1 K_IE dx_E (the Euler predictor of
        continuation in the ends' positions: a taut leg turns about its anchor). A string with a free
        end hangs from its coupling end and moves with it (its turn about the vertical through that
        end is free, without current: a null direction of K_II, along which the tangent's response
        is round-off amplified; on tripod.txt's float string this takes fewer iterations than the
        tangent's response or a shift falling from the end's move to none at the free end)."""
        if free_end(self.lines[k]) is not None:
            (e, target), = targets.items()
            fem = self.systems[k].fem
            move = target - X[fem.end_dofs[e]]
            if fem.hermite:  # the vertices move, the tangent rows stay
                out = X.copy()
                out[: fem.n_vertices] += move
                return out
            return X + move
        _, K, dofs, E, interior = self._tangent(k, X)
        moves = np.concatenate([targets[e] - X[dofs[e]] for e in dofs])
        out = X.copy()
        for e, dof in dofs.items():
            out[dof] = targets[e]
        rows = out.reshape(-1)
        rows[interior] -= spla.splu(K[interior][:, interior].tocsc()).solve(K[interior][:, E] @ moves)
        return out

    def _tangent(self, k, X):
        """String k at X (N, 3): its residual rows (N, 3), full tangent (sparse), its coupling ends'
        vertices {end: dof}, their vector rows E and the free vector rows."""
        system = self.systems[k]
        fem = system.fem
        residual, blocks = system.evaluate(system.state(X))
        K = system.matrix(blocks, free_only=False).tocsc()
        dofs = {e: fem.end_dofs[e] for kk, e, _ in self.ends if kk == k}
        E = np.concatenate([3 * dofs[e] + np.arange(3) for e in dofs])
        return residual, K, dofs, E, fem.free_vector_dofs

    def condensed(self, k, X):
        """End forces {end: F (3,)} of string k on its coupling nodes and their stiffness
        {(end, end'): dF_end / dx_end' (3, 3)} (the Schur complement of the string's tangent)."""
        residual, K, dofs, E, interior = self._tangent(k, X)
        ends = list(dofs)
        K_ii = K[interior][:, interior].tocsc()
        K_ie = K[interior][:, E].toarray()
        K_ei = K[E][:, interior]
        schur = K[E][:, E].toarray() - K_ei @ spla.splu(K_ii).solve(K_ie)
        forces = {e: -residual[dofs[e]] for e in ends}
        stiffness = {(a, b): -schur[3 * i:3 * i + 3, 3 * j:3 * j + 3]
                     for i, a in enumerate(ends) for j, b in enumerate(ends)}
        return forces, stiffness

    # ---------------------------------------------------------------------- balance
    def balance(self, q, states, places):
        """The residual (size,) of the nodes' and bodies' balance at q and its Jacobian (size, size)."""
        r, J = np.zeros(self.size), np.zeros((self.size, self.size))
        node_force = {name: np.zeros(3) for name in self.nodes}
        node_stiff = {name: np.zeros((3, self.size)) for name in self.nodes}
        for k in self.coupled:
            forces, stiffness = self.condensed(k, states[k])
            at = {e: name for kk, e, name in self.ends if kk == k}
            for e, F in forces.items():
                node_force[at[e]] += F
                for e2 in forces:
                    node_stiff[at[e]] += stiffness[(e, e2)] @ places[at[e2]][1]
        for name, node in self.nodes.items():
            x, T = places[name]
            if node.loads is not None:
                terms = node.loads.evaluate(SimpleNamespace(r=x[:, None], v=None, a=None))
                node_force[name] += terms.force[:, 0]
                node_stiff[name] += terms.force_r[:, :, 0] @ T
            o, F, dF = node.offset, node_force[name], node_stiff[name]
            r[o:o + 3] += F
            J[o:o + 3] += dF
            if node.local is not None:
                arm = x - q[o:o + 3]
                r[o + 3:o + 6] += np.cross(arm, F)
                J[o + 3:o + 6] += _cross(arm) @ dF
                J[o + 3:o + 6, o + 3:o + 6] -= _cross(F) @ T[:, o + 3:o + 6]
        for name in self.bodies:
            self._body_terms(name, q, r, J)
        return r, J

    def _body_terms(self, name, q, r, J):
        """A free body's own weight, buoyancy, waterplane and external load into r and J."""
        body, o = self.scene.bodies[name], self.offsets[name]
        g = self.scene.environment.gravity
        R, dR = rotation_derivatives(q[o + 3:o + 6])
        r[o + 2] += -body.mass * g + self.rho_g * body.volume - self.rho_g * body.waterplane_area * q[o + 2]
        J[o + 2, o + 2] -= self.rho_g * body.waterplane_area
        r[o:o + 3] += body.force
        r[o + 3:o + 6] += body.moment
        for local, load in ((body.cg, np.array([0.0, 0.0, -body.mass * g])),
                            (body.cb, np.array([0.0, 0.0, self.rho_g * body.volume]))):
            r[o + 3:o + 6] += np.cross(R @ local, load)
            J[o + 3:o + 6, o + 3:o + 6] -= _cross(load) @ (dR.transpose(0, 2, 1) @ local)

    def scale(self):
        """A force scale of the balance [N]: the strings' and points' weights and the external loads."""
        total = sum(float(np.linalg.norm(self.systems[k].weight_vector())) for k in self.coupled)
        total += sum(abs(p.mass * self.scene.environment.gravity) + self.rho_g * p.volume
                     for p in self.scene.points.values())
        total += sum(float(np.linalg.norm(self.scene.bodies[b].force)) for b in self.bodies)
        return total or 1.0

    def length(self):
        """A length scale [m]: the shortest coupled string."""
        return min(self.lines[k].unstretched_length for k in self.coupled)


def _start(system, targets):
    """A first state of a string with its coupling ends at ``targets`` {end: position}: its start
    shape (the line's ends are where [points] and [bodies] put the coupling nodes at q0)."""
    from cablefem.statics.start_shape import initial_shape

    X = initial_shape(system)[0].copy()
    fem = system.fem
    for e, position in targets.items():
        X[fem.end_dofs[e]] = position
    return X


def solve_network(scene, build, tolerance=1e-8, max_iterations=50):
    """Static equilibrium of the strings of a network that end at coupling unknowns, and of those
    unknowns (the module docstring); a ``NetworkStatics``. ``build(line)`` makes a string's static
    system (its coupling ends prescribed)."""
    start = time.perf_counter()
    net = Network(scene, build)
    states = [None] * len(scene.lines)
    q = net.start()
    places = net.place(q)
    iterations = net.solve_strings(places, states, tolerance, max_iterations)
    balance = _Balance(net, tolerance, max_iterations)
    (q, states, places), _, norm, history, converged = iterate(balance, (q, states, places), tolerance,
                                                               max_iterations, Halving())
    outer = "halving"
    if not converged:  # no equilibrium within Newton's reach: follow a damped pseudo-motion to one
        q0, states0 = net.start(), [None] * len(scene.lines)
        places0 = net.place(q0)
        iterations += net.solve_strings(places0, states0, tolerance, max_iterations)
        relaxed = iterate(balance, (q0, states0, places0), tolerance, 10 * max_iterations,
                          NetworkPseudoTransient(net))
        if relaxed[4]:
            (q, states, places), _, norm, more, converged = relaxed
            history, outer = history + more, "halving, then pseudo-transient"
        else:
            norm = min(norm, relaxed[2])
    iterations += balance.iterations
    if not converged:
        raise ConvergenceError(
            f"network statics did not converge: relative residual {norm:.3g} of the balance of "
            f"{', '.join(net.junctions + net.bodies)} after {len(history) - 1} iterations (tolerance "
            f"{tolerance:g}); check that the lines can reach the free points and bodies from where "
            "[points] and [bodies] put them, give a free body a waterplane_area, or start it closer",
            residual=norm, iterations=iterations)
    points = {name: places[name][0] for name in net.junctions}
    poses = {name: q[net.offsets[name]:net.offsets[name] + 6].copy() for name in net.bodies}
    return NetworkStatics(net.systems, states, points, poses, iterations, norm, history,
                          time.perf_counter() - start, net.solves, net.string_iterations, outer)


class _Balance:
    """The coupling unknowns' balance as the statics' Newton solves it (``cablefem.statics.newton.
    iterate``): a point is (q, the strings' states, the coupling nodes' places); a trial solves the
    strings with their ends where q puts them (``ConvergenceError`` if one fails); steps are small
    below the tolerance of the network's length."""

    def __init__(self, net, tolerance, max_iterations):
        self.net, self.tolerance, self.max_iterations = net, tolerance, max_iterations
        self.scale, self.length = net.scale(), net.length()
        self.iterations = 0  # the strings' Newton iterations in the trials

    def evaluate(self, point):
        r, J = self.net.balance(*point)
        return r, J, _norm(r, self.net, self.scale, self.length)

    def solve(self, J, r):
        try:
            return np.linalg.solve(J, -r)
        except np.linalg.LinAlgError:
            return np.linalg.lstsq(J, -r, rcond=None)[0]

    def trial(self, point, step, lam):
        q = point[0] + lam * step
        states, places = list(point[1]), self.net.place(q)
        self.iterations += self.net.solve_strings(places, states, self.tolerance, self.max_iterations)
        return q, states, places

    def small(self, step):
        return np.max(np.abs(step)) <= self.tolerance * self.length


def _norm(r, net, scale, length):
    """The balance's residual relative to the force scale (moments over the length scale)."""
    out = 0.0
    for name in net.junctions:
        o = net.offsets[name]
        out = max(out, np.linalg.norm(r[o:o + 3]))
    for name in net.bodies:
        o = net.offsets[name]
        out = max(out, np.linalg.norm(r[o:o + 3]), np.linalg.norm(r[o + 3:o + 6]) / length)
    return out / scale
