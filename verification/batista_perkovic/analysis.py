"""What verification/batista_perkovic computes from the case: Tables 3 and 4 (a, b), the geometry
evidence, the convergence study (c), the P1 diagnosis and the issue's targets (d)."""

import math

import numpy as np

from cablefem.statics.catenary import inclined_catenary
from cablefem.study import observed_orders

from verification.batista_perkovic.case import (DIAMETER, EA, ELEMENTS, FAST_ELEMENTS, FORCES, HEIGHT, LENGTH, MESHES,
                                                NODES, ORDERS, PAPER_STIFFNESS, PAPER_TABLE4, POSITION_FLOOR, SLOPE,
                                                STUDY_STIFFNESS, TABLE3_NODES, TARGETS, TENSION_FLOOR, Case,
                                                closed_forms, measure, solve, weight)


def table_rows(setup):
    """Tables 3 and 4 for one setup (order, elements, mesh) over the five H, at G_K = 3e14."""
    rows = []
    s = np.arange(NODES) * LENGTH / (NODES - 1)  # the paper's 32 nodes, node 0 at the anchor
    for force in FORCES:
        case = Case(force)
        system, result, wall = solve(case, setup["order"], setup["elements"], setup["mesh"])
        row = measure(case, system, result, wall)
        row["force"] = force
        positions = system.fem.evaluate(result.X, s)
        for name, solution in (("elastic", case.elastic), ("inextensible", case.inextensible)):
            delta = np.linalg.norm(positions - case.reference_points(solution, s), axis=1)
            row[name]["table3_delta_m"] = delta[list(TABLE3_NODES)].tolist()
            row[name]["max_delta_32_nodes_m"] = float(delta.max())
            row[name]["closed_form_fairlead_tension"] = solution.fairlead_tension
        row["positions_32_nodes"] = positions.tolist()
        rows.append(row)
    return rows


def evidence():
    """Our inextensible fairlead tension per H against the paper's T_A with H reversed."""
    rows = []
    for force in FORCES:
        inextensible, elastic = closed_forms(force)
        paper = PAPER_TABLE4[force][1] * 1e3
        rows.append({"force": force, "paper_T_A": paper, "inextensible_T": inextensible.fairlead_tension,
                     "relative": inextensible.fairlead_tension / paper - 1.0,
                     "elastic_T": elastic.fairlead_tension, "span_m": inextensible.horizontal_span,
                     "touchdown_s_inextensible": inextensible.touchdown_s,
                     "touchdown_s_elastic": elastic.touchdown_s,
                     "inextensible_vs_elastic": inextensible.fairlead_tension / elastic.fairlead_tension - 1.0})
    return rows


def stiffness_note(case, stiffnesses=(PAPER_STIFFNESS, STUDY_STIFFNESS)):
    """Per G_K: resting penetration [m], its effect on the fairlead tension (the closed form with
    the fairlead moved by the penetration along the normal), and the contact force [N/m] one
    rounding of a position (eps |r|) makes, against the weight per unit length."""
    rows = []
    n = case.seabed.normal
    reach = float(np.abs(case.anchor).max())
    for stiffness in stiffnesses:
        depth = case.resting_depth(stiffness)
        moved = inclined_catenary(case.span + depth * n[0], HEIGHT + depth * n[2], LENGTH, weight(), SLOPE, EA)
        ulp_force = stiffness * DIAMETER * np.finfo(float).eps * reach
        rows.append({"stiffness": stiffness, "penetration_m": depth,
                     "tension_effect": moved.fairlead_tension / case.elastic.fairlead_tension - 1.0,
                     "roundoff_contact_force_per_m": ulp_force, "relative_to_weight": ulp_force / weight()})
    return rows


def chord_surplus(case, elements):
    """P1's intrinsic error: (surplus length [m], the fairlead tension error it predicts).

    A P1 element is the chord of an arc of length h and curvature kappa, shorter than the
    arc by kappa^2 h^3 / 24; between fixed ends the polygon of chords is as slack as a line
    longer by (h^2 / 24) int kappa^2 ds over the hanging part (kappa = w H / T^2), which the
    elastic closed form with that length turns into a tension error.
    """
    elastic = case.elastic
    s = np.linspace(elastic.touchdown_s, LENGTH, 20001)
    curvature = weight() * elastic.fairlead_horizontal / elastic.tension(s) ** 2
    h = LENGTH / elements
    surplus = h * h / 24.0 * float(np.sum(0.5 * (curvature[1:] ** 2 + curvature[:-1] ** 2) * np.diff(s)))
    longer = inclined_catenary(case.span, HEIGHT, LENGTH + surplus, weight(), SLOPE, EA)
    return surplus, longer.fairlead_tension / elastic.fairlead_tension - 1.0


