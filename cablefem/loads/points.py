"""Point bodies on a line: clump weights, buoys and connectors at its vertices (MoorDyn's points).

A ``Joint`` (``cablefem.model.line``) of mass m, volume V, drag area CdA and added-mass coefficient Ca
sits at one vertex x of the line. It adds the concentrated force

    F = (-m g + rho g V phi(z)) e_z + F_ext + 1/2 rho CdA |u| u - (m + Ca rho V) a,   u = U - v,

at that vertex: weight, buoyancy, a steady external force F_ext (MoorDyn's FX FY FZ, ``pointF``),
drag in the relative velocity u (U the current, v the point's velocity) and the inertia of its mass
and added mass, all isotropic as MoorDyn-C's points have them (Point.cpp). In waves
(``cablefem.waves``) the water's velocity u_w joins the current, u = U + u_w - v, and its
acceleration a_w adds the fluid inertia (1 + Ca) rho V a_w (Froude-Krylov and added mass; MoorDyn-C's
points leave it out, ``Point.cpp`` marks it to do); a point above the instantaneous surface has no
drag, fluid inertia or added mass (its buoyancy stays the still-water one below). The buoyancy takes
the volume as a sphere of radius R = (3 V / 4 pi)^(1/3)
whose submerged fraction at centre height z is phi = h^2 (3 R - h) / (4 R^3), h = clip(R - z, 0,
2 R): continuous and differentiable through the surface, so a buoy can float in equilibrium;
fully submerged (z <= -R) it is MoorDyn's V rho g. The point has no seabed contact of its own: the
line's elements on both sides carry it there.

In the weak form a concentrated force is a Dirac load, so this is the catalog's one "node" load:
it is evaluated at the vertices, not at quadrature points, and its rows go straight into the
residual at the vertex (``LineSystem.evaluate``, ``cablefem.compiled.kernels.assemble_nodes``). Points at a
prescribed end are not loaded: the end's motion is given, and the force reported there is the
line's.
"""

import math

import numpy as np
from numba import njit

from cablefem.loads import LoadSpec, Terms
from cablefem.loads.current import PROFILE_FIELDS, current_at, no_profile, relative_water


def sphere_fraction(z, radius):
    """Submerged fraction phi (k,) of spheres of ``radius`` (k,) [m] centred at height z (k,) [m]
    and dphi/dz (k,) [1/m]; a zero radius is fully submerged (phi = 1)."""
    r = np.where(radius > 0.0, radius, 1.0)
    h = np.clip(r - z, 0.0, 2.0 * r)
    fraction = h * h * (3.0 * r - h) / (4.0 * r ** 3)
    slope = -3.0 * h * (2.0 * r - h) / (4.0 * r ** 3)
    return np.where(radius > 0.0, fraction, 1.0), np.where(radius > 0.0, slope, 0.0)


def sphere_integral(z, radius):
    """G(z) (k,) with dG/dz = phi: z below the sphere's band, 0 above it (the buoyancy's potential
    energy is -rho g V G(z))."""
    r = np.where(radius > 0.0, radius, 1.0)
    h = np.clip(r - z, 0.0, 2.0 * r)
    # int phi dz from above the band (h = 0) down to z, as a function of h: -int_0^h phi dh
    inside = -(h ** 3 * r - h ** 4 / 4.0) / (4.0 * r ** 3)
    below = z <= -r
    return np.where(radius > 0.0, np.where(below, z, inside), z)


