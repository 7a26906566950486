"""Catenary moorings of barreiro2015: single lines and a three-line spread mooring, FEM statics
against closed forms.

barreiro2015 (Sec. 2.2.1 "Static approach", after Faltinsen 1993) gives, for an inextensible
line of submerged weight w [N/m] lying on a flat seabed and rising h [m] to the fairlead,
the horizontal span X = l - h (1 + 2a/h)^(1/2) + a acosh(1 + h/a), a = T_H / w, and the
fairlead tension T = T_H + w h; for a spread mooring F = sum_i T_Hi (cos Psi_i, sin Psi_i).
Its two single lines have w = 850 and 1000 N/m, h = 20 m, l = 100 m.
Run ``python -m validation.spread_mooring.run [--fast] [--out DIR]``; ``run(fast=True)``
returns the numbers the tests assert on, in a few seconds.

(1) Single lines, fairlead tension and horizontal tension against the span X, from
    (a) Barreiro's formula solved for a at each X, (b) ``elastic_catenary`` with EA = inf
    (and with the FEM's EA), (c) cablefem FEM statics (``solve_static`` on a uniform mesh,
    reactions from ``results.end_forces``), from a line mostly on the seabed to a nearly
    taut one; and (c*) ``solve_line`` with its touchdown-fitted mesh, as ``cablefem static``
    solves a scene, where it converges.
(2) Three identical lines at 120 deg around a floater: the horizontal restoring force,
    the sum of the three FEM fairlead forces against the sum of the closed-form ones, for
    floater offsets in the directions 0, 30, 60 and 90 deg, with the symmetry checks of the
    layout (120 deg rotations, mirrors about the 0 and 60 deg axes).
"""

import argparse
import math
import time
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from cablefem import ConvergenceError, Line, LineType, Segment
from cablefem.catenary import elastic_catenary
from cablefem.geometry import Horizontal
from cablefem.results import end_forces
from cablefem.scene import Contact, Environment
from cablefem.statics import solve_line, solve_static
from cablefem.study import write_json
from cablefem.system import LineSystem

HERE = Path(__file__).resolve().parent

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

#: spread mooring: three copies of line1, anchors at ANCHOR_RADIUS, fairleads at FAIRLEAD_RADIUS
SPREAD_WEIGHT = WEIGHTS["line1"]
ANCHOR_AZIMUTHS = (0.0, 120.0, 240.0)  # [deg]
FAIRLEAD_RADIUS = 5.0  # [m], a 10 m wide buoy
ANCHOR_RADIUS = 97.0  # [m]: span 92 m at rest, pretension H0 = 18.7 kN, T0 = 35.7 kN
DIRECTIONS = (0.0, 30.0, 60.0, 90.0)  # offset directions [deg]


def line_type(weight, EA=EA):
    """LineType of submerged weight ``weight`` [N/m] in ENVIRONMENT: mass = w/g + rho A [kg/m]."""
    area = math.pi * DIAMETER**2 / 4.0
    mass = weight / ENVIRONMENT.gravity + ENVIRONMENT.water_density * area
    return LineType("chain", diameter=DIAMETER, mass=mass, EA=EA)


# ---------------------------------------------------------------- (a) barreiro2015
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


