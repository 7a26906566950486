"""A rod's own loads as a ``RigidBody``'s (``cablefem.dynamics.rigid_body``): a free rod stepped in a
run, and the rods a free body carries added to the body's rows.

A ``RodPart`` is one rod on a rigid frame (a free rod's own frame, ``cablefem.model.rod.rod_body``:
end A at the reference point, end B at (0, 0, L); or a free body's, the rod's ends where the file puts
them in the body's frame). At the frame's pose X = (r, theta), rates V and accelerations A (2, 3)
each, its ends are at r + R p, move at r' + R' p and accelerate at r'' + R'' p (R = R_0 Rx Ry Rz,
``cablefem.model.network.rotation_rates``), and its rows are those of ``cablefem.loads.rod``
(MoorDyn-C's ``Rod::doRHS``: weight, buoyancy with partial submergence, the drag along the rod and at
its ends, the added mass across it and at its ends) as the frame's balance about r:

    rows = [F; M_A + (R p_A) x F],  F = M_AA a_A + M_At alpha + f_v - f,  M_A likewise,

with M the rod's 6 x 6 mass matrix about end A (``cablefem.loads.rod.mass_matrix``), alpha the
angular acceleration, f the static loads and the drag, and f_v the inertial terms in the angular
velocity omega (``cablefem.loads.rod.turning``): the mass and added mass times each point's
centripetal acceleration and the gyroscopic term of the section's inertia (Newton-Euler's for the
rigid cylinder, Goldstein, Classical Mechanics, Sec. 5.5; the added mass on each point's whole
acceleration, Morison's). MoorDyn-C's rod leaves f_v out (``Rod::doRHS`` sums M a over its nodes
with the 6 x 6 mass matrix and no centripetal terms); it vanishes for a rod that does not turn.

A pinned rod is a free rod with a ``Pin`` at end A: a spring so stiff that the pin gives by 1e-6 of
the rod's length under a force of the rod's weight (a penalty, where statics replaces the force rows,
``cablefem.statics.rods.pin``), so that the rod turns about its pin and a run starts within that of
where statics put it. A rod pinned to a free body hands the body the force at its pin and no moment, at
the angle the file gives it on the body, as network statics has it
(``cablefem.statics.rods.carried_terms``).

Left out, as in ``cablefem.loads.rod``: a rod's seabed contact and the waterplane's moments of area;
a rod feels the current (a depth profile's at the middle of its submerged part), not the waves, as a
free body does.

``Loads`` sums parts: a free body's ``BodyLoads`` and its rods, each part's rows and mass matrix
added, one mechanism for a free rod (one part), a pinned rod (and its pin) and a body carrying rods.
"""

import numpy as np

from cablefem.loads.body import BodyLoads, frame_rates, linear_in_acceleration
from cablefem.loads.rod import drag, mass_matrix, static_loads, submerged_interval, turning
from cablefem.model.rod import rod_end_local


class RodPart:
    """The own loads of ``rod`` with its ends at ``end_a``, ``end_b`` (3,) [m] in its frame, in
    ``environment`` (water density, gravity, current); ``pinned``: it hands its frame its force at
    end A and no moment (a rod pinned to a free body)."""

    def __init__(self, rod, end_a, end_b, environment, pinned=False):
        self.rod, self.pinned = rod, pinned
        self.local = (np.asarray(end_a, dtype=float), np.asarray(end_b, dtype=float))
        self.rho, self.g = environment.water_density, environment.gravity
        self.weight = rod.mass * self.g  # [N], the balance's force scale
        self.current = np.asarray(environment.current, dtype=float)
        self.profile = environment.current_profile
        self.frame = np.eye(3)  # the angles turn the frame from this orientation (``RigidBody``)

    def _water(self, a, b):
        """The current (3,) [m/s]: uniform, or a depth profile's at the middle of the submerged part."""
        if self.profile is None:
            return self.current
        s0, s1 = submerged_interval(a[2], b[2])
        return self.profile.at(np.array(a[2] + 0.5 * (s0 + s1) * (b[2] - a[2])))[0].reshape(3)

    def _motion(self, X, V, A):
        """The ends a, b (3,), their velocities, end A's acceleration, omega and alpha (3,)."""
        R, dR, ddR, omega, alpha = frame_rates(self.frame, X, V, A)
        (p_a, p_b) = self.local
        ends = X[0] + R @ p_a, X[0] + R @ p_b
        velocities = V[0] + dR @ p_a, V[0] + dR @ p_b
        return ends, velocities, A[0] + ddR @ p_a, omega, alpha

    def residual(self, X, V, A):
        """The rod's rows (6,) in its frame's balance: inertial force and moment about the reference
        point less the loads, [N] and [N m], at pose X, rates V, accelerations A (2, 3) each."""
        rod = self.rod
        (a, b), (v_a, v_b), a_a, omega, alpha = self._motion(X, V, A)
        inertial = mass_matrix(a, b, rod, self.rho) @ np.concatenate([a_a, alpha])
        force, moment = turning(a, b, omega, rod, self.rho)
        force, moment = force + inertial[:3], moment + inertial[3:]
        for f, m in (static_loads(a, b, rod, self.rho, self.g),
                     drag(a, b, v_a, v_b, rod, self.rho, self._water(a, b))):
            force -= f
            moment -= m
        if self.pinned:
            moment = np.zeros(3)
        return np.concatenate([force, moment + np.cross(a - X[0], force)])

    def mass_matrix(self, X):
        """d(rows)/dA (6, 6) at pose X."""
        return linear_in_acceleration(self.residual, X)

    def energy(self, X, V):
        """Kinetic energy [J] of the rod and its added mass, 1/2 [v_A; omega] M [v_A; omega], and the
        potential of its weight at its middle and of its buoyancy, rho g A times the integral of the
        depth over its submerged axis (whose derivative is the buoyancy of ``static_loads``)."""
        rod = self.rod
        (a, b), (v_a, _), _, omega, _ = self._motion(X, V, np.zeros((2, 3)))
        rates = np.concatenate([v_a, omega])
        kinetic = 0.5 * rates @ mass_matrix(a, b, rod, self.rho) @ rates
        s0, s1 = submerged_interval(a[2], b[2])
        depth = -(a[2] + 0.5 * (s0 + s1) * (b[2] - a[2]))  # at the middle of the submerged part
        buoyancy = self.rho * self.g * rod.area * rod.length * (s1 - s0) * depth
        return kinetic + rod.mass * self.g * 0.5 * (a[2] + b[2]) + buoyancy