class PointLoads:
    """The joints of one line: vertex index (k,) and per joint its dry weight m g [N], buoyancy
    rho g V [N], sphere radius [m], drag factor rho CdA / 2 [kg/m], inertia m + Ca rho V [kg] and
    external force (k, 3) [N]; the current is uniform (3,) [m/s] or a ``CurrentProfile``
    (``profile``) at each point's height; ``sea``: the waves (``cablefem.waves.Sea``), None in still
    water."""

    name = "points"
    rule = "node"

    def __init__(self, vertices, joints, water_density, gravity, current=(0.0, 0.0, 0.0), profile=None, sea=None):
        self.vertices = np.asarray(vertices, dtype=np.int64)
        self.names = [joint.name for joint in joints]
        mass = np.array([joint.mass for joint in joints], dtype=float)
        volume = np.array([joint.volume for joint in joints], dtype=float)
        self.dry = mass * gravity
        self.buoyancy = water_density * gravity * volume
        self.radius = np.cbrt(3.0 * volume / (4.0 * math.pi))
        self.drag = 0.5 * water_density * np.array([joint.CdA for joint in joints], dtype=float)
        self.added = water_density * volume * np.array([joint.Ca for joint in joints], dtype=float)
        self.inertia = mass + self.added
        self.fluid = water_density * volume + self.added  # (1 + Ca) rho V
        self.external = np.array([joint.force for joint in joints], dtype=float).reshape(-1, 3)
        self.current = np.asarray(current, dtype=float)
        self.profile = profile
        self.sea = sea

    def evaluate(self, state, jacobian=True):
        """Forces (3, k) at the points of ``state`` (positions, velocities and accelerations (3, k))."""
        z = state.r[2]
        k = z.shape[0]
        fraction, slope = sphere_fraction(z, self.radius)
        force = self.external.T.copy()
        force[2] += -self.dry + self.buoyancy * fraction
        terms = Terms(force=force)
        if jacobian:
            terms.force_r = np.zeros((3, 3, k))
            terms.force_r[2, 2] = self.buoyancy * slope
        if state.v is not None and self.sea is not None:
            return self._in_waves(state, terms, jacobian)
        if state.v is not None and np.any(self.drag):
            if self.profile is None:
                u = self.current[:, None] - state.v
            else:
                U, slope = self.profile.at(z)
                u = U - state.v
            speed = np.sqrt(np.einsum("ck,ck->k", u, u))
            force += self.drag * speed * u
            if jacobian:
                unit = np.divide(u, speed, out=np.zeros_like(u), where=speed > 0.0)
                df_du = self.drag * (speed * np.eye(3)[:, :, None] + speed * unit[:, None] * unit[None, :])
                terms.force_v = -df_du
                if self.profile is not None:  # u = U(z) - v: df/dz = df/du dU/dz
                    terms.force_r[:, 2] += np.einsum("abk,bk->ak", df_du, slope)
        if state.a is not None and np.any(self.inertia):
            force -= self.inertia * state.a
            if jacobian:
                terms.force_a = -self.inertia * np.broadcast_to(np.eye(3)[:, :, None], (3, 3, k))
        return terms

    def _in_waves(self, state, terms, jacobian):
        """The terms with drag on U + u_w - v, the fluid inertia (1 + Ca) rho V a_w, the inertia of the
        mass and added mass (the added mass, drag and fluid inertia only below the surface)."""
        kin = self.sea.kinematics(state.r.T, state.t, jacobian)
        wet = kin.wet.astype(float)
        current, slope = ((np.broadcast_to(self.current[:, None], state.r.shape), None) if self.profile is None
                          else self.profile.at(state.r[2]))
        u = current + kin.velocity.T - state.v
        speed = np.sqrt(np.einsum("ck,ck->k", u, u))
        a = np.zeros_like(state.v) if state.a is None else state.a
        inertia = self.inertia - (1.0 - wet) * self.added
        terms.force += wet * (self.drag * speed * u + self.fluid * kin.acceleration.T) - inertia * a
        if not jacobian:
            return terms
        unit = np.divide(u, speed, out=np.zeros_like(u), where=speed > 0.0)
        df_du = wet * self.drag * (speed * np.eye(3)[:, :, None] + speed * unit[:, None] * unit[None, :])
        gradient = np.moveaxis(kin.velocity_gradient, 0, -1)
        if slope is not None:
            gradient[:, 2] += slope
        terms.force_r += np.einsum("abk,bck->ack", df_du, gradient) \
            + wet * self.fluid * np.moveaxis(kin.acceleration_gradient, 0, -1)
        terms.force_v = -df_du
        terms.force_a = -inertia * np.broadcast_to(np.eye(3)[:, :, None], (3, 3, len(wet)))
        return terms

    def energy(self, state):
        """Potential energy [J] (k,) of the points at their vertices (``state``: their kinematics,
        (3, k)): weight m g z less buoyancy, less the external force's work F . r."""
        z = state.r[2]
        return self.dry * z - self.buoyancy * sphere_integral(z, self.radius) - np.einsum("kc,ck->k", self.external,
                                                                                          state.r)

    def params(self):
        """The compiled face's parameters per point (``SPEC.params``), each (k,)."""
        k = len(self.dry)
        profile = no_profile(k) if self.profile is None else self.profile.params(k)
        return {"dry": self.dry, "buoyancy": self.buoyancy, "radius": self.radius, "drag": self.drag,
                "inertia": self.inertia, "external": self.external, "current": np.broadcast_to(self.current, (k, 3)),
                **profile, "waves": np.full(k, self.sea is not None), "added": self.added, "fluid": self.fluid}


