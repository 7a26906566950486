"""Weight and buoyancy per unit unstretched length (desire2023 Eq. 3, f_hg times (1 + e)).

Mass per unit unstretched length is conserved as the line stretches, and so
is the displaced volume in this model, so the submerged weight per unit
unstretched length is (m - rho A) g, a constant. A part of the line above
the still water surface z = 0 gets no buoyancy.
"""

import numpy as np

from . import Terms


class Weight:
    """Mass [kg/m] and volume-equivalent area [m^2] per element (nel,), water density, gravity."""

    def __init__(self, mass, area, water_density, gravity):
        self.dry = np.asarray(mass, dtype=float)[:, None] * gravity
        self.buoyancy = water_density * np.asarray(area, dtype=float)[:, None] * gravity

    def evaluate(self, state, jacobian=True):
        z = state.r[2]
        force = np.zeros_like(state.r)
        force[2] = -(self.dry - np.where(z < 0.0, self.buoyancy, 0.0))
        return Terms(force=force)

    def energy(self, state):
        """Potential energy density [J/m] (nel, nq): dry weight x z minus buoyancy x min(z, 0)."""
        z = state.r[2]
        return self.dry * z - self.buoyancy * np.minimum(z, 0.0)