# ---------------------------------------------------------------- (c) FEM
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
    """``solve_line`` (a mesh vertex fitted to the touchdown, what ``cablefem static`` runs) from its
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


# ---------------------------------------------------------------- (1) single lines
def single_line_spans(fast):
    """Spans X [m]: from 78 % of the line on the seabed (84 m) to 99.7 % of the taut span (97.7 m)."""
    if fast:
        return [85.0, 92.0, 97.0, 97.6]
    _, x_max = barreiro_limit()
    spans = list(np.arange(84.0, 97.01, 0.5)) + [97.2, x_max, 97.4, 97.5, 97.6, 97.7]
    return sorted(float(x) for x in spans)


def single_lines(fast):
    """(1): tensions of (a), (b) and (c) against the span for both lines; their differences."""
    _, x_max = barreiro_limit()
    out = {"spans_m": single_line_spans(fast), "barreiro_limit_span_m": x_max,
           "taut_span_m": math.sqrt(LENGTH**2 - HEIGHT**2), "lines": {}}
    for name, weight in WEIGHTS.items():
        rows = []
        for span in out["spans_m"]:
            formula = barreiro_line(span, weight)
            rigid = elastic_catenary(span, HEIGHT, LENGTH, np.inf, weight)
            elastic = elastic_catenary(span, HEIGHT, LENGTH, EA, weight)
            fem = fem_line(np.array([-span, 0.0, -DRAFT - HEIGHT]), np.array([0.0, 0.0, -DRAFT]), weight)
            force = fem["force"]
            fitted = fitted_line(np.array([-span, 0.0, -DRAFT - HEIGHT]), np.array([0.0, 0.0, -DRAFT]), weight)
            row = {
                "span_m": span, "regime": rigid.regime, "lying_length_m": rigid.lying_length,
                "barreiro_tension_N": None if formula is None else formula["tension"],
                "barreiro_horizontal_N": None if formula is None else formula["horizontal"],
                "catenary_tension_N": rigid.fairlead_tension,
                "catenary_horizontal_N": rigid.fairlead_horizontal,
                "elastic_catenary_tension_N": elastic.fairlead_tension,
                "elastic_catenary_horizontal_N": elastic.fairlead_horizontal,
                "fem_tension_N": float(np.linalg.norm(force)),
                "fem_horizontal_N": float(np.hypot(force[0], force[1])),
                "fem_vertical_N": float(-force[2]),
                "fem_iterations": fem["iterations"], "fem_residual": fem["residual"],
                "fem_wall_time_s": fem["wall_time_s"],
            }
            row["fem_vs_catenary_tension"] = _relative(row["fem_tension_N"], row["catenary_tension_N"])
            row["fem_vs_catenary_horizontal"] = _relative(row["fem_horizontal_N"], row["catenary_horizontal_N"])
            row["fem_vs_elastic_tension"] = _relative(row["fem_tension_N"], row["elastic_catenary_tension_N"])
            row["fem_vs_elastic_horizontal"] = _relative(row["fem_horizontal_N"],
                                                         row["elastic_catenary_horizontal_N"])
            row["elastic_vs_rigid_tension"] = _relative(row["elastic_catenary_tension_N"],
                                                        row["catenary_tension_N"])
            if "error" in fitted:
                row["fitted_error"] = fitted["error"]
            else:
                fitted_force = fitted["force"]
                row["fitted_tension_N"] = float(np.linalg.norm(fitted_force))
                row["fitted_horizontal_N"] = float(np.hypot(fitted_force[0], fitted_force[1]))
                row["fitted_iterations"] = fitted["iterations"]
                row["fitted_vs_elastic_tension"] = _relative(row["fitted_tension_N"],
                                                             row["elastic_catenary_tension_N"])
                row["fitted_vs_elastic_horizontal"] = _relative(row["fitted_horizontal_N"],
                                                                row["elastic_catenary_horizontal_N"])
            row["fitted_wall_time_s"] = fitted["wall_time_s"]
            if formula is not None:
                row["fem_vs_barreiro_tension"] = _relative(row["fem_tension_N"], formula["tension"])
                row["fem_vs_barreiro_horizontal"] = _relative(row["fem_horizontal_N"], formula["horizontal"])
                row["barreiro_vs_catenary_tension"] = _relative(formula["tension"], rigid.fairlead_tension)
                row["barreiro_vs_catenary_horizontal"] = _relative(formula["horizontal"],
                                                                   rigid.fairlead_horizontal)
            rows.append(row)
        out["lines"][name] = {"weight_N_per_m": weight, "rows": rows, "max": _maxima(rows),
                              "fitted_failed_spans_m": [r["span_m"] for r in rows if "fitted_error" in r]}
    out["formula_check"] = barreiro_check()
    return out


def _maxima(rows):
    """Largest value of each relative-difference column over the rows that have it."""
    keys = [k for k in rows[0] if "_vs_" in k] + ["fem_vs_barreiro_tension", "fem_vs_barreiro_horizontal",
                                                  "fitted_vs_elastic_tension", "fitted_vs_elastic_horizontal",
                                                  "barreiro_vs_catenary_tension",
                                                  "barreiro_vs_catenary_horizontal"]
    return {k: max((r[k] for r in rows if k in r), default=None) for k in dict.fromkeys(keys)}


def barreiro_check(count=200):
    """Largest relative difference between Barreiro's formula and ``elastic_catenary`` (EA = inf)
    in T_H, V and T, over ``count`` spans across the whole touchdown regime, for both lines."""
    _, x_max = barreiro_limit()
    spans = np.linspace(LENGTH - HEIGHT, x_max, count + 1)[1:]
    worst = {"horizontal": 0.0, "vertical": 0.0, "tension": 0.0}
    for weight in WEIGHTS.values():
        for span in spans:
            formula = barreiro_line(float(span), weight)
            rigid = elastic_catenary(float(span), HEIGHT, LENGTH, np.inf, weight)
            for key, ours in (("horizontal", rigid.fairlead_horizontal), ("vertical", rigid.fairlead_vertical),
                              ("tension", rigid.fairlead_tension)):
                worst[key] = max(worst[key], _relative(formula[key], ours))
    return {"spans": int(count), "span_range_m": [float(spans[0]), float(spans[-1])], "max_relative": worst}


# ---------------------------------------------------------------- (2) spread mooring
def _unit(degrees):
    angle = math.radians(degrees)
    return np.array([math.cos(angle), math.sin(angle), 0.0])


def spread_layout():
    """Anchors and fairleads at zero offset, each (3, 3) [m], one row per line."""
    anchors = np.array([ANCHOR_RADIUS * _unit(psi) + [0.0, 0.0, -DRAFT - HEIGHT] for psi in ANCHOR_AZIMUTHS])
    fairleads = np.array([FAIRLEAD_RADIUS * _unit(psi) + [0.0, 0.0, -DRAFT] for psi in ANCHOR_AZIMUTHS])
    return anchors, fairleads


def spread_forces(offset, fem=True):
    """Forces (3,) [N] of the three lines on the floater displaced by ``offset`` (3,) [m]: the
    closed-form sum (``elastic_catenary`` at EA), Barreiro's sum T_Hi (cos Psi_i, sin Psi_i)
    and, with ``fem``, the FEM sum; with the per-line spans and tensions."""
    anchors, fairleads = spread_layout()
    out = {"closed_form": np.zeros(3), "barreiro": np.zeros(3), "fem": np.zeros(3) if fem else None,
           "spans_m": [], "fem_iterations": 0, "fem_wall_time_s": 0.0, "lines": []}
    for anchor, fairlead in zip(anchors, fairleads + offset):
        chord = anchor - fairlead
        span = float(np.hypot(chord[0], chord[1]))
        towards_anchor = np.array([chord[0] / span, chord[1] / span, 0.0])  # (cos Psi_i, sin Psi_i, 0)
        elastic = elastic_catenary(span, HEIGHT, LENGTH, EA, SPREAD_WEIGHT)
        line_force = elastic.fairlead_horizontal * towards_anchor - [0.0, 0.0, elastic.fairlead_vertical]
        out["closed_form"] += line_force
        formula = barreiro_line(span, SPREAD_WEIGHT)
        out["barreiro"] += (np.nan if formula is None else formula["horizontal"]) * towards_anchor
        entry = {"span_m": span, "closed_form_force_N": line_force.tolist()}
        if fem:
            solved = fem_line(anchor, fairlead, SPREAD_WEIGHT)
            out["fem"] += solved["force"]
            out["fem_iterations"] += solved["iterations"]
            out["fem_wall_time_s"] += solved["wall_time_s"]
            entry["fem_force_N"] = solved["force"].tolist()
        out["spans_m"].append(span)
        out["lines"].append(entry)
    return out


def _rotation(degrees):
    """Rotation about z by ``degrees``, (3, 3)."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _mirror(axis_degrees):
    """Reflection about the vertical plane through the horizontal axis at ``axis_degrees``, (3, 3)."""
    c, s = math.cos(math.radians(2 * axis_degrees)), math.sin(math.radians(2 * axis_degrees))
    return np.array([[c, s, 0.0], [s, -c, 0.0], [0.0, 0.0, 1.0]])