def p1_diagnosis(setup_rows):
    """Per H: the chord-surplus prediction for P1 x 31 against P1 x 31 with a vertex at the exact
    touchdown and on the uniform mesh (whose touchdown sits on a vertex near the true one)."""
    rows = []
    for row in setup_rows:
        case = Case(row["force"])
        surplus, predicted = chord_surplus(case, NODES - 1)
        system, result, wall = solve(case, 1, NODES - 1, "exact-vertex")
        vertex = measure(case, system, result, wall)
        rows.append({"force": row["force"], "surplus_m": surplus, "predicted": predicted,
                     "exact_vertex": vertex["elastic"]["fairlead_tension_error"],
                     "exact_vertex_position_m": vertex["elastic"]["node_position_error_m"],
                     "uniform": row["elastic"]["fairlead_tension_error"],
                     "uniform_touchdown_error_m": row["elastic"]["touchdown_error_m"]})
    return rows


def convergence(force, stiffness, fast):
    """(c): every order x element count x mesh at one H; runs and observed orders."""
    case = Case(force)
    elements = FAST_ELEMENTS if fast else ELEMENTS
    runs, orders = [], {}
    floors = {key: TENSION_FLOOR if "tension" in key else POSITION_FLOOR
              for key in ("fairlead_tension_error", "node_position_error_m", "curve_position_error_m")}
    for mesh in MESHES:
        for order in ORDERS:
            found = [dict(measure(case, *solve(case, order, n, mesh, stiffness)), mesh=mesh) for n in elements]
            runs += found
            orders[f"{mesh} P{order}"] = observed_orders(elements, found, floors, lambda run, key: run["elastic"][key])
    return {"force": force, "stiffness": stiffness, "elements": list(elements), "runs": runs,
            "orders": orders, "tension_floor": TENSION_FLOOR, "position_floor_m": POSITION_FLOOR,
            "stiffness_note": stiffness_note(case)}


def targets(setups, study):
    """(d): the issue's accuracy targets and whether they are met."""
    paper = setups[0]["rows"]  # P1, 31 elements, uniform: the paper's 32 nodes
    out = {}
    for name in ("elastic", "inextensible"):
        tension = max(abs(r[name]["fairlead_tension_error"]) for r in paper)
        position = max(r[name]["max_delta_32_nodes_m"] for r in paper)
        out[f"p1_32_nodes_tension_vs_{name}"] = {"value": tension, "target": TARGETS["p1_32_nodes_tension"],
                                                 "met": tension <= TARGETS["p1_32_nodes_tension"]}
        out[f"p1_32_nodes_position_vs_{name}"] = {"value": position, "target": TARGETS["p1_32_nodes_position_m"],
                                                  "met": position <= TARGETS["p1_32_nodes_position_m"]}
    for mesh in MESHES:
        for order in (2, 3):
            runs = [r for r in study["runs"] if r["mesh"] == mesh and r["order"] == order]
            meets = [r["converged"] and abs(r["elastic"]["fairlead_tension_error"]) <= TARGETS["p2_p3_tension"]
                     for r in runs]
            # the smallest count from which every finer mesh of the sweep meets the target
            needed = next((r["elements"] for i, r in enumerate(runs) if all(meets[i:])), None)
            out[f"P{order}_{mesh}_tension_1e-6"] = {
                "elements_needed": needed, "target": TARGETS["p2_p3_tension"], "met": needed is not None,
                "first_met": next((r["elements"] for r, ok in zip(runs, meets) if ok), None),
                "misses": [r["elements"] for r, ok in zip(runs, meets) if not ok],
                "errors": {r["elements"]: r["elastic"]["fairlead_tension_error"] for r in runs}}
    # P1 on a uniform mesh: the element count where the O(h^2) error would reach 1e-4
    p1 = [r for r in study["runs"] if r["mesh"] == "uniform" and r["order"] == 1]
    last = p1[-1]
    out["p1_elements_for_1e-4"] = math.ceil(last["elements"] * math.sqrt(
        abs(last["elastic"]["fairlead_tension_error"]) / TARGETS["p1_32_nodes_tension"]))
    return out
