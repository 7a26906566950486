"""The bending study's cases, each against its closed form (``closed_forms``): the runs and their errors.

Each function returns a dict of rows (one per element count, load, angle or EI) and, where the
case is a convergence study, the observed orders (``cablefem.study.observed_orders``).
"""

import math
import time

import numpy as np

from cablefem.statics.catenary import elastic_catenary
from cablefem.statics.solve import solve_static
from cablefem.study import observed_orders, position_errors
from verification.bending import closed_forms as exact
from verification.bending import models
from verification.bending.models import GRAVITY, IN_WATER, WEIGHTLESS, line_system, neutral_mass

#: below these an error is round-off or the extensible line's own stretch (the elastica's tip moves
#: by ~alpha 1e-8 L at EA L^2 / EI = 1e8), not discretisation: left out of the fitted orders
POSITION_FLOOR, CURVATURE_FLOOR, FREQUENCY_FLOOR = 5e-8, 5e-8, 1e-11
#: the arc is compared with its stretched closed form: only round-off below this (the full circle's
#: tip returns to the clamp, 6e-11 from it at any mesh)
ARC_FLOOR = 1e-10

#: the cantilever under its own weight: 10 m, EI 1e8 N m^2, 10 kg/m in air: a tip drop of 1.2e-4 L,
#: whose geometric nonlinearity, ~(drop / L)^2, is below 1e-7 of it
CANTILEVER = {"L": 10.0, "EI": 1e8, "EA": 1e12, "mass": 10.0}
#: the elastica: L = 1 m, EI = 1 N m^2, EA = 1e8 N (EA L^2 / EI = 1e8: the stretch moves the tip by
#: ~alpha / 1e8 L), a dead tip load alpha EI / L^2; under the end moment the line carries no axial
#: force, and EA = 1e6 N keeps the tangent's conditioning from setting a floor (2e-8 at 1e8)
ELASTICA = {"L": 1.0, "EI": 1.0, "EA": 1e8, "EA_arc": 1e6}
#: the beams that vibrate: 10 m, 0.2 m diameter, neutrally buoyant, EI 1e5 N m^2, EA 1e9 N (the taut
#: one 1e7 N, stretched by 1e-3: T = 1e4 N, its bending and tension shares of omega_1^2 alike)
BEAM = {"L": 10.0, "diameter": 0.2, "EI": 1e5, "EA": 1e9}
TAUT = {"EA": 1e7, "strain": 1e-3}
#: the hanging cable of the catenary limit: 90 m between (-60, 0, -40) and the origin, 20 kg/m,
#: 0.1 m diameter, EA 1e8 N, 40 Hermite elements; no seabed under it
HANGING = {"L": 90.0, "span": 60.0, "rise": 40.0, "mass": 20.0, "diameter": 0.1, "EA": 1e8, "elements": 40}


def cantilever(counts):
    """The cantilever under its own weight (small deflection) at n elements: the tip's and the
    vertices' largest deflection error relative to the tip's w L^4 / (8 EI)."""
    c = CANTILEVER
    w = c["mass"] * GRAVITY
    reference = exact.cantilever_deflection(c["L"], w, c["L"], c["EI"])
    rows = []
    for n in counts:
        system = line_system(n, c["L"], c["EI"], c["EA"], c["mass"])
        X, its, ok = models.solve(system, models.straight(system), w * c["L"])
        x = system.fem.mesh.p[0]
        drop = system.line.anchor[2] - X[: system.fem.n_vertices, 2]
        rows.append({"elements": n, "iterations": its, "converged": ok,
                     "tip_error": float(drop[-1] / reference - 1.0),
                     "node_error": float(np.max(np.abs(drop - exact.cantilever_deflection(x, w, c["L"], c["EI"])))
                                         / reference)})
    return {"tip_deflection": reference, "rows": rows}


