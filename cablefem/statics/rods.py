"""Rods in a network's statics (``cablefem.statics.network``): a free or pinned rod as a coupling
unknown, and the rods a free body carries.

A free rod's body (``cablefem.model.rod.rod_body``) has six unknowns like any free body, but they are
the positions of its two ends, q = (A, B), not a pose: a rod's turn about its own axis moves nothing
(every load acts on the axis), and the ends carry no angle that could meet a gimbal's pole as a
floating rod rights itself. Its six equations are the balance of forces (3) and of moments about end
A (3, of which the part along the axis is identically zero) with the rod's length added along the
axis, k (|B - A| - L) u: zero exactly where the moments balance and the rod has its length. A pinned
rod's force rows are instead k (A_0 - A): end A stays where the file puts it, the pin's reaction is
whatever balances the forces, and the moments about A do not see it.

The rod's loads are ``cablefem.loads.rod.static_loads``; their Jacobian with respect to the six
unknowns is taken by central differences (six evaluations of a closed form, against each string's
exact condensed stiffness, which dominates the coupling's Jacobian).
"""

import numpy as np

from cablefem.loads.rod import static_loads
from cablefem.model.network import rotation
from cablefem.model.rod import axis_angles

#: the relative step of the central differences, times the rod's length
STEP = 1e-7


def start(body):
    """q (6,) of a rod's body where the file puts it: its two ends (3,) each [m]."""
    a = np.asarray(body.position, dtype=float)
    return np.concatenate([a, a + rotation(body.rotation) @ np.array([0.0, 0.0, body.rod.length])])


def place(body, local, q):
    """Where the point at ``local`` (its body's frame: (0, 0, s L)) of a rod's body is at q (6,) and
    d position / d q (3, 6)."""
    s = local[2] / body.rod.length
    T = np.hstack([(1.0 - s) * np.eye(3), s * np.eye(3)])
    return (1.0 - s) * q[:3] + s * q[3:], T


def pose(body, q):
    """(x, y, z, roll, pitch, yaw) of a rod's body at q (6,): end A and the turn of z onto the axis."""
    return np.concatenate([q[:3], axis_angles(q[3:] - q[:3])])


def _differences(function, q, step):
    """The Jacobian (m, 6) of ``function`` (6,) -> (m,) at q by central differences."""
    columns = []
    for j in range(6):
        dq = np.zeros(6)
        dq[j] = step
        columns.append((function(q + dq) - function(q - dq)) / (2.0 * step))
    return np.stack(columns, axis=1)


def rod_terms(body, q, rho, g, stiffness):
    """A free or pinned rod's own rows (6,) (its weight and buoyancy; its length along the axis)
    and their Jacobian (6, 6) at q (6,); ``stiffness`` [N] scales the length's and the pin's rows."""
    rod = body.rod

    def rows(x):
        force, moment = static_loads(x[:3], x[3:], rod, rho, g)
        axis = x[3:] - x[:3]
        length = np.linalg.norm(axis)
        return np.concatenate([force, moment + stiffness * (length - rod.length) * axis / length])

    r = rows(q)
    J = _differences(rows, q, STEP * rod.length)
    return r, J


def pin(body, q, r, J, o, stiffness):
    """A pinned rod's force rows of r (size,) and J (size, size) at offset ``o`` replaced by
    k (A_0 - A): the pin holds end A, its reaction takes the forces."""
    r[o:o + 3] = stiffness * (body.position - q[o:o + 3])
    J[o:o + 3] = 0.0
    J[o:o + 3, o:o + 3] = -stiffness * np.eye(3)


def carried_terms(body, q, rho, g):
    """The weight and buoyancy of the rods fixed on a free ``body`` at its pose q (6,): the force
    (3,) and moment about its reference point (3,) as rows (6,), and their Jacobian (6, 6). A rod
    pinned to the body hands it its force at end A, no moment (it turns to balance its own)."""

    def rows(x):
        R = rotation(x[3:])
        out = np.zeros(6)
        for rod in body.rods:
            a, b = x[:3] + R @ rod.end_a, x[:3] + R @ rod.end_b
            force, moment = static_loads(a, b, rod, rho, g)
            out[:3] += force
            out[3:] += np.cross(a - x[:3], force) + (0.0 if rod.pinned else moment)
        return out

    size = max(rod.length for rod in body.rods) or 1.0
    return rows(q), _differences(rows, q, STEP * size)


def limit(net, step):
    """The Newton ``step`` (size,) of a network's coupling unknowns, scaled so that no body carrying
    rods and no rod moves by more than its longest rod: a rod out of the water has no buoyancy to
    stiffen its heave, and Newton's step from there falls through the water column (MoorDyn's
    BodiesAndRods.dat starts its float's rods above the surface). Unchanged without rods."""
    scale = 1.0
    for name in net.bodies:
        body = net.scene.bodies[name]
        carried = (body.rod,) if body.rod is not None else tuple(body.rods)
        if carried:
            o = net.offsets[name]
            move = max(np.linalg.norm(step[o:o + 3]), np.linalg.norm(step[o + 3:o + 6]) if body.rod else 0.0)
            scale = min(scale, max(rod.length for rod in carried) / move if move > 0.0 else 1.0)
    return step if scale >= 1.0 else scale * step
