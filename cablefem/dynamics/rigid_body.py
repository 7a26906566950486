"""A rigid body's six unknowns stepped by a scheme: the body side of a ``BodyGroup``
(``cablefem.dynamics.body_group``).

The unknowns are the pose q = (r, theta) as two rows (2, 3): the reference point r [m] and the
angles theta [rad] of the body's turn from the orientation R_0 it starts in, R = R_0 Rx Ry Rz
(``cablefem.model.network``; Tait-Bryan angles, MoorDyn-C's convention, of an incremental rotation
as Cardona & Geradin 1988 take one from a reference configuration). The scheme (``cablefem.dynamics.scheme``) steps them as it steps a line's rows, with its
own arithmetic (BDF2, generalised-alpha, any registered one): the same ``begin``, ``point``,
``accept`` and ``error`` on (2, 3) arrays, so that the body's V and A are the rates and accelerations
of q that the scheme's finite differences give, and Newton's tangent is g_x (K + v_x C + a_x M)
as a line's is. Tait-Bryan angles are exact for large rotations away from pitch = +-90 deg, where
R's derivative loses a rank (gimbal lock; Shabana, Dynamics of Multibody Systems, Sec. 2.6): measured
from the start orientation, a body may start in any orientation (MoorDyn's bodyDrag.txt hangs at
pitch -90 deg) and turn by up to ``GIMBAL`` about its pitch axis from it; a run stops beyond.

What loads a body has is its ``loads`` object (``residual(X, V, A)`` (6,), ``mass_matrix(X)``
(6, 6), ``energy(X, V)``): a MoorDyn body's (``cablefem.loads.body.BodyLoads``), or a rod's. The
tangent of the rows in X and V is by central differences of ``residual`` (six unknowns: twelve
evaluations), in A exact (the rows are linear in A).
"""

import numpy as np

from cablefem.dynamics import policy
from cablefem.errors import ConvergenceError

#: the largest |pitch| [rad] a step may reach: 85 deg, short of the Tait-Bryan angles' singularity
GIMBAL = np.radians(85.0)
#: relative step of the central differences of the rows in the pose and the rates
DIFFERENCE = 1e-6


def angles_of(R):
    """The Tait-Bryan angles (roll, pitch, yaw) (3,) [rad] of R = Rx Ry Rz (3, 3)."""
    return np.array([np.arctan2(-R[1, 2], R[2, 2]), np.arcsin(np.clip(R[0, 2], -1.0, 1.0)),
                     np.arctan2(-R[0, 1], R[0, 0])])


