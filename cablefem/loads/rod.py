"""A rigid rod's own loads (MoorDyn's RODS; ``cablefem.model.rod``): weight, buoyancy with partial
submergence, the transverse drag along it and the axial drag at its ends, and its mass matrix with
the added mass across it and at its ends.

MoorDyn-C's ``Rod::doRHS`` (Rod.cpp) lumps these on the rod's NumSegs + 1 nodes: the dry weight
m_i g, the buoyancy of the submerged fraction VOF of each node's volume (its side pressure) plus the
pressure rho g A |z| on each submerged end, the drag 1/2 rho Cd d dL |v_p| v_p of the flow across
the rod and 1/2 rho A CdEnd |v_q| v_q along it at each submerged end. The side and end pressures of
a submerged part sum to rho g times its volume, upward at its centroid (Archimedes); here they are
integrated along the axis instead of lumped: the submerged part of the rod is the interval of its
axis below the still water surface z = 0, its buoyancy rho g A L f at the interval's midpoint. What
is left out: the waterplane's and the ends' moments of area (terms in d^4 of Rod.cpp's ``Mext``,
small against the buoyancy's moment in d^2 L^2 for a slender rod) and seabed contact of a rod.

A rod is a rigid body: these are its resultant force and moment about its end A, the loads a
network's rigid-body balance takes (``cablefem.statics.rods``), not loads per unit length of a
finite element line; the load catalog's lines never see a rod.
"""

import numpy as np


def submerged_interval(z_a, z_b):
    """(s0, s1): the part 0 <= s0 <= s <= s1 <= 1 of the axis r(s) = A + s (B - A) below z = 0,
    for end heights ``z_a``, ``z_b`` [m]; (0, 0) if the rod is out of the water."""
    if z_a <= 0.0 and z_b <= 0.0:
        return 0.0, 1.0
    if z_a >= 0.0 and z_b >= 0.0:
        return 0.0, 0.0
    crossing = z_a / (z_a - z_b)  # where z(s) = 0
    return (0.0, crossing) if z_a < 0.0 else (crossing, 1.0)


def static_loads(end_a, end_b, rod, water_density, gravity):
    """The weight and buoyancy of ``rod`` with its ends at ``end_a``, ``end_b`` (3,) [m]: its
    resultant force (3,) [N] and moment (3,) [N m] about end A. The weight m L g acts at the middle
    of the axis, the buoyancy rho g A L (s1 - s0) at the middle of its submerged part
    (``submerged_interval``)."""
    a, b = np.asarray(end_a, dtype=float), np.asarray(end_b, dtype=float)
    axis = b - a
    L = rod.length
    weight = np.array([0.0, 0.0, -rod.mass * gravity])
    s0, s1 = submerged_interval(a[2], b[2])
    buoyancy = np.array([0.0, 0.0, water_density * gravity * rod.area * L * (s1 - s0)])
    moment = np.cross(0.5 * axis, weight) + np.cross(0.5 * (s0 + s1) * axis, buoyancy)
    return weight + buoyancy, moment


def drag(end_a, end_b, velocity_a, velocity_b, rod, water_density, current=np.zeros(3), points=16):
    """The drag of still water or a uniform ``current`` (3,) [m/s] on ``rod`` moving with its end
    velocities ``velocity_a``, ``velocity_b`` (3,) [m/s] (a rigid motion: linear along the axis):
    the transverse drag 1/2 rho Cd d |v_p| v_p per unit length integrated along the submerged axis
    (``points`` Gauss points) and the axial drag 1/2 rho A CdEnd |v_q| v_q at each submerged end
    (Rod.cpp's Dp and Dq); force (3,) [N] and moment (3,) [N m] about end A."""
    a, b = np.asarray(end_a, dtype=float), np.asarray(end_b, dtype=float)
    va, vb = np.asarray(velocity_a, dtype=float), np.asarray(velocity_b, dtype=float)
    axis = b - a
    L = float(np.linalg.norm(axis))
    q = axis / L
    t = rod.type
    s0, s1 = submerged_interval(a[2], b[2])
    nodes, weights = np.polynomial.legendre.leggauss(points)
    s = s0 + 0.5 * (s1 - s0) * (nodes + 1.0)
    w = 0.5 * (s1 - s0) * L * weights
    relative = current - (va + s[:, None] * (vb - va))
    across = relative - np.outer(relative @ q, q)
    per_length = 0.5 * water_density * t.Cd * t.diameter * np.linalg.norm(across, axis=1)[:, None] * across
    force = (w[:, None] * per_length).sum(axis=0)
    moment = (w[:, None] * np.cross(s[:, None] * axis, per_length)).sum(axis=0)
    for at, v, arm in ((a, va, 0.0), (b, vb, 1.0)):
        if at[2] < 0.0:
            along = ((current - v) @ q) * q
            end = 0.5 * water_density * rod.area * t.CdEnd * np.linalg.norm(along) * along
            force += end
            moment += np.cross(arm * axis, end)
    return force, moment