def spread_cases(fast):
    """(direction [deg], offset [m]) pairs: the main directions at every offset, and the copies
    rotated by 120 and 240 deg that the symmetry checks need."""
    if fast:
        offsets, rotated = [3.0], {30.0: (150.0, 270.0), 90.0: (210.0, 330.0)}
    else:
        offsets = [1.0, 2.0, 3.0, 4.0, 5.0]
        rotated = {d: (d + 120.0, d + 240.0) for d in DIRECTIONS}
    cases = [(0.0, 0.0)]
    for offset in offsets:
        cases += [(d, offset) for d in DIRECTIONS]
        cases += [(r, offset) for d in DIRECTIONS for r in rotated.get(d, ())]
    return cases, offsets


def spread_mooring(fast):
    """(2): restoring forces for every case, FEM against closed form, and the symmetry checks."""
    cases, offsets = spread_cases(fast)
    rest = elastic_catenary(ANCHOR_RADIUS - FAIRLEAD_RADIUS, HEIGHT, LENGTH, EA, SPREAD_WEIGHT)
    rows, by_case = [], {}
    for direction, offset in cases:
        forces = spread_forces(offset * _unit(direction))
        fem, closed = forces["fem"], forces["closed_form"]
        horizontal_fem, horizontal_closed = fem[:2], closed[:2]
        scale = float(np.linalg.norm(horizontal_closed))
        row = {
            "direction_deg": direction, "offset_m": offset,
            "fem_force_N": fem.tolist(), "closed_form_force_N": closed.tolist(),
            "barreiro_force_N": forces["barreiro"][:2].tolist(),
            "spans_m": forces["spans_m"], "lines": forces["lines"],
            "fem_restoring_N": float(np.linalg.norm(horizontal_fem)),
            "closed_form_restoring_N": scale,
            # horizontal difference over the restoring force, and over the lines' own tension scale
            "fem_vs_closed_form": float(np.linalg.norm(horizontal_fem - horizontal_closed) / scale) if offset else None,
            "fem_vs_closed_form_per_line_H": float(np.linalg.norm(horizontal_fem - horizontal_closed)
                                                   / rest.fairlead_horizontal),
            "fem_vs_closed_form_vertical": _relative(fem[2], closed[2]),
            "fem_iterations": forces["fem_iterations"], "fem_wall_time_s": forces["fem_wall_time_s"],
        }
        if offset:
            along = offset * _unit(direction)[:2] / offset
            row["restoring_cosine"] = float(horizontal_fem @ along / np.linalg.norm(horizontal_fem))
            row["angle_from_minus_offset_deg"] = math.degrees(math.acos(min(1.0, -row["restoring_cosine"])))
        rows.append(row)
        by_case[(round(direction % 360.0, 9), offset)] = fem
    zero = by_case[(0.0, 0.0)]
    checks = {
        "zero_offset_horizontal_N": float(np.linalg.norm(zero[:2])),
        "zero_offset_relative_to_H0": float(np.linalg.norm(zero[:2]) / rest.fairlead_horizontal),
        "zero_offset_vertical_N": float(-zero[2]),
        "all_restoring": all(r["restoring_cosine"] < 0.0 for r in rows if r["offset_m"]),
        "max_angle_from_minus_offset_deg": max(r["angle_from_minus_offset_deg"] for r in rows if r["offset_m"]),
        "rotation": [], "mirror": [],
    }
    for (direction, offset), fem in by_case.items():
        for turn in (120.0, 240.0):
            other = by_case.get((round((direction + turn) % 360.0, 9), offset))
            if offset and direction in DIRECTIONS and other is not None:
                checks["rotation"].append(_compare(f"F({direction + turn:g}) = R{turn:g} F({direction:g})",
                                                   offset, other, _rotation(turn) @ fem))
    for offset in offsets:
        for direction, axis in ((0.0, 0.0), (60.0, 60.0)):  # offsets along a mirror axis
            fem = by_case[(direction, offset)]
            checks["mirror"].append(_compare(f"F({direction:g}) = M{axis:g} F({direction:g})", offset,
                                             fem, _mirror(axis) @ fem))
        for target, source, axis in ((90.0, 30.0, 60.0), (330.0, 30.0, 0.0)):
            if (target, offset) in by_case:
                checks["mirror"].append(_compare(f"F({target:g}) = M{axis:g} F({source:g})", offset,
                                                 by_case[(target, offset)], _mirror(axis) @ by_case[(source, offset)]))
    checks["max_rotation"] = max(c["relative"] for c in checks["rotation"])
    checks["max_mirror"] = max(c["relative"] for c in checks["mirror"])
    moving = [r for r in rows if r["offset_m"]]
    return {
        "layout": {"anchor_radius_m": ANCHOR_RADIUS, "fairlead_radius_m": FAIRLEAD_RADIUS,
                   "anchor_azimuths_deg": list(ANCHOR_AZIMUTHS), "weight_N_per_m": SPREAD_WEIGHT,
                   "height_m": HEIGHT, "length_m": LENGTH, "span_at_rest_m": ANCHOR_RADIUS - FAIRLEAD_RADIUS,
                   "pretension_horizontal_N": rest.fairlead_horizontal, "pretension_N": rest.fairlead_tension},
        "offsets_m": offsets, "directions_deg": list(DIRECTIONS), "rows": rows, "checks": checks,
        "max_fem_vs_closed_form": max(r["fem_vs_closed_form"] for r in moving),
        "max_fem_vs_closed_form_per_line_H": max(r["fem_vs_closed_form_per_line_H"] for r in rows),
        "max_fem_vs_closed_form_vertical": max(r["fem_vs_closed_form_vertical"] for r in rows),
    }


