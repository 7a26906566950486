"""The lines of validation/spread_mooring: barreiro2015's two lines and their closed form (a), the
FEM line that stands in for an inextensible line on a rigid seabed (c), solved on a uniform mesh
or on the mesh statics fits to the touchdown (c*)."""

import math
import time

from scipy.optimize import brentq

from cablefem import ConvergenceError, Line, LineType, Segment
from cablefem.geometry import Horizontal
from cablefem.runs.results import end_forces
from cablefem.model.scene import Contact, Environment
from cablefem.statics.touchdown import solve_line
from cablefem.statics.solve import solve_static
from cablefem.fem.system import LineSystem

#: barreiro2015's two lines: submerged weight [N/m]
WEIGHTS = {"line1": 850.0, "line2": 1000.0}
HEIGHT = 20.0  # fairlead above the anchor and the seabed [m]
LENGTH = 100.0  # unstretched length [m]
DRAFT = 1.0  # fairlead below the still water level [m]: the whole line stays submerged
DIAMETER = 0.1  # [m]; the mass is chosen so that (m - rho A) g is the wanted weight exactly
ENVIRONMENT = Environment(water_density=1025.0, gravity=9.81)

# The FEM stands in for an inextensible line on a rigid seabed (justified in the README):
EA = 1e12  # [N]: strain T/EA <= 4e-7 over the sweep; EA = inf vs 1e12 differs <= 7e-5 in T
SEABED_STIFFNESS = 1e10  # G_K [N/m^3]: the lying line sinks w / (G_K d) = 0.85-1 micrometre
ORDER, ELEMENTS = 2, 400  # P2, 0.25 m elements (the touchdown curvature radius is >= 1.8 m)
TOLERANCE = 1e-11  # relative residual; Newton stops earlier on a step below 1e-9 m
EA_START = 1e9  # EA continuation: solve at 1e9 N from the catenary guess, then x10 steps to EA
FITTED_TOLERANCE = 1e-9  # solve_line (touchdown-fitted mesh, no warm start): 1e-11 fails more often


def line_type(weight, EA=EA):
    """LineType of submerged weight ``weight`` [N/m] in ENVIRONMENT: mass = w/g + rho A [kg/m]."""
    area = math.pi * DIAMETER**2 / 4.0
    mass = weight / ENVIRONMENT.gravity + ENVIRONMENT.water_density * area
    return LineType("chain", diameter=DIAMETER, mass=mass, EA=EA)


def barreiro_span(a, height=HEIGHT, length=LENGTH):
    """Horizontal span X [m] of an inextensible touchdown line with catenary parameter a = T_H/w [m]."""
    return length - height * math.sqrt(1.0 + 2.0 * a / height) + a * math.acosh(1.0 + height / a)


def barreiro_limit(height=HEIGHT, length=LENGTH):
    """(a [m], X [m]) where the touchdown reaches the anchor: the end of the formula's validity."""
    a = 0.5 * height * ((length / height) ** 2 - 1.0)  # suspended length h (1 + 2a/h)^(1/2) = l
    return a, barreiro_span(a, height, length)


def barreiro_line(span, weight, height=HEIGHT, length=LENGTH):
    """Fairlead forces of barreiro2015's formula at span X [m]: dict of T_H, V, T [N] and a [m];
    None beyond the touchdown regime (X <= l - h is slack, X past ``barreiro_limit`` lifts the anchor)."""
    a_max, x_max = barreiro_limit(height, length)
    if span <= length - height or span > x_max:
        return None
    if span == x_max:
        a = a_max
    else:
        low = 1e-9 * height
        while barreiro_span(low, height, length) >= span:
            low *= 1e-3
        a = brentq(lambda a: barreiro_span(a, height, length) - span, low, a_max, xtol=1e-300, rtol=1e-15)
    horizontal = a * weight
    vertical = weight * height * math.sqrt(1.0 + 2.0 * a / height)  # weight of the suspended length
    return {"a": a, "horizontal": horizontal, "vertical": vertical, "tension": horizontal + weight * height}


def fem_line(anchor, fairlead, weight, EA=EA, order=ORDER, elements=ELEMENTS):
    """FEM statics of one line anchor -> fairlead [m] (3,) on the seabed through the anchor: dict with
    the force (3,) the line exerts on its fairlead [N], Newton iterations, residual and wall time [s]."""
    start = time.perf_counter()
    seabed = Horizontal(-float(anchor[2]))
    contact = Contact(stiffness=SEABED_STIFFNESS)
    stiffness, guess, iterations = min(EA_START, EA), None, 0
    while True:
        # a stiff line from an interpolated guess gives Newton residuals of EA x (guess strain
        # error), 1e4 times the weight at 1e12 N: it stalls; from the solution of a softer
        # line the strains are already right to T/EA and Newton converges in a few steps
        line = Line("line", anchor, fairlead, [Segment(line_type(weight, stiffness), LENGTH, elements)], order)
        system = LineSystem(line, seabed, contact, ENVIRONMENT)
        result = solve_static(system, guess, tolerance=TOLERANCE)
        iterations += result.iterations
        if stiffness >= EA:
            break
        guess, stiffness = result.X, min(10.0 * stiffness, EA)
    fairlead_force, _ = end_forces(system, result.X)
    return {"force": fairlead_force, "iterations": iterations, "residual": result.residual,
            "strategy": result.strategy, "wall_time_s": time.perf_counter() - start}


def fitted_line(anchor, fairlead, weight, EA=EA, order=ORDER, elements=ELEMENTS):
    """``solve_line`` (a mesh vertex fitted to the touchdown, ``cablefem static`` with ``fit_touchdown``) from its
    own catenary guess: dict as ``fem_line``, or with ``error`` (the solver's message) if it fails."""
    start = time.perf_counter()
    line = Line("line", anchor, fairlead, [Segment(line_type(weight, EA), LENGTH, elements)], order)
    try:
        system, result = solve_line(line, Horizontal(-float(anchor[2])), Contact(stiffness=SEABED_STIFFNESS),
                                    ENVIRONMENT, tolerance=FITTED_TOLERANCE)
    except ConvergenceError as error:
        return {"error": str(error), "wall_time_s": time.perf_counter() - start}
    fairlead_force, _ = end_forces(system, result.X)
    return {"force": fairlead_force, "iterations": result.iterations, "residual": result.residual,
            "elements": system.fem.n_elements, "wall_time_s": time.perf_counter() - start}


def _relative(value, reference):
    return abs(value / reference - 1.0)
