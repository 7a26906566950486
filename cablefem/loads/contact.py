"""Seabed contact per unit unstretched length: normal force (desire2023 Eq. 11; housner2022
Eq. 4) and, optionally, friction (desire2023 Eq. 12; housner2022 Eq. 5-14).

f_n = -d G_K min(d_G, 0) d_P - c min(v_n, 0) d_P   while d_G < 0,

with d_G the penetration depth and d_P the projection direction of the
seabed (geometry package), d the contact diameter, G_K the ground stiffness
per unit area [N/m^3] and v_n = v . d_P. The damping per unit length c is
2 G_c sqrt(G_K d m) (Eq. 11, G_c the fraction of critical) or, given as
MoorDyn's cBot [N s/m^3], cBot d. On a plane d_G is the distance to the
plane, which equals MoorDyn's (z_b - r_3) n_z of housner2022 Eq. 4.

Eq. 11's third term, |p . d_P| d_P (the normal part of the line's weight,
added in contact), is left out: it switches on discontinuously as a point
touches the seabed, which breaks Newton's convergence, and it only shifts
the resting penetration from w/(d G_K) to zero; with the stiffnesses in use
(3e5 N/m^3 gives 0.07 m for the Table 5 chain) the spring carries the weight.

Friction (``cablefem.loads.friction``) uses the same projection: the normal
force magnitude N = |f_n|, the in-plane velocity v_pi = v - (v . d_P) d_P
and, for the anisotropic law, the axial direction q = normalise((I - d_P d_P) t)
with t = r'/|r'| (housner2022 Eq. 5). It acts only where d_G < 0 (N = 0
elsewhere) and only when a velocity is given (statics has none). Where the
line is perpendicular to the seabed q is undefined and taken as 0, so all
sliding counts as transverse.
"""

import numpy as np

from ..geometry.triangulated import TriangulatedSurface
from . import Terms, add, compose, identity_like, outer, unit_tangent

#: |(I - d_P d_P) t| below which the in-plane axial direction q is taken as 0
DEGENERATE_AXIS = 1e-12


class SeabedContact:
    """Contact of a line with ``seabed``: stiffness and damping per unit length per element (nel,),
    and optionally a friction law (``IsotropicFriction`` / ``AnisotropicFriction``, see
    ``cablefem.loads.friction.friction_law``)."""

    def __init__(self, seabed, stiffness, damping, friction=None):
        self.seabed = seabed
        self.stiffness = np.asarray(stiffness, dtype=float)[:, None]  # G_K d [N/m^2]
        self.damping = np.asarray(damping, dtype=float)[:, None]  # [N s/m^2]
        self.friction = friction

    def evaluate(self, state, jacobian=True):
        r = state.r
        shape = r.shape[1:]
        points = r.reshape(3, -1).T
        proj = _project(self.seabed, points, jacobian)
        gap = proj.gap.reshape(shape)
        n = proj.direction.T.reshape(3, *shape)
        touching = gap < 0.0
        pressure = -self.stiffness * np.where(touching, gap, 0.0)  # >= 0
        damped = state.v is not None and np.any(self.damping > 0)
        sliding = state.v is not None and self.friction is not None
        if damped or sliding:
            vn = np.einsum("ceq,ceq->eq", state.v, n)
        if damped:
            closing = touching & (vn < 0.0)
            pressure = pressure - self.damping * np.where(closing, vn, 0.0)
        terms = Terms(force=pressure * n)
        if sliding:
            v_plane = state.v - vn * n
            axis, axis_norm, t, divisor = _axis(state.dr, n) if self.friction.uses_axis else (None,) * 4
            friction, df_dw, df_dN, df_dq = self.friction.evaluate(v_plane, pressure, axis)
            terms.force = terms.force + friction
        if not jacobian:
            return terms
        grad_gap = proj.gap_gradient.T.reshape(3, *shape)
        dn = np.moveaxis(proj.direction_gradient, 0, -1).reshape(3, 3, *shape)
        # a point exactly on the seabed counts as touching in the tangent (a semismooth
        # Newton choice): a guess resting at d_G = 0 then gets the seabed's support at once
        on = (gap <= 0.0).astype(float)
        dpressure_dr = -self.stiffness * on * grad_gap
        dpressure_dv = None
        if damped:
            c = self.damping * closing
            # v_n = v . n(r): d v_n/dr = v . dn/dr
            dpressure_dr = dpressure_dr - c * np.einsum("aeq,abeq->beq", state.v, dn)
            dpressure_dv = -c * n
            terms.force_v = outer(n, dpressure_dv)
        terms.force_r = outer(n, dpressure_dr) + pressure * dn
        if sliding:
            eye = identity_like(n)
            in_plane = eye - outer(n, n)
            # v_pi = v - (v . n) n: d v_pi/dn = -(n v^T + (v . n) I)
            dw_dr = compose(-(outer(n, state.v) + vn * eye), dn)
            force_r = compose(df_dw, dw_dr) + outer(df_dN, dpressure_dr)
            force_v = compose(df_dw, in_plane)
            if dpressure_dv is not None:
                force_v = force_v + outer(df_dN, dpressure_dv)
            if axis is not None:
                # q = p / |p|, p = (I - n n^T) t, t = r'/|r'|; the t t^T part of dt/dr' drops
                # out, since (I - q q^T)(I - n n^T) t = (I - q q^T) |p| q = 0
                dq_dp = (eye - outer(axis, axis)) / axis_norm
                dq_ddr = compose(dq_dp, in_plane) / divisor
                terms.force_dr = compose(df_dq, dq_ddr)
                dp_dn = -(outer(n, t) + np.einsum("ceq,ceq->eq", n, t) * eye)
                force_r = force_r + compose(df_dq, compose(dq_dp, compose(dp_dn, dn)))
            terms.force_r = terms.force_r + force_r
            terms.force_v = add(terms.force_v, force_v)
        return terms


def _project(seabed, points, derivatives):
    """The seabed's projection of points (n, 3) [m]; a residual alone needs no derivatives,
    which the triangulated surface can skip (a third of its cost)."""
    if not derivatives and isinstance(seabed, TriangulatedSurface):
        return seabed.project(points, derivatives=False)
    return seabed.project(points)


def _axis(dr, n):
    """In-plane unit axial direction q (3, nel, nq), |p| with p = (I - n n^T) t (nel, nq),
    the unit tangent t (3, nel, nq) and |r'| as a divisor (nel, nq) (``unit_tangent``), for dr/ds and
    the normal n."""
    t, _, divisor = unit_tangent(dr)
    p = t - np.einsum("ceq,ceq->eq", t, n) * n
    size = np.sqrt(np.einsum("ceq,ceq->eq", p, p))
    degenerate = size < DEGENERATE_AXIS
    # a zero q makes the law all transverse and, with an infinite |p|, zeroes dq
    safe = np.where(degenerate, np.inf, size)
    return p / safe, safe, t, divisor