def mass_matrix(end_a, end_b, rod, water_density):
    """The rod's 6 x 6 mass matrix about end A [kg, kg m, kg m^2] (force and moment against the
    acceleration and angular acceleration of a frame at A): its own mass, the added mass rho Ca A
    across its submerged axis and rho CaEnd V_end along it at each submerged end, V_end = (2/3) pi
    (d/2)^3 (Rod.cpp's M[i], lumped there on its nodes and integrated here along the axis), and
    the cylinder's own inertia about its axis m r^2 / 2 and across it m r^2 / 4 per unit length."""
    a, b = np.asarray(end_a, dtype=float), np.asarray(end_b, dtype=float)
    axis = b - a
    L = float(np.linalg.norm(axis))
    q = axis / L
    Q, I3 = np.outer(q, q), np.eye(3)
    t, r = rod.type, 0.5 * rod.type.diameter
    s0, s1 = submerged_interval(a[2], b[2])
    m = rod.mass / L  # per unit length
    added = water_density * t.Ca * rod.area  # per unit length, across the axis, where submerged

    def skew(v):
        return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])

    # moments of the mass along the axis: int mu(s) s^k ds over s in [0, L], k = 0, 1, 2
    own = [m * L, m * L ** 2 / 2.0, m * L ** 3 / 3.0]
    wet = [added * L ** (k + 1) * (s1 ** (k + 1) - s0 ** (k + 1)) / (k + 1) for k in range(3)]
    block = np.zeros((6, 6))
    translation = own[0] * I3 + wet[0] * (I3 - Q)
    first = own[1] * I3 + wet[1] * (I3 - Q)  # int mu s ds, acting through the arm s q
    second = own[2] + wet[2]
    block[:3, :3] = translation
    # a point at s q moves with a + alpha x (s q): force = M (a - s [q]x alpha), moment = s q x force
    block[:3, 3:] = -first @ skew(q)
    block[3:, :3] = skew(q) @ first
    block[3:, 3:] = second * (skew(q) @ -skew(q)) + m * L * r * r * (0.5 * Q + 0.25 * (I3 - Q))
    volume = 2.0 / 3.0 * np.pi * r ** 3
    for end, arm in ((a, 0.0), (b, L)):
        if end[2] < 0.0:
            mass = water_density * t.CaEnd * volume * Q
            block[:3, :3] += mass
            block[:3, 3:] += -arm * mass @ skew(q)
            block[3:, :3] += arm * skew(q) @ mass
    return block


def turning(end_a, end_b, omega, rod, water_density):
    """The inertial force (3,) [N] and moment about end A (3,) [N m] of the rod turning at ``omega``
    (3,) [rad/s], what ``mass_matrix`` leaves out: its mass and added mass (as ``mass_matrix`` has
    them) times each point's centripetal acceleration omega x (omega x s q), and the gyroscopic
    omega x I_r omega of its section's inertia I_r (Newton-Euler's; the added mass on each point's
    acceleration across the rod and along it at its ends, Morison's as Rod.cpp has it)."""
    a, b = np.asarray(end_a, dtype=float), np.asarray(end_b, dtype=float)
    L = float(np.linalg.norm(b - a))
    q = (b - a) / L
    Q, I3 = np.outer(q, q), np.eye(3)
    t, r = rod.type, 0.5 * rod.type.diameter
    s0, s1 = submerged_interval(a[2], b[2])
    m = rod.mass / L
    added = water_density * t.Ca * rod.area
    w = np.cross(omega, np.cross(omega, q))  # the centripetal acceleration at s = 1 m along the axis
    across = w - (w @ q) * q
    first = m * L ** 2 / 2.0 + added * L ** 2 * (s1 ** 2 - s0 ** 2) / 2.0  # int mu s ds; across: with the added mass
    second = m * L ** 3 / 3.0 + added * L ** 3 * (s1 ** 3 - s0 ** 3) / 3.0
    along = m * L ** 2 / 2.0 + (water_density * t.CaEnd * 2.0 / 3.0 * np.pi * r ** 3 * L if b[2] < 0.0 else 0.0)
    force = first * across + along * (w @ q) * q
    section = m * L * r * r * (0.5 * Q + 0.25 * (I3 - Q))
    moment = second * np.cross(q, across) + np.cross(omega, section @ omega)
    return force, moment