def _compare(name, offset, value, expected):
    """A symmetry check: horizontal and vertical differences relative to the expected force."""
    return {"check": name, "offset_m": offset,
            "relative": float(np.linalg.norm(value[:2] - expected[:2]) / np.linalg.norm(expected[:2])),
            "vertical_relative": _relative(value[2], expected[2])}


# ---------------------------------------------------------------- driver
def run(fast=False):
    """Both studies; a dict of plain numbers (JSON-ready)."""
    start = time.perf_counter()
    results = {"fast": fast,
               "settings": {"EA_N": EA, "seabed_stiffness_N_per_m3": SEABED_STIFFNESS, "diameter_m": DIAMETER,
                            "order": ORDER, "elements": ELEMENTS, "element_length_m": LENGTH / ELEMENTS,
                            "tolerance": TOLERANCE, "EA_start_N": EA_START, "draft_m": DRAFT,
                            "water_density": ENVIRONMENT.water_density, "gravity": ENVIRONMENT.gravity},
               "single_lines": single_lines(fast), "spread": spread_mooring(fast)}
    results["wall_time_s"] = time.perf_counter() - start
    return results


def _number(value, fmt):
    return "-" if value is None else format(value, fmt)


def report(results):
    """The tables, as text."""
    s = results["settings"]
    single = results["single_lines"]
    lines = [f"FEM: P{s['order']} x {s['elements']} elements ({s['element_length_m']:g} m), EA = {s['EA_N']:.0e} N, "
             f"G_K = {s['seabed_stiffness_N_per_m3']:.0e} N/m^3, d = {s['diameter_m']:g} m, "
             f"tolerance {s['tolerance']:g}",
             f"(1) single lines, h = {HEIGHT:g} m, l = {LENGTH:g} m; Barreiro's formula holds up to "
             f"X = {single['barreiro_limit_span_m']:.4f} m (touchdown at the anchor), taut at "
             f"{single['taut_span_m']:.4f} m"]
    check = single["formula_check"]
    lines.append(f"  Barreiro vs elastic_catenary(EA=inf), {check['spans']} spans in "
                 f"[{check['span_range_m'][0]:.3f}, {check['span_range_m'][1]:.3f}] m, both lines: max rel. diff "
                 + ", ".join(f"{k} {v:.1e}" for k, v in check["max_relative"].items()))
    for name, data in single["lines"].items():
        lines.append(f"  {name}: w = {data['weight_N_per_m']:g} N/m")
        lines.append(f"  {'X [m]':>7} {'regime':>9} {'lying m':>7} {'T (a) kN':>10} {'T (b) kN':>10} "
                     f"{'T (c) kN':>10} {'(c)/(a)-1':>10} {'(c)/(b)-1':>10} {'(c)/(bEA)-1':>11} {'H (b) kN':>10} "
                     f"{'H (c)/(b)-1':>11} {'iters':>5} {'s':>5} {'(c*)/(bEA)-1':>12}")
        for r in data["rows"]:
            dt_a = None if r["barreiro_tension_N"] is None else r["fem_tension_N"] / r["barreiro_tension_N"] - 1
            lines.append(
                f"  {r['span_m']:7.3f} {r['regime']:>9} {r['lying_length_m']:7.2f} "
                f"{_number(r['barreiro_tension_N'] and r['barreiro_tension_N'] / 1e3, '10.4f'):>10} "
                f"{r['catenary_tension_N'] / 1e3:10.4f} {r['fem_tension_N'] / 1e3:10.4f} "
                f"{_number(dt_a, '10.1e'):>10} {r['fem_tension_N'] / r['catenary_tension_N'] - 1:10.1e} "
                f"{r['fem_tension_N'] / r['elastic_catenary_tension_N'] - 1:11.1e} "
                f"{r['catenary_horizontal_N'] / 1e3:10.4f} "
                f"{r['fem_horizontal_N'] / r['catenary_horizontal_N'] - 1:11.1e} {r['fem_iterations']:5d} "
                f"{r['fem_wall_time_s']:5.2f} "
                f"{'FAIL' if 'fitted_error' in r else format(r['fitted_tension_N'] / r['elastic_catenary_tension_N'] - 1, '12.1e'):>12}")
        m = data["max"]
        lines.append(f"  max |rel. diff| {name}: T (c)-(a) {m['fem_vs_barreiro_tension']:.2e}, (c)-(b) "
                     f"{m['fem_vs_catenary_tension']:.2e}, (c)-(b at EA) {m['fem_vs_elastic_tension']:.2e}; "
                     f"T_H (c)-(a) {m['fem_vs_barreiro_horizontal']:.2e}, (c)-(b) {m['fem_vs_catenary_horizontal']:.2e}; "
                     f"(b at EA)-(b) {m['elastic_vs_rigid_tension']:.2e}")
        lines.append(f"  (c*) touchdown-fitted solve_line vs (b at EA): T {_number(m['fitted_vs_elastic_tension'], '.2e')}, "
                     f"T_H {_number(m['fitted_vs_elastic_horizontal'], '.2e')}; "
                     + (f"did not converge at X = {data['fitted_failed_spans_m']} m" if data["fitted_failed_spans_m"]
                        else "converged at every span"))
    sp = results["spread"]
    lay = sp["layout"]
    lines.append(f"(2) spread mooring: 3 x {name_of_spread()} at {lay['anchor_azimuths_deg']} deg, anchors at "
                 f"R = {lay['anchor_radius_m']:g} m, fairleads at r = {lay['fairlead_radius_m']:g} m; span at rest "
                 f"{lay['span_at_rest_m']:g} m, H0 = {lay['pretension_horizontal_N'] / 1e3:.3f} kN, "
                 f"T0 = {lay['pretension_N'] / 1e3:.3f} kN per line")
    lines.append(f"  {'dir deg':>7} {'off m':>5} {'Fx FEM kN':>10} {'Fy FEM kN':>10} {'|F| FEM kN':>10} "
                 f"{'|F| c.f. kN':>11} {'|F| Barr kN':>11} {'FEM/cf-1':>9} {'/H0':>8} {'angle deg':>9} {'Fz FEM kN':>10}")
    for r in sp["rows"]:
        fem, barreiro = r["fem_force_N"], r["barreiro_force_N"]
        lines.append(f"  {r['direction_deg']:7.0f} {r['offset_m']:5.1f} {fem[0] / 1e3:10.4f} {fem[1] / 1e3:10.4f} "
                     f"{r['fem_restoring_N'] / 1e3:10.4f} {r['closed_form_restoring_N'] / 1e3:11.4f} "
                     f"{math.hypot(*barreiro) / 1e3:11.4f} {_number(r['fem_vs_closed_form'], '9.1e'):>9} "
                     f"{r['fem_vs_closed_form_per_line_H']:8.1e} "
                     f"{_number(r.get('angle_from_minus_offset_deg'), '9.3f'):>9} {fem[2] / 1e3:10.4f}")
    c = sp["checks"]
    lines.append(f"  max |F_FEM - F_cf| / |F_cf| (horizontal) {sp['max_fem_vs_closed_form']:.2e}; / H0 "
                 f"{sp['max_fem_vs_closed_form_per_line_H']:.2e}; vertical {sp['max_fem_vs_closed_form_vertical']:.2e}")
    lines.append(f"  zero offset: |F_h| = {c['zero_offset_horizontal_N']:.3e} N = {c['zero_offset_relative_to_H0']:.1e} H0;"
                 f" restoring everywhere: {c['all_restoring']}; largest angle between F_h and -offset "
                 f"{c['max_angle_from_minus_offset_deg']:.3f} deg")
    lines.append(f"  symmetry (|difference| / |F_h|): rotations max {c['max_rotation']:.1e}, mirrors max "
                 f"{c['max_mirror']:.1e}")
    for item in c["rotation"] + c["mirror"]:
        lines.append(f"    {item['check']:<26} offset {item['offset_m']:g} m: {item['relative']:.1e} "
                     f"(vertical {item['vertical_relative']:.1e})")
    lines.append(f"wall time {results['wall_time_s']:.1f} s")
    return "\n".join(lines)