class Pin:
    """End A of a pinned rod held at ``position`` (3,) [m], the frame's reference point: a spring of
    ``stiffness`` [N/m] between them (``pin_stiffness``); its force acts at the reference point, no
    moment."""

    weight = 0.0

    def __init__(self, position, stiffness):
        self.position, self.stiffness = np.asarray(position, dtype=float), float(stiffness)
        self.frame = np.eye(3)

    def residual(self, X, V, A):
        """The pin's rows (6,): minus its pull k (p - r) on the reference point r."""
        return np.concatenate([self.stiffness * (X[0] - self.position), np.zeros(3)])

    def mass_matrix(self, X):
        """No mass (6, 6)."""
        return np.zeros((6, 6))

    def energy(self, X, V):
        """The spring's energy [J]."""
        gap = X[0] - self.position
        return 0.5 * self.stiffness * gap @ gap


#: how far [rod lengths] a pin gives under the rod's weight: stiffer, and the spring's round-off
#: k eps |r| (|r| the pin's distance from the origin) nears Newton's tolerance, 1e-8 of the weight
PIN_GIVE = 1e-6


def pin_stiffness(rod, gravity):
    """k [N/m]: the rod's weight (or 1 N) over ``PIN_GIVE`` of its length."""
    return max(rod.mass * gravity, 1.0) / (PIN_GIVE * rod.length)


class Loads:
    """The sum of ``parts`` (each with ``residual``, ``mass_matrix``, ``energy``, ``weight`` and
    ``frame``): the own loads of one rigid body made of them."""

    def __init__(self, parts):
        self.parts = list(parts)
        self.weight = sum(part.weight for part in self.parts)
        self._frame = np.eye(3)

    @property
    def frame(self):
        """R_0 (3, 3): the orientation the angles turn the body from (``RigidBody`` sets it)."""
        return self._frame

    @frame.setter
    def frame(self, value):
        self._frame = value
        for part in self.parts:
            part.frame = value

    def residual(self, X, V, A):
        """The parts' rows (6,) summed."""
        return sum(part.residual(X, V, A) for part in self.parts)

    def mass_matrix(self, X):
        """The parts' mass matrices (6, 6) summed."""
        return sum(part.mass_matrix(X) for part in self.parts)

    def energy(self, X, V):
        """The parts' energies [J] summed."""
        return sum(part.energy(X, V) for part in self.parts)


def body_loads(body, environment):
    """The own loads in a run of free ``body`` (``cablefem.model.network.Body``): a MoorDyn body's
    (``BodyLoads``) alone, a free or pinned rod's (``body.rod``), or the body's with the rods it
    carries (``body.rods``)."""
    if body.rod is not None:
        rod = RodPart(body.rod, rod_end_local(body.rod, "A"), rod_end_local(body.rod, "B"), environment)
        if not body.rod.pinned:
            return Loads([rod])
        return Loads([rod, Pin(body.position, pin_stiffness(body.rod, environment.gravity))])
    if not body.rods:
        return BodyLoads(body, environment)
    return Loads([BodyLoads(body, environment)] + [RodPart(rod, rod.end_a, rod.end_b, environment, rod.pinned)
                                                   for rod in body.rods])
