"""A free rigid body's own loads in a run: its inertia, added mass, weight, buoyancy, waterplane, drag
and steady external load (MoorDyn-C's ``Body::doRHS`` and ``Body::initializeUnfreeBody``), as the
residual rows of its six unknowns.

The unknowns are the reference point r (3,) [m] and the angles theta (3,) [rad] of the body's turn
from the orientation it starts in, R = R_0 Rx(roll) Ry(pitch) Rz(yaw) (``frame`` R_0;
``cablefem.model.network.rotation``: MoorDyn-C's convention, the one network statics solves in). A body's rows are its balance in the scene's frame, force and moment
about the reference point, as network statics has them; the lines' pull enters where the body's
points are (``cablefem.dynamics.body_group``). The rigid body's inertia is Newton-Euler's, exact for
large rotations: the centre of gravity at c_w = R c accelerates as a_g = r'' + R'' c, the angular
velocity and acceleration in the scene's frame are [omega]x = R' R^T and [alpha]x = R'' R^T + R' R'^T,
and the moment of the inertial forces about r is c_w x m a_g + I_w alpha + omega x I_w omega with
I_w = R diag(I) R^T (Goldstein, Classical Mechanics, Sec. 5.5: Euler's equations). MoorDyn-C leaves
out the last term and the moment of the centrifugal force (a small-rotation-rate simplification);
both vanish in the pure heave and small pitch of its decay tests.

MoorDyn-C's hydrodynamics of a body: added mass rho V Ca about the reference point in body axes
(translation; its rotational entries are zero as MoorDyn-C reads them, kept general here), drag
0.5 rho R diag(CdA) R^T |u| u on the reference point's velocity u relative to the current
(translation) and on -omega (rotation), weight and buoyancy at the centre of gravity as MoorDyn-C has
them, or buoyancy at a centre of buoyancy and a waterplane's heave restoring -rho g A_wp z where a
TOML gives them (as network statics has them).
"""

import numpy as np

from cablefem.model.network import rotation_rates


def vex(skew):
    """The vector a of a skew matrix [a]x."""
    return np.array([skew[2, 1] - skew[1, 2], skew[0, 2] - skew[2, 0], skew[1, 0] - skew[0, 1]]) * 0.5


def frame_rates(frame, X, V, A):
    """R = R_0 Rx Ry Rz (``frame`` R_0) and its first and second time derivatives (3, 3) at pose X,
    rates V, accelerations A (2, 3) each, and the angular velocity omega and acceleration alpha (3,) in
    the scene's frame: [omega]x = R' R^T, [alpha]x = R'' R^T + R' R'^T."""
    R, dR, ddR = (frame @ each for each in rotation_rates(X[1], V[1], A[1]))
    return R, dR, ddR, vex(dR @ R.T), vex(ddR @ R.T + dR @ dR.T)


def linear_in_acceleration(residual, X):
    """d(rows)/dA (6, 6) at pose X of ``residual(X, V, A)`` (6,), rows linear in A: its columns at
    unit accelerations, at rest."""
    zero = np.zeros((2, 3))
    base = residual(X, zero, zero)
    out = np.empty((6, 6))
    for j in range(6):
        A = np.zeros(6)
        A[j] = 1.0
        out[:, j] = residual(X, zero, A.reshape(2, 3)) - base
    return out


class BodyLoads:
    """The own loads of free ``body`` (``cablefem.model.network.Body``) in ``environment`` (water
    density, gravity, current)."""

    def __init__(self, body, environment):
        self.body = body
        self.rho, self.g = environment.water_density, environment.gravity
        self.weight = body.mass * self.g  # [N], the balance's force scale
        self.added = self.rho * body.volume * body.Ca  # (6,) [kg], about the reference point, body axes
        self.current = np.asarray(environment.current, dtype=float)
        self.frame = np.eye(3)  # the angles turn the body from this orientation (``RigidBody``)
        self.profile = environment.current_profile

    def _water(self, z):
        """The current (3,) [m/s] at height z [m]."""
        if self.profile is not None:
            return self.profile.at(np.array(z))[0].reshape(3)
        return self.current

    def kinematics(self, X, V, A):
        """R, the angular velocity omega and acceleration alpha (3,) in the scene's frame, and the
        centre of gravity's acceleration (3,), at pose X, rates V, accelerations A (2, 3) each."""
        R, _, ddR, omega, alpha = frame_rates(self.frame, X, V, A)
        return R, omega, alpha, A[0] + ddR @ self.body.cg

    def residual(self, X, V, A):
        """The body's own rows (6,): inertial force and moment about the reference point less the
        loads, [N] and [N m], at pose X, rates V, accelerations A (2, 3) each."""
        body, rho, g = self.body, self.rho, self.g
        R, omega, alpha, a_g = self.kinematics(X, V, A)
        c_w = R @ body.cg
        inertia_w = (R * body.inertia) @ R.T
        force = body.mass * a_g + (R * self.added[:3]) @ (R.T @ A[0])
        moment = np.cross(c_w, body.mass * a_g) + inertia_w @ alpha + np.cross(omega, inertia_w @ omega)
        moment += (R * self.added[3:]) @ (R.T @ alpha)
        weight = np.array([0.0, 0.0, -body.mass * g])
        buoyancy = np.array([0.0, 0.0, rho * g * body.volume])
        force -= weight + buoyancy + body.force
        force[2] += rho * g * body.waterplane_area * X[0, 2]
        moment -= np.cross(c_w, weight) + np.cross(R @ body.cb, buoyancy) + body.moment
        if np.any(body.CdA):
            u = self._water(X[0, 2]) - V[0]
            force -= 0.5 * rho * (R * body.CdA[:3]) @ (R.T @ u) * np.sqrt(u @ u)
            moment += 0.5 * rho * (R * body.CdA[3:]) @ (R.T @ omega) * np.sqrt(omega @ omega)
        return np.concatenate([force, moment])

    def mass_matrix(self, X):
        """d(rows)/dA (6, 6) at pose X (the rows are linear in A): the rigid body's and the added mass
        in the unknowns' coordinates."""
        return linear_in_acceleration(self.residual, X)

    def energy(self, X, V):
        """Kinetic and potential energy [J] at pose X and rates V (2, 3): translation of the centre
        of gravity and rotation about it; weight at the centre of gravity, buoyancy at the centre of
        buoyancy, the waterplane's spring and the steady external force (the added mass's share
        where it is the same on the three axes)."""
        body, rho, g = self.body, self.rho, self.g
        R, dR, _, omega, _ = frame_rates(self.frame, X, V, np.zeros((2, 3)))
        v_g = V[0] + dR @ body.cg
        omega_b = R.T @ omega
        kinetic = 0.5 * body.mass * v_g @ v_g + 0.5 * omega_b @ (body.inertia * omega_b)
        kinetic += 0.5 * V[0] @ (R * self.added[:3]) @ (R.T @ V[0])
        z_g, z_b = X[0, 2] + (R @ body.cg)[2], X[0, 2] + (R @ body.cb)[2]
        potential = (body.mass * g * z_g - rho * g * body.volume * z_b
                     + 0.5 * rho * g * body.waterplane_area * X[0, 2] ** 2 - body.force @ X[0])
        return kinetic + potential
