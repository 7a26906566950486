"""(2) of validation/spread_mooring: three identical lines at 120 deg around a floater, the FEM's
horizontal restoring force against the closed form's, and the layout's symmetries."""

import math

import numpy as np

from cablefem.statics.catenary import elastic_catenary

from validation.spread_mooring.lines import DRAFT, EA, HEIGHT, LENGTH, WEIGHTS, _relative, barreiro_line, fem_line

#: spread mooring: three copies of line1, anchors at ANCHOR_RADIUS, fairleads at FAIRLEAD_RADIUS
SPREAD_WEIGHT = WEIGHTS["line1"]
ANCHOR_AZIMUTHS = (0.0, 120.0, 240.0)  # [deg]
FAIRLEAD_RADIUS = 5.0  # [m], a 10 m wide buoy
ANCHOR_RADIUS = 97.0  # [m]: span 92 m at rest, pretension H0 = 18.7 kN, T0 = 35.7 kN
DIRECTIONS = (0.0, 30.0, 60.0, 90.0)  # offset directions [deg]


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


def name_of_spread():
    """The spread mooring's line, named as in ``WEIGHTS``."""
    return next(name for name, weight in WEIGHTS.items() if weight == SPREAD_WEIGHT)