@njit(cache=True, _nrt=False)
def point_point(ctx, p, old, new, state, hold, out):
    """The compiled face: one point's force at its vertex (``ctx.r``, ``ctx.v``, ``ctx.a``)."""
    q = p.points
    if not q.active:
        return
    fraction, slope = 1.0, 0.0
    radius = q.radius
    if radius > 0.0:
        h = min(max(radius - ctx.r[2], 0.0), 2.0 * radius)
        cube = 4.0 * radius * radius * radius
        fraction = h * h * (3.0 * radius - h) / cube
        slope = -3.0 * h * (2.0 * radius - h) / cube
    out.f[0] += q.external[0]
    out.f[1] += q.external[1]
    out.f[2] += q.external[2] - q.dry + q.buoyancy * fraction
    if ctx.jac:
        out.A[2, 2] += -q.buoyancy * slope
    if q.waves:
        _in_waves(ctx, q, out)
        return
    if q.drag != 0.0:
        current, slope = ctx.points.current, ctx.points.slope
        if q.profile_n == 0:
            for a in range(3):
                current[a] = q.current[a]
        else:
            current_at(ctx.r[2], q.profile_n, q.profile_z, q.profile_u, current, slope)
        u0, u1, u2 = current[0] - ctx.v[0], current[1] - ctx.v[1], current[2] - ctx.v[2]
        speed = np.sqrt(u0 * u0 + u1 * u1 + u2 * u2)
        c = q.drag * speed
        out.f[0] += c * u0
        out.f[1] += c * u1
        out.f[2] += c * u2
        if ctx.jac and speed > 0.0:
            # A = -(f_v v_x): f_v = -drag (speed I + u u^T / speed)
            w = ctx.v_x * q.drag
            inv = 1.0 / speed
            uu = (u0, u1, u2)
            for a in range(3):
                out.A[a, a] += w * speed
                for b in range(3):
                    out.A[a, b] += w * uu[a] * uu[b] * inv
            if q.profile_n != 0:  # A -= f_r: f_r[:, 2] = drag (speed I + u u^T / speed) dU/dz
                for a in range(3):
                    out.A[a, 2] -= q.drag * (speed * slope[a] + uu[a] * inv * (uu[0] * slope[0] + uu[1] * slope[1]
                                                                                 + uu[2] * slope[2]))
    if q.inertia != 0.0:
        for a in range(3):
            out.f[a] -= q.inertia * ctx.a[a]
            if ctx.jac:
                out.A[a, a] += ctx.a_x * q.inertia


@njit(cache=True, _nrt=False)
def _in_waves(ctx, q, out):
    """``PointLoads._in_waves`` at one point: the water's kinematics are in the context."""
    s = ctx.points
    current, slope, w, D = s.current, s.slope, s.w, s.D
    relative_water(ctx, q.profile_n, q.current, q.profile_z, q.profile_u, current, slope, w)
    wet = 1.0 if ctx.wet else 0.0
    speed = np.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    inertia = q.inertia - (1.0 - wet) * q.added
    for a in range(3):
        out.f[a] += wet * (q.drag * speed * w[a] + q.fluid * ctx.water_a[a]) - inertia * ctx.a[a]
    if not ctx.jac:
        return
    inverse = 1.0 / speed if speed > 0.0 else 0.0
    for a in range(3):  # D = df/du = drag (|u| I + u u^T / |u|), below the surface
        for b in range(3):
            D[a, b] = wet * q.drag * ((speed if a == b else 0.0) + w[a] * w[b] * inverse)
    # A = -(f_r + v_x f_v + a_x f_a): f_v = -D, f_a = -inertia I, f_r = D (du_w/dr + dU/dz e_z^T) + fluid da_w/dr
    for a in range(3):
        out.A[a, a] += ctx.a_x * inertia
        for b in range(3):
            position = wet * q.fluid * ctx.water_da[a, b]
            for c in range(3):
                position += D[a, c] * (ctx.water_du[c, b] + (slope[c] if b == 2 else 0.0))
            out.A[a, b] += ctx.v_x * D[a, b] - position


def build(setting):
    """A line with loaded joints off its prescribed ends gets them (statics: weight and buoyancy; in
    dynamics in waves, the waves too)."""
    line = setting.line
    if line is None:
        return None
    vertices = line.joint_vertices()
    keep = [i for i, (k, joint) in enumerate(line.joints) if joint.loaded
            and not (k == 0 and line.prescribed[0]) and not (k == len(line.segments) and line.prescribed[1])]
    if not keep:
        return None
    env = setting.environment
    return PointLoads(vertices[keep], [line.joints[i][1] for i in keep], env.water_density, env.gravity,
                      env.current, profile=env.current_profile, sea=env.waves if setting.dynamic else None)


SPEC = LoadSpec("points", "node", (("dry", "f8"), ("buoyancy", "f8"), ("radius", "f8"), ("drag", "f8"),
                                   ("inertia", "f8"), ("external", "f8", (3,)), ("current", "f8", (3,)))
                + PROFILE_FIELDS + (("waves", "?"), ("added", "f8"), ("fluid", "f8")), point_point, PointLoads,
                build=build,
                # the current at the point and its slope dU/dz; in waves the water's velocity relative
                # to the point and the drag's derivative df/du
                scratch=(("current", "f8", (3,)), ("slope", "f8", (3,)), ("w", "f8", (3,)), ("D", "f8", (3, 3))))
