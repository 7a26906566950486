"""(e) Morison's load on a fixed, very stiff horizontal line in regular waves: its end reactions
against the integral of the Morison force along it.

A neutrally buoyant line (its mass is the water it displaces, so weight and buoyancy cancel) spans
``SPAN`` m at z = ``HEIGHT`` between two fixed ends, pretensioned to ``PRETENSION`` N by an axial
stiffness of 1e10 N: under the waves it moves by ~1e-6 m, so it feels the water's motion as a
fixed cylinder does (its axial stiffness is not higher: the sag, ~1e-6 m, stretches it by
EA/(2 l) int y'^2 dx, ~1e-5 of the reactions here, a hundred times that at 1e13 N). Between two fixed supports the line carries its load to them as a bar
fixed at both ends and a taut string do, by the lever rule: the force it exerts on the anchor is
int f (l - x) / l dx and on the fairlead int f x / l dx, f the Morison force per unit length of a
cylinder at rest (drag 1/2 rho d (Cd_n |u_n| u_n + Cd_t |u_t| u_t) and inertia rho A ((1 + Ca_n)
a_n + (1 + Ca_t) a_t)), written here from the closed-form kinematics (``closed_forms.py``) and
integrated by Gauss-Legendre quadrature on 400 points. cablefem's reactions come from a run
(generalised-alpha, the waves ramped in), less the pretension of the same line in still water.
"""

import numpy as np

from cablefem.geometry import Horizontal
from cablefem.model.line import Line, LineType, Segment
from cablefem.model.scene import Environment, Scene, Solver
from cablefem.study import start_line
from cablefem.waves import Sea
from verification.waves.closed_forms import sea_at

RHO, G, DEPTH = 1025.0, 9.81, 50.0
SPAN, HEIGHT, PRETENSION = 10.0, -8.0, 1.0e9
DIAMETER, CD_N, CD_T, CA_N, CA_T = 0.2, 1.2, 0.5, 1.0, 0.5
#: a regular wave at 30 degrees to the line: every component of the load moves
WAVE = (2.0, 2 * np.pi / 8.0, np.radians(30.0), 0.7)  # A [m], omega [rad/s], heading, phase [rad]
RAMP = 16.0


def line(elements, order):
    """The stiff line from (-SPAN/2, 0, HEIGHT) to (SPAN/2, 0, HEIGHT), its strain PRETENSION / EA."""
    area = np.pi * DIAMETER ** 2 / 4.0
    EA = 1.0e10
    kind = LineType("stiff", diameter=DIAMETER, mass=RHO * area, EA=EA, damping=1e-4, Cd_normal=CD_N,
                    Cd_tangential=CD_T, Ca_normal=CA_N, Ca_tangential=CA_T)
    length = SPAN / (1.0 + PRETENSION / EA)
    return Line("stiff", [-SPAN / 2, 0.0, HEIGHT], [SPAN / 2, 0.0, HEIGHT], (Segment(kind, length, elements),), order)


def scene(elements, order, waves=True):
    """The line in the regular wave (or in still water), dt 0.02 s."""
    sea = Sea.regular(WAVE[0], 2 * np.pi / WAVE[1], WAVE[2], WAVE[3], DEPTH, G, ramp=RAMP) if waves else None
    return Scene("stiff-line", [line(elements, order)], Horizontal(DEPTH), environment=Environment(RHO, G, waves=sea),
                 solver=Solver(integrator="generalized-alpha", dt=0.02, tolerance=1e-12))


def morison_per_length(x, t):
    """The Morison force per unit length [N/m] (3,) on the cylinder at rest along x at (x, 0, HEIGHT)."""
    _, u, a = sea_at([WAVE], DEPTH, G, "wheeler", np.array([x, 0.0, HEIGHT]), t)
    R = min(t / RAMP, 1.0) ** 2 * (3.0 - 2.0 * min(t / RAMP, 1.0))
    rate = 6.0 * (t / RAMP) * (1.0 - t / RAMP) / RAMP if t < RAMP else 0.0
    u, a = R * u, R * a + rate * u  # the ramp of ``Sea.ramp_factor``
    axis = np.array([1.0, 0.0, 0.0])
    u_t, a_t = u @ axis * axis, a @ axis * axis
    u_n, a_n = u - u_t, a - a_t
    area = np.pi * DIAMETER ** 2 / 4.0
    drag = 0.5 * RHO * DIAMETER * (CD_N * np.linalg.norm(u_n) * u_n + CD_T * np.linalg.norm(u_t) * u_t)
    return drag + RHO * area * ((1.0 + CA_N) * a_n + (1.0 + CA_T) * a_t)


def lever_rule(t, points=400):
    """The forces [N] the line exerts on its anchor and fairlead, (2, 3): int f (l - x)/l, int f x/l."""
    nodes, weights = np.polynomial.legendre.leggauss(points)
    x = 0.5 * SPAN * nodes
    f = np.array([morison_per_length(xi, t) for xi in x])
    share = (x + SPAN / 2) / SPAN  # x / l from the anchor
    return np.array([(weights * (1 - share)) @ f, (weights * share) @ f]) * 0.5 * SPAN


def reactions(elements=10, order=2, integrator="generalized-alpha", duration=24.0, every=0.5):
    """cablefem's reactions less the still-water ones and the lever rule's, every ``every`` s after the
    ramp: (times (m,), cablefem's (m, 2, 3), the reference's (m, 2, 3)), anchor first."""
    base = scene(elements, order)
    steps = np.arange(1, int(round(duration / base.solver.dt)) + 1) * base.solver.dt
    still = start_line(scene(elements, order, waves=False), integrator=integrator).march(steps[:1])[0]
    forces = start_line(base, integrator=integrator).march(steps)  # (fairlead, anchor) after each step
    keep = (steps > RAMP) & (np.abs(steps / every - np.round(steps / every)) < 1e-9)
    times = steps[keep]
    return times, forces[keep][:, ::-1] - still[::-1], np.array([lever_rule(t) for t in times])


def check(elements=10, order=2, integrator="generalized-alpha"):
    """The largest difference of the end reactions from the lever rule over the run, relative to the
    largest reaction, per component of the force on (anchor, fairlead)."""
    times, ours, reference = reactions(elements, order, integrator)
    scale = np.abs(reference).max()
    error = np.abs(ours - reference).max(axis=0) / scale
    return {"integrator": integrator, "elements": elements, "order": order, "times": len(times),
            "largest_reaction_N": float(scale),
            "error_anchor": error[0].tolist(), "error_fairlead": error[1].tolist(),
            "error": float(error.max())}
