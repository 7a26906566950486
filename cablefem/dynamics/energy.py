"""Energy bookkeeping of a line between accepted states: the work its moving ends put in, its kinetic,
strain and gravity energy, and the work the soil takes (``cablefem.loads.soil``) with the part of it
that the soil's plastic slip dissipates.

Between two states a and b (X (N, 3) positions, V velocities, the committed history of the full
points), with the trapezoidal rule in time:

    work in        W = sum over the moving ends of (G_a + G_b) / 2 . (r_b - r_a),  G the end's residual
                   row (the force the support exerts on the line, inertia included in dynamics)
    soil's work    S = -int (f_a + f_b) / 2 . (r_b - r_a) ds over the full points, f the soil's reaction
    plastic work   D = int (-f_b) . (q_b - q_a) ds >= 0     (``soil.plastic_dissipation``)
    stored         E = V . M V / 2 + int EA e^2 / 2 ds + int (weight's potential) ds

so that W = dE + S + (what the integrator and the damping loads dissipate); the balance closes when
that last part is the only remainder. The soil's work S holds D and the change of its springs'
elastic energy.
"""

import numpy as np


def stored_energy(system, X, V=None, mass=None):
    """Kinetic [J] (with ``mass``, the sparse consistent mass of ``forms.mass_matrix``), strain and
    gravity energy of ``system`` at X (N, 3), V (N, 3): a dict of the three."""
    state = system.state(X)
    strain = float(np.sum(system.tension.energy(state.reduced) * system.fem.reduced.dx))
    gravity = float(np.sum(system.weight.energy(state) * system.fem.full.dx))
    kinetic = 0.0 if V is None or mass is None else 0.5 * float(V.ravel() @ (mass @ V.ravel()))
    return {"kinetic": kinetic, "strain": strain, "gravity": gravity}


def step_work(system, a, b, moving=("fairlead",)):
    """Work [J] between states a and b, each a dict of X (N, 3), the end rows ``rows`` (N, 3) (the
    residual rows, M A + G in dynamics) and the committed full-point history ``history``: the work in
    at the ``moving`` ends, the soil's work and the plastic work (module docstring)."""
    from cablefem.loads.soil import plastic_dissipation

    fem = system.fem
    work_in = 0.0
    for end in moving:
        row = fem.fairlead_dof if end == "fairlead" else fem.anchor_dof
        work_in += float(0.5 * (a["rows"][row] + b["rows"][row]) @ (b["X"][row] - a["X"][row]))
    r_a = fem.full.interpolate(a["X"])[0].reshape(fem.full.s.shape + (3,))
    r_b = fem.full.interpolate(b["X"])[0].reshape(fem.full.s.shape + (3,))
    f_a, f_b = a["history"]["soil"]["reaction"], b["history"]["soil"]["reaction"]
    soil = -float(np.sum(np.einsum("eqc,eqc->eq", 0.5 * (f_a + f_b), r_b - r_a) * fem.full.dx))
    plastic = plastic_dissipation(a["history"], b["history"], fem.full.dx)
    return {"work_in": work_in, "soil": soil, "plastic": plastic}
