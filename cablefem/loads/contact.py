"""Seabed normal contact force per unit unstretched length (desire2023 Eq. 11; housner2022 Eq. 4).

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
"""

import numpy as np

from . import Terms, outer


class SeabedContact:
    """Contact of a line with ``seabed``: stiffness and damping per unit length per element (nel,)."""

    def __init__(self, seabed, stiffness, damping):
        self.seabed = seabed
        self.stiffness = np.asarray(stiffness, dtype=float)[:, None]  # G_K d [N/m^2]
        self.damping = np.asarray(damping, dtype=float)[:, None]  # [N s/m^2]

    def evaluate(self, state, jacobian=True):
        r = state.r
        shape = r.shape[1:]
        points = r.reshape(3, -1).T
        proj = self.seabed.project(points)
        gap = proj.gap.reshape(shape)
        n = proj.direction.T.reshape(3, *shape)
        touching = gap < 0.0
        pressure = -self.stiffness * np.where(touching, gap, 0.0)  # >= 0
        damped = state.v is not None and np.any(self.damping > 0)
        if damped:
            vn = np.einsum("ceq,ceq->eq", state.v, n)
            closing = touching & (vn < 0.0)
            pressure = pressure - self.damping * np.where(closing, vn, 0.0)
        terms = Terms(force=pressure * n)
        if not jacobian:
            return terms
        grad_gap = proj.gap_gradient.T.reshape(3, *shape)
        dn = np.moveaxis(proj.direction_gradient, 0, -1).reshape(3, 3, *shape)
        on = touching.astype(float)
        dpressure_dr = -self.stiffness * on * grad_gap
        if damped:
            c = self.damping * closing
            # v_n = v . n(r): d v_n/dr = v . dn/dr
            dpressure_dr = dpressure_dr - c * np.einsum("aeq,abeq->beq", state.v, dn)
            terms.force_v = outer(n, -c * n)
        terms.force_r = outer(n, dpressure_dr) + pressure * dn
        return terms