class RigidBody:
    """The pose (2, 3), rates and accelerations of a rigid body stepped by ``scheme`` with record
    ``parameters``; ``loads`` its own loads; ``links`` [(member, end, local (3,))]: the string ends
    on its points, each at ``local`` in the body's frame; ``length`` [m]: its moments' lever arm."""

    def __init__(self, name, loads, pose, scheme, parameters, links, t0=0.0, velocity=None):
        self.name, self.loads, self.scheme, self.parameters = name, loads, scheme, parameters
        self.links = [(k, end, np.asarray(local, dtype=float)) for k, end, local in links]
        from cablefem.model.network import rotation

        pose = np.asarray(pose, dtype=float).reshape(2, 3)
        self.frame = rotation(pose[1])  # R_0: the angles are the turn from the start's orientation
        loads.frame = self.frame
        self.X = np.array([pose[0], np.zeros(3)])
        self.V = np.zeros((2, 3)) if velocity is None else np.asarray(velocity, dtype=float).reshape(2, 3).copy()
        self.A = np.zeros((2, 3))
        self.memory = np.zeros((scheme.memory, 2, 3))
        self.clock = np.zeros(1, policy.CLOCK)
        self.t = float(t0)
        self.length = max([1.0] + [float(np.linalg.norm(local)) for _, _, local in self.links])
        self.history = [(self.t, self.absolute(self.X))]  # (t, pose (6,)) after each accepted step

    # ------------------------------------------------------------------ placing its points
    def rotation(self, angles):
        """R = R_0 Rx Ry Rz (3, 3) at the turn ``angles`` (3,) [rad] from the start's orientation."""
        from cablefem.model.network import rotation

        return self.frame @ rotation(angles)

    def rotation_derivatives(self, angles):
        """R (3, 3) and dR/dtheta_j (3, 3, 3), j the last index, at ``angles`` (3,)."""
        from cablefem.statics.network import rotation_derivatives

        R, dR = rotation_derivatives(angles)
        return self.frame @ R, np.einsum("ab,bcj->acj", self.frame, dR)

    def absolute(self, X):
        """The pose (6,) of X (2, 3) in the scene's frame: the reference point and the Tait-Bryan angles
        (roll, pitch, yaw) [rad] of R_0 Rx Ry Rz."""
        return np.concatenate([X[0], angles_of(self.rotation(X[1]))])

    def pose_at(self, t):
        """The pose (6,) after the accepted step that ended at t [s] (the last one at or before t)."""
        times = [each for each, _ in self.history]
        k = int(np.searchsorted(times, t + 1e-9 * max(1.0, abs(t)), side="right")) - 1
        return self.history[max(k, 0)][1]

    # ------------------------------------------------------------------ the scheme, as a line's
    def begin(self, h):
        clock = self.clock
        clock["t"] = self.t
        self.guess = np.empty_like(self.X)
        self.scheme.begin(self.parameters, clock, self.X, self.V, self.A, self.memory, self.guess, h)
        self.factors = (float(clock["v_x"][0]), float(clock["a_x"][0]), float(clock["g_x"][0]))

    def point(self, X1):
        Xe, Ve, Ae = np.empty_like(X1), np.empty_like(X1), np.empty_like(X1)
        self.scheme.point(self.parameters, self.clock, self.X, self.V, self.A, self.memory, X1, Xe, Ve, Ae)
        return Xe, Ve, Ae

    def accept(self, h):
        if abs(self.X1[1, 1]) > GIMBAL:
            raise ConvergenceError(
                f"body '{self.name}': its pitch reached {np.degrees(self.X1[1, 1]):.1f} deg at t = {self.t + h:.6g} s; "
                "its Tait-Bryan angles (roll, pitch, yaw) are singular at +-90 deg: turn the body's frame so that "
                "it does not pitch through 90 deg")
        X, V, A, memory = self.X.copy(), self.V.copy(), self.A.copy(), self.memory.copy()
        self.scheme.accept(self.parameters, self.clock, X, V, A, memory, self.X1)
        self.X, self.V, self.A, self.memory = X, V, A, memory
        self.t += h
        self.clock["t"], self.clock["h_before"], self.clock["last_h"] = self.t, h, h
        self.history.append((self.t, self.absolute(self.X)))

    # ------------------------------------------------------------------ rows and tangent
    def evaluate(self, tangent):
        """Its own rows ``rows`` (6,) at the evaluation point of the trial pose ``X1`` and, with
        ``tangent``, their derivative in X1 ``tangent`` (6, 6) (else None); R and dR/dtheta (3, 3, 3)
        there (``arm``, ``turn``)."""
        Xe, _, _ = self.point(self.X1)
        self.R, self.turn = self.rotation_derivatives(Xe[1])
        self.rows, self.tangent = self.rows_and_tangent(self.X1, tangent)

    def arm(self, local):
        """The lever arm R p (3,) of the point at ``local`` at the last evaluation point [m]."""
        return self.R @ local

    def rows_and_tangent(self, X1, tangent):
        """Its own rows (6,) at the evaluation point of trial pose X1 and, with ``tangent``, their
        derivative in X1 (6, 6): g_x (K + v_x C + a_x M)."""
        Xe, Ve, Ae = self.point(X1)
        rows = self.loads.residual(Xe, Ve, Ae)
        if not tangent:
            return rows, None
        v_x, a_x, g_x = self.factors
        K, C = np.empty((6, 6)), np.empty((6, 6))
        for j in range(6):
            for matrix, state in ((K, Xe), (C, Ve)):
                step = DIFFERENCE * max(1.0, abs(state.flat[j]))
                plus, minus = state.copy(), state.copy()
                plus.flat[j] += step
                minus.flat[j] -= step
                args_plus = [Xe, Ve, Ae]
                args_minus = [Xe, Ve, Ae]
                index = 0 if state is Xe else 1
                args_plus[index], args_minus[index] = plus, minus
                matrix[:, j] = (self.loads.residual(*args_plus) - self.loads.residual(*args_minus)) / (2 * step)
        M = self.loads.mass_matrix(Xe)
        return rows, g_x * (K + v_x * C + a_x * M)

    def initial_acceleration(self, line_rows):
        """A (2, 3) from the body's balance at its state with the lines' rows ``line_rows`` (6,) (their
        force and moment on the body, as rows: minus the pull)."""
        rows = self.loads.residual(self.X, self.V, np.zeros((2, 3))) + line_rows
        return np.linalg.solve(self.loads.mass_matrix(self.X), -rows).reshape(2, 3)

    # ------------------------------------------------------------------ undo
    def snapshot(self):
        return (self.t, self.X.copy(), self.V.copy(), self.A.copy(), self.memory.copy(), self.clock.copy(),
                len(self.history))

    def restore(self, snapshot):
        self.t, X, V, A, memory, clock, kept = snapshot
        self.X, self.V, self.A, self.memory, self.clock = X.copy(), V.copy(), A.copy(), memory.copy(), clock.copy()
        del self.history[kept:]