def name_of_spread():
    """The spread mooring's line, named as in ``WEIGHTS``."""
    return next(name for name, weight in WEIGHTS.items() if weight == SPREAD_WEIGHT)


def figures(results, out):
    """PNG figures: single_lines.png, spread_offset.png and spread_polar.png in directory out."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    single = results["single_lines"]
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    for column, (name, data) in enumerate(single["lines"].items()):
        rows = data["rows"]
        spans = np.array([r["span_m"] for r in rows])
        dense = np.linspace(80.05, min(single["taut_span_m"] - 0.05, spans.max() + 0.1), 400)
        formula = [barreiro_line(x, data["weight_N_per_m"]) for x in dense]
        inside = np.array([f is not None for f in formula])
        rigid = [elastic_catenary(x, HEIGHT, LENGTH, np.inf, data["weight_N_per_m"]) for x in dense]
        ax = axes[0, column]
        ax.semilogy(dense[inside], [f["tension"] / 1e3 for f in formula if f is not None], "-", lw=3.5,
                    color="0.75", label="(a) barreiro2015 formula, T = T_H + w h")
        ax.semilogy(dense, [c.fairlead_tension / 1e3 for c in rigid], "-", color="C0",
                    label="(b) elastic_catenary, EA = inf")
        ax.semilogy(spans, [r["fem_tension_N"] / 1e3 for r in rows], "o", ms=4, color="C3",
                    label=f"(c) FEM statics, EA = {EA:.0e} N")
        ax.semilogy(dense[inside], [f["horizontal"] / 1e3 for f in formula if f is not None], "-", lw=3.5,
                    color="0.85")
        ax.semilogy(dense, [c.fairlead_horizontal / 1e3 for c in rigid], "--", color="C0",
                    label="horizontal tension T_H: (a), (b) dashed, (c) squares")
        ax.semilogy(spans, [r["fem_horizontal_N"] / 1e3 for r in rows], "s", ms=3.5, mfc="none", color="C3")
        ax.axvline(single["barreiro_limit_span_m"], color="0.5", ls=":", lw=1)
        ax.text(single["barreiro_limit_span_m"] - 0.15, 2.0, "touchdown\nat anchor", ha="right", fontsize=8,
                color="0.4")
        ax.set(ylabel="fairlead tension [kN]", ylim=(1.0, None),
               title=f"{name}: w = {data['weight_N_per_m']:g} N/m, h = {HEIGHT:g} m, l = {LENGTH:g} m")
        ax.legend(fontsize=7.5, loc="upper left")
        ax.grid(True, which="both", alpha=0.3)
        ax = axes[1, column]
        for key, label, style in (("fem_vs_barreiro_tension", "T: |(c)/(a) - 1|", "o-"),
                                  ("fem_vs_catenary_tension", "T: |(c)/(b) - 1|", "^--"),
                                  ("fem_vs_barreiro_horizontal", "T_H: |(c)/(a) - 1|", "s:"),
                                  ("fem_vs_elastic_tension", f"T: |(c)/(b at EA = {EA:.0e}) - 1|", "d-."),
                                  ("fitted_vs_elastic_tension", "T: |(c*)/(b at EA) - 1|, fitted mesh", "v"),
                                  ("elastic_vs_rigid_tension", f"T: EA = {EA:.0e} vs inf (closed forms)", "x-")):
            xs = [r["span_m"] for r in rows if key in r]
            ax.semilogy(xs, [max(r[key], 1e-12) for r in rows if key in r], style, ms=3.5, lw=1, label=label)
        ax.axhline(1e-4, color="k", lw=0.8)
        ax.set(xlabel="horizontal span anchor-fairlead X [m]", ylabel="relative difference", ylim=(1e-11, 1e-2))
        ax.legend(fontsize=7, ncol=2, loc="lower left")
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "single_lines.png", dpi=120)

    spread = results["spread"]
    rows = spread["rows"]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    ax = axes[0]
    for i, direction in enumerate(DIRECTIONS):
        chosen = sorted((r for r in rows if r["direction_deg"] == direction or r["offset_m"] == 0.0),
                        key=lambda r: r["offset_m"])
        offsets = [r["offset_m"] for r in chosen]
        dense = np.linspace(0.0, max(spread["offsets_m"]), 60)
        closed = [np.hypot(*spread_forces(d * _unit(direction), fem=False)["closed_form"][:2]) / 1e3 for d in dense]
        ax.plot(dense, closed, "-", color=f"C{i}", lw=1, label=f"{direction:g} deg: closed form")
        ax.plot(offsets, [r["fem_restoring_N"] / 1e3 for r in chosen], "o", color=f"C{i}", ms=4,
                label=f"{direction:g} deg: FEM")
    ax.set(xlabel="floater offset [m]", ylabel="horizontal restoring force |F_h| [kN]",
           title="spread mooring: restoring force against offset")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(True, alpha=0.3)
    ax = axes[1]
    moving = [r for r in rows if r["offset_m"]]
    ax.semilogy([r["offset_m"] + 0.04 * (r["direction_deg"] % 120 / 30 - 1.5) for r in moving],
                [max(r["fem_vs_closed_form"], 1e-12) for r in moving], "o", ms=4,
                label="|F_FEM - F_closed form| / |F_closed form| (horizontal)")
    ax.semilogy([r["offset_m"] for r in rows], [max(r["fem_vs_closed_form_vertical"], 1e-12) for r in rows],
                "^", ms=4, label="vertical force, relative")
    checks = spread["checks"]
    for group, marker, label in (("rotation", "x", "120 deg rotation symmetry"), ("mirror", "+", "mirror symmetry")):
        ax.semilogy([c["offset_m"] for c in checks[group]], [max(c["relative"], 1e-12) for c in checks[group]],
                    marker, ms=6, label=label)
    ax.axhline(1e-4, color="k", lw=0.8)
    ax.axhline(1e-6, color="k", lw=0.8, ls=":")
    ax.set(xlabel="floater offset [m]", ylabel="relative difference", ylim=(1e-12, 1e-2),
           title="FEM against closed form; FEM symmetries")
    ax.legend(fontsize=7, loc="upper right")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "spread_offset.png", dpi=120)

    fig = plt.figure(figsize=(11, 6))
    ax = fig.add_subplot(1, 2, 1)
    anchors, fairleads = spread_layout()
    for anchor, fairlead in zip(anchors, fairleads):
        ax.plot([fairlead[0], anchor[0]], [fairlead[1], anchor[1]], "-", color="0.6", lw=1)
    ax.plot(anchors[:, 0], anchors[:, 1], "kv", ms=7, label="anchors")
    ax.plot(fairleads[:, 0], fairleads[:, 1], "ko", ms=3, label="fairleads at rest")
    largest = max(spread["offsets_m"])
    outer = [r for r in rows if r["offset_m"] == largest]
    ring, arrow = 55.0, 30.0  # [m] on the drawing: where each case is drawn, length of the largest arrow
    kilonewtons = max(r["fem_restoring_N"] for r in outer) / 1e3
    for r in outer:
        start = ring * _unit(r["direction_deg"])[:2]
        force = np.array(r["fem_force_N"][:2]) / 1e3 * arrow / kilonewtons
        ax.annotate("", xy=start + force, xytext=start, arrowprops={"arrowstyle": "->", "color": "C3", "lw": 1.4})
        ax.annotate("", xy=start + 6.0 * _unit(r["direction_deg"])[:2], xytext=start,
                    arrowprops={"arrowstyle": "->", "color": "C0", "lw": 1.0})
        ax.text(*(1.28 * start), f"{r['direction_deg']:g}\N{DEGREE SIGN}", fontsize=7, ha="center", va="center")
    ax.plot([], [], "-", color="C0", label=f"offset direction ({largest:g} m, not to scale)")
    ax.plot([], [], "-", color="C3", label=f"FEM restoring force (arrow {arrow:g} m = {kilonewtons:.1f} kN)")
    ax.set(aspect="equal", xlabel="x [m]", ylabel="y [m]", xlim=(-110, 110), ylim=(-110, 110),
           title=f"plan view: restoring force for a {largest:g} m offset\nin each direction (drawn on a ring)")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2)
    ax.grid(True, alpha=0.3)
    ax = fig.add_subplot(1, 2, 2, projection="polar")
    for j, offset in enumerate(spread["offsets_m"]):
        theta = np.radians(np.linspace(0.0, 360.0, 145))
        closed = [np.hypot(*spread_forces(offset * _unit(np.degrees(t)), fem=False)["closed_form"][:2]) / 1e3
                  for t in theta]
        ax.plot(theta, closed, "-", lw=1, color=f"C{j}", label=f"{offset:g} m: closed form")
        chosen = [r for r in rows if r["offset_m"] == offset]
        ax.plot(np.radians([r["direction_deg"] for r in chosen]), [r["fem_restoring_N"] / 1e3 for r in chosen],
                "o", ms=4, color=f"C{j}", label=f"{offset:g} m: FEM")
    ax.plot(np.radians(ANCHOR_AZIMUTHS), [0.0] * 3, "kv", ms=6)
    ax.set_title("|F_h| [kN] against the offset direction [deg]\n(anchors at 0, 120, 240 deg)", fontsize=10)
    ax.legend(fontsize=6.5, loc="upper left", bbox_to_anchor=(1.05, 1.0))
    fig.tight_layout()
    fig.savefig(out / "spread_polar.png", dpi=120)
    plt.close("all")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="a few spans and offsets, a few seconds")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for results.json and PNGs")
    args = parser.parse_args(argv)
    results = run(fast=args.fast)
    print(report(results))
    args.out.mkdir(parents=True, exist_ok=True)
    write_json(args.out / "results.json", results, private=True, finite=True)
    figures(results, args.out)
    print(f"wrote {args.out / 'results.json'}, single_lines.png, spread_offset.png, spread_polar.png")


if __name__ == "__main__":
    main()