def elastica(alphas, counts):
    """The elastica under a dead tip load at each alpha = P L^2 / EI and element count, solved from the
    straight line at the full load: the tip's position error |r - r_exact| / L, the clamp's curvature
    error, Newton's iterations and time; the observed orders per alpha."""
    c = ELASTICA
    out = []
    for alpha in alphas:
        x, drop, theta = exact.elastica_tip(alpha)
        load = alpha * c["EI"] / c["L"] ** 2
        reference = np.array([x, 0.0, -drop]) * c["L"]
        kappa = load * x * c["L"] / c["EI"]  # the clamp's moment P x over EI
        rows = []
        for n in counts:
            system = line_system(n, c["L"], c["EI"], c["EA"], WEIGHTLESS, tip_mass=load / GRAVITY)
            start = time.perf_counter()
            X, its, ok = models.solve(system, models.straight(system), load)
            rows.append({"elements": n, "iterations": its, "converged": ok, "seconds": time.perf_counter() - start,
                         "tip_error": float(np.linalg.norm(models.tip(system, X) - reference) / c["L"]),
                         "curvature_error": float(models.clamp_curvature(system, X) / kappa - 1.0),
                         "moment_error": float(models.clamp_moment(system, X) / (kappa * c["EI"]) - 1.0)})
        orders = observed_orders(counts, rows, {"tip_error": POSITION_FLOOR, "curvature_error": CURVATURE_FLOOR,
                                                "moment_error": CURVATURE_FLOOR})
        out.append({"alpha": alpha, "tip": [x, drop], "tip_angle_deg": math.degrees(theta), "clamp_curvature": kappa,
                    "rows": rows, "orders": orders})
    return out


def end_moment(thetas, counts, step=math.pi / 4):
    """The cantilever whose free end's tangent is clamped at theta (a pure end moment), turned in steps
    of at most ``step`` [rad] from straight: the tip's position error against the arc (relative to L;
    the arc stretched as the model stretches it, ``closed_forms.arc_strain``), the largest deviation
    of the vertices' curvature from the arc's (relative)."""
    c = ELASTICA
    out = []
    for theta in thetas:
        stages = np.linspace(0.0, theta, int(math.ceil(theta / step)) + 1)[1:]
        rows = []
        for n in counts:
            X, total, ok = None, 0, True
            for angle in stages:
                direction = (math.cos(angle), 0.0, math.sin(angle))
                system = line_system(n, c["L"], c["EI"], c["EA_arc"], WEIGHTLESS,
                                     tangents=((1.0, 0.0, 0.0), direction))
                X, its, converged = models.solve(system, models.straight(system) if X is None else X,
                                                 c["EI"] * angle / c["L"] ** 2)
                total, ok = total + its, ok and converged
            from cablefem.runs.curvature import node_curvature

            strain = exact.arc_strain(theta, c["L"], c["EI"], c["EA_arc"])
            reference = exact.arc(np.array([c["L"]]), theta, c["L"], strain)[0]
            at = models.tip(system, X)
            kappa = node_curvature(system, X)[0]
            rows.append({"elements": n, "iterations": total, "converged": ok, "strain": strain,
                         "tip_error": float(np.hypot(at[0] - reference[0], at[2] - reference[1]) / c["L"]),
                         "curvature_error": float(np.max(np.abs(kappa * c["L"] * (1.0 + strain) / theta - 1.0)))})
        orders = observed_orders(counts, rows, {"tip_error": ARC_FLOOR, "curvature_error": ARC_FLOOR})
        out.append({"theta_deg": math.degrees(theta), "stages": len(stages), "rows": rows, "orders": orders})
    return out


def _beam(n, taut=False):
    """A neutrally buoyant pinned beam of ``BEAM`` (taut: ``TAUT``'s EA, stretched by its strain) and
    its straight state."""
    b = BEAM
    EA = TAUT["EA"] if taut else b["EA"]
    end = IN_WATER + np.array([b["L"] * (1.0 + (TAUT["strain"] if taut else 0.0)), 0.0, 0.0])
    system = line_system(n, b["L"], b["EI"], EA, neutral_mass(b["diameter"]), origin=IN_WATER,
                         diameter=b["diameter"], tangents=(None, None), free_end=False, end=end)
    return system, models.straight(system)


def frequencies(counts, modes=3):
    """The pinned beam's and the taut beam's ``modes`` lowest frequencies (each twice: two planes) at
    n elements, relative errors; the observed orders of the first and last."""
    b, m = BEAM, neutral_mass(BEAM["diameter"])
    out = {}
    for taut in (False, True):
        T = TAUT["EA"] * TAUT["strain"]
        reference = [exact.taut_beam(k, b["EI"], m, b["L"], T, TAUT["strain"]) if taut
                     else exact.pinned_beam(k, b["EI"], m, b["L"]) for k in range(1, modes + 1)]
        rows = []
        for n in counts:
            system, X = _beam(n, taut)
            omega = models.frequencies(system, X, 2 * modes)
            rows.append({"elements": n, "omega": omega.tolist(),
                         "errors": [float(max(abs(omega[2 * k] / reference[k] - 1.0),
                                              abs(omega[2 * k + 1] / reference[k] - 1.0))) for k in range(modes)]})
        floors = {f"mode_{k + 1}": FREQUENCY_FLOOR for k in range(modes)}
        orders = observed_orders(counts, rows, floors, error=lambda run, key: run["errors"][int(key[5:]) - 1])
        out["taut" if taut else "pinned"] = {"reference": reference, "rows": rows, "orders": orders}
    return out


def vibration(n, periods=5, steps_per_period=64):
    """The neutrally buoyant cantilever of ``BEAM`` (clamped, free end) released from its first mode at
    a tip amplitude of 1e-4 L: its first frequency from the eigenproblem against the closed form, and
    the period of its tip from a run of each integrator (compiled) against both."""
    from cablefem.dynamics.bdf2 import BDF2
    from cablefem.dynamics.generalized_alpha import GeneralizedAlpha

    b, m = BEAM, neutral_mass(BEAM["diameter"])
    system = line_system(n, b["L"], b["EI"], b["EA"], m, origin=IN_WATER, diameter=b["diameter"])
    X = models.straight(system)
    omega = float(models.frequencies(system, X, 1)[0])
    reference = exact.cantilever_frequency(b["EI"], m, b["L"])
    X0 = X + 1e-4 * b["L"] * models.first_mode(system, X)
    T = 2.0 * math.pi / reference
    runs = {}
    for name, cls, options in (("bdf2", BDF2, {}), ("generalized-alpha", GeneralizedAlpha, {"rho_inf": 1.0})):
        start = time.perf_counter()
        heights, times = models.free_vibration(system, X0, cls, T / steps_per_period, periods * T, **options)
        measured = models.period(heights, times)
        runs[name] = {"period": measured, "period_error": measured / T - 1.0,
                      "period_error_fem": measured * omega / (2.0 * math.pi) - 1.0,
                      "amplitude_ratio": float(np.max(np.abs(heights[-steps_per_period:])) / np.max(np.abs(heights[:steps_per_period]))),
                      "seconds": time.perf_counter() - start}
    return {"elements": n, "omega": omega, "reference": reference, "omega_error": omega / reference - 1.0,
            "steps_per_period": steps_per_period, "runs": runs}


def catenary_limit(EIs):
    """The hanging cable of ``HANGING`` (pinned ends) with each EI, against the elastic catenary
    (``cablefem.statics.catenary``): the largest position difference along the line and at the
    vertices [m], the fairlead tension's relative difference, and the bending boundary layer's length
    sqrt(EI / T) [m] at the fairlead."""
    from cablefem.model.line import Line, LineType, Segment
    from cablefem.fem.system import LineSystem
    from cablefem.model.scene import Contact

    h = HANGING
    kind_weight = (h["mass"] - models.WATER_DENSITY * math.pi * h["diameter"] ** 2 / 4.0) * GRAVITY
    closed = elastic_catenary(h["span"], h["rise"], h["L"], h["EA"], kind_weight, seabed=False)
    anchor = np.array([-h["span"], 0.0, -h["rise"]])

    def reference(s):
        x, z = closed.profile(s)
        return anchor + np.column_stack([x, np.zeros_like(x), z])

    rows = []
    for EI in EIs:
        kind = LineType("cable", h["diameter"], h["mass"], h["EA"], EI=EI)
        line = Line("cable", anchor, (0.0, 0.0, 0.0), (Segment(kind, h["L"], h["elements"]),), element="hermite")
        system = LineSystem(line, models.SEABED, Contact(), models.ENVIRONMENT)
        result = solve_static(system, tolerance=1e-11)
        nodes, curve = position_errors(system.fem, result.X, reference, h["L"])
        fairlead = system.residual(result.X)[system.fem.fairlead_dof]
        tension = float(np.linalg.norm(fairlead))
        rows.append({"EI": EI, "iterations": result.iterations, "curve_error": curve, "node_error": nodes,
                     "fairlead_tension_error": tension / closed.fairlead_tension - 1.0,
                     "boundary_layer": math.sqrt(EI / tension)})
    return {"fairlead_tension": closed.fairlead_tension, "rows": rows}
