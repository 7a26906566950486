"""rui2025 Sec. 4: the IEA 15 MW VolturnUS-S mooring in clay, the pretension with and without the
embedded chain (Table 2; Figs. 4 and 5).

Three chain lines 120 deg apart in 200 m of water: fairleads 14 m below the surface at radius 58 m,
anchors at radius 837.6 m, 850 m of chain (d_b 0.185 m, 685 kg/m, EA 3270 MN), clay
su = 1.5 z kPa (Sec. 2.2), E_t 8, E_n 2.5, k_n 2/d_b, k_t 1/d_b (Table 1). The lines do not share
anything (fixed fairleads, no floater), so one line stands for all three; ``--full`` also solves the
three-line scene and checks that its lines agree. Runs (``python -m validation.rui2025.run
[--fast | --full] [--out DIR]``; ``run(fast=True)`` returns what the tests assert on):

- the conventional model: padeye fixed on the mudline, no soil, the seabed a frictionless contact
  (``cablefem static`` of the scene without [soil]), and the frictionless elastic catenary with the
  volume-equivalent diameter 1.8 d_b (``cablefem.statics.catenary``); rui2025: 2437 kN at 56.4 deg;
- Case 1: 850 m, padeye 10 m below the mudline; Case 2: 840 m, padeye on the mudline; Case 3:
  850 m, padeye on the mudline; all with soil, installed by the pretension path (``installation =
  "laid"``, ``cablefem.statics.pretension``); rui2025: ~2665 (Case 2 is 14.6 % above it, Case 3 7.6 %
  below), 3059, 2462 kN at the fairlead, 960 kN at Case 3's padeye;
- Case 3 installed as ``"catenary"`` (no path: the soil unloaded at the frictionless equilibrium);
- the sensitivity of Cases 1-3 to the bearing factor N_c (7.6, 9, 11.5, 14) and to the mesh
  (full run).
"""

import argparse
import time
from pathlib import Path

import numpy as np

from cablefem.statics.catenary import elastic_catenary
from cablefem.geometry import Horizontal
from cablefem.io.checks import check_scene
from cablefem.model.line import Line, LineType, Segment
from cablefem.statics.pretension import resting_depth, solve_pretension
from cablefem.runs.results import report
from cablefem.study import write_json
from cablefem.fem.system import build_system
from cablefem.model.scene import Environment, Scene
from cablefem.statics.touchdown import solve_line

HERE = Path(__file__).resolve().parent

D_B = 0.185  # nominal (bar) diameter [m], Table 2
CHAIN = LineType("chain", diameter=1.8 * D_B, mass=685.0, EA=3.27e9, nominal_diameter=D_B)
DEPTH, FAIRLEAD_DEPTH = 200.0, 14.0  # [m]
ANCHOR_RADIUS, FAIRLEAD_RADIUS = 837.6, 58.0  # [m]
SOIL = {"su_mudline": 0.0, "su_gradient": 1500.0, "width_tangential": 8.0, "width_normal": 2.5}
#: (line length [m], padeye depth below the mudline [m]) of rui2025 Sec. 4's cases
CASES = {"case1": (850.0, 10.0), "case2": (840.0, 0.0), "case3": (850.0, 0.0)}
#: rui2025's numbers [N, deg]: Sec. 3.1 and Table 2 (conventional), Sec. 4.2 (cases; Case 1 from
#: Case 2 = +14.6 % and Case 3 = -7.6 % of it: 3059 / 1.146 = 2669, 2462 / 0.924 = 2665)
PAPER = {"conventional": {"fairlead_tension": 2437e3, "fairlead_angle_deg": 56.4},
         "case1": {"fairlead_tension": 2665e3}, "case2": {"fairlead_tension": 3059e3},
         "case3": {"fairlead_tension": 2462e3, "padeye_tension": 960e3}}
BEARING_FACTORS = (7.6, 9.0, 11.5, 14.0)
#: the mesh: 1 m elements over the first 60 m (the embedded climb and the inverse catenary),
#: 5 m beyond (measured: halving both moves the fairlead tension by < 0.01 %, the padeye's by < 1 %)
NEAR, NEAR_ELEMENTS, FAR_ELEMENT = 60.0, 60, 5.0


def line(length, padeye_depth, azimuth=0.0, refine=1, order=1):
    """One line of the layout, anchor at ``azimuth`` [deg] (x towards the anchor at 0)."""
    u = np.array([np.cos(np.radians(azimuth)), np.sin(np.radians(azimuth)), 0.0])
    anchor = ANCHOR_RADIUS * u - (DEPTH + padeye_depth) * np.array([0.0, 0.0, 1.0])
    fairlead = FAIRLEAD_RADIUS * u - FAIRLEAD_DEPTH * np.array([0.0, 0.0, 1.0])
    far = length - NEAR
    segments = (Segment(CHAIN, NEAR, NEAR_ELEMENTS * refine // order),
                Segment(CHAIN, far, max(1, round(far / FAR_ELEMENT)) * refine // order))
    return Line(f"line{1 + round(azimuth / 120.0)}", anchor, fairlead, segments, order)


def scene(case, soil=None, lines=1, refine=1, order=1):
    """The scene of a case (``CASES``), with the [soil] table ``soil`` (None: the conventional model
    without soil), ``lines`` of the three, the mesh refined ``refine`` times and of ``order``."""
    length, padeye = CASES[case]
    built = Scene(f"rui2025-{case}", [line(length, padeye, 120.0 * k, refine, order) for k in range(lines)],
                  Horizontal(DEPTH), environment=Environment(water_density=1025.0, gravity=9.81),
                  load_settings={} if soil is None else {"soil": dict(soil)})
    return check_scene(built)


def angle(force):
    """Angle [deg] of a force (3,) from the horizontal."""
    return float(np.degrees(np.arctan2(abs(force[2]), np.hypot(force[0], force[1]))))


def solve(scene_):
    """Pretension path (or, without soil, ``solve_line``) of the scene's first line: a dict of its
    numbers and the profile along it."""
    start = time.perf_counter()
    line_ = scene_.lines[0]
    if "soil" in scene_.load_settings:
        system = build_system(scene_, line_, dynamic=False)
        result = solve_pretension(system)
    else:
        system, result = solve_line(line_, scene_.seabed, scene_.contact, scene_.environment)
    rep = report(system, result.X, result if "soil" in scene_.load_settings else None)
    out = {"fairlead_tension": rep.fairlead_tension, "fairlead_angle_deg": angle(rep.fairlead_force),
           "padeye_tension": rep.anchor_tension, "padeye_angle_deg": angle(rep.anchor_force),
           "touchdown_s": rep.touchdown_s, "wall_time_s": time.perf_counter() - start,
           "profile": {"nodes": rep.nodes, "tension": rep.tension,
                       "s": system.fem.mesh.p[0].copy()}}
    if rep.soil is not None:
        out.update({k: rep.soil[k] for k in ("mudline_tension", "mudline_angle_deg", "embedded_length")})
        out.update({"steps": result.steps, "halvings": result.halvings, "newton_iterations": result.iterations,
                    "resting_depth": float(np.max(resting_depth(system))),
                    "padeye_slip": padeye_slip(system)})
    return out


def padeye_slip(system, reach=50.0):
    """Mean plastic slip [m] of the soil's points between 10 m and ``reach`` [m] of line from the padeye:
    how far the chain next to it has slid through the soil on the way (the friction it mobilised)."""
    s = system.fem.full.s
    near = (s > 10.0) & (s < reach)
    return float(np.mean(system.history["full"][0]["soil"]["slip"][near]))


def conventional():
    """The conventional model: cablefem without soil and the frictionless elastic catenary."""
    fem = solve(scene("case3"))
    w = CHAIN.submerged_weight(1025.0, 9.81)
    closed = elastic_catenary(ANCHOR_RADIUS - FAIRLEAD_RADIUS, DEPTH - FAIRLEAD_DEPTH, 850.0, CHAIN.EA, w)
    fem["catenary_tension"] = float(np.hypot(closed.fairlead_horizontal, closed.fairlead_vertical))
    fem["catenary_angle_deg"] = float(np.degrees(np.arctan2(closed.fairlead_vertical, closed.fairlead_horizontal)))
    return fem


def cases(soil=SOIL, **mesh):
    """Cases 1-3 with ``soil`` (laid), each a dict of ``solve``."""
    return {case: solve(scene(case, soil, **mesh)) for case in CASES}


def compare(results):
    """Relative differences to rui2025 and its ordering (Case 2 > Case 1 > Case 3 at the fairlead)."""
    rows = {}
    for case, paper in PAPER.items():
        ours = results["conventional"] if case == "conventional" else results["cases"][case]
        rows[case] = {key: {"paper": value, "cablefem": ours[key], "relative": ours[key] / value - 1.0}
                      for key, value in paper.items() if key.endswith("tension")}
    fair = {case: results["cases"][case]["fairlead_tension"] for case in CASES}
    rows["ordering_holds"] = bool(fair["case2"] > fair["case1"] > fair["case3"])
    rows["case2_over_case1"] = fair["case2"] / fair["case1"] - 1.0
    rows["case3_under_case1"] = fair["case3"] / fair["case1"] - 1.0
    return rows


def sensitivity(factors=BEARING_FACTORS):
    """Cases 1-3 for each bearing factor N_c: fairlead and padeye tensions, resting depth, and the
    lying chain's friction ratio t_f / w = E_t / (E_n N_c)."""
    table = {}
    for factor in factors:
        solved = cases(dict(SOIL, bearing_factor=factor))
        table[f"{factor:g}"] = {case: {k: solved[case][k] for k in ("fairlead_tension", "padeye_tension",
                                                                     "resting_depth", "mudline_tension")}
                                for case in CASES}
        table[f"{factor:g}"]["friction_ratio"] = SOIL["width_tangential"] / (SOIL["width_normal"] * factor)
    return table


def three_lines():
    """Case 1 as the three-line scene: every line's fairlead tension (they must agree)."""
    built = scene("case1", SOIL, lines=3)
    tensions = []
    for line_ in built.lines:
        system = build_system(built, line_, dynamic=False)
        result = solve_pretension(system)
        tensions.append(report(system, result.X).fairlead_tension)
    return tensions


def run(fast=False, full=False):
    """Every run of the study (module docstring); ``fast``: the conventional model, Cases 1-3 and
    Case 3 installed as "catenary"; ``full`` adds the three-line scene."""
    start = time.perf_counter()
    results = {"conventional": conventional(), "cases": cases()}
    results["case3_catenary"] = solve(scene("case3", dict(SOIL, installation="catenary")))
    if not fast:
        results["bearing_factor"] = sensitivity()
        results["mesh"] = {"refined": cases(refine=2), "p2": cases(order=2)}
    if full:
        results["three_lines"] = three_lines()
    results["comparison"] = compare(results)
    results["wall_time_s"] = time.perf_counter() - start
    return results


def table(results):
    """The study's tables as text."""
    lines = ["rui2025 Sec. 4: tensions [kN], fairlead angle from the horizontal [deg], embedded length [m], "
             "plastic slip of the chain 10-50 m from the padeye [m]",
             f"{'run':<24}{'fairlead':>10}{'paper':>8}{'diff':>8}{'angle':>7}{'padeye':>9}{'paper':>7}"
             f"{'mudline':>9}{'embedded':>10}{'slip':>8}"]
    conv = results["conventional"]
    lines.append(f"{'conventional (no soil)':<24}{conv['fairlead_tension'] / 1e3:10.1f}{2437:8.0f}"
                 f"{100 * (conv['fairlead_tension'] / 2437e3 - 1):7.2f}%{conv['fairlead_angle_deg']:7.2f}"
                 f"{conv['padeye_tension'] / 1e3:9.1f}")
    lines.append(f"{'catenary 1.8 d_b':<24}{conv['catenary_tension'] / 1e3:10.1f}{2436:8.0f}"
                 f"{100 * (conv['catenary_tension'] / 2436e3 - 1):7.2f}%{conv['catenary_angle_deg']:7.2f}")
    runs = [(case, results["cases"][case]) for case in CASES] + [("case3 catenary start", results["case3_catenary"])]
    for name, row in runs:
        paper = PAPER.get(name.split()[0], {})
        pf, pp = paper.get("fairlead_tension"), paper.get("padeye_tension")
        diff = f"{100 * (row['fairlead_tension'] / pf - 1):7.2f}%" if pf and name in CASES else f"{'':8}"
        shown = [f"{x / 1e3:.0f}" if x and name in CASES else "-" for x in (pf, pp)]
        lines.append(f"{name:<24}{row['fairlead_tension'] / 1e3:10.1f}{shown[0]:>8}"
                     f"{diff}{row['fairlead_angle_deg']:7.2f}{row['padeye_tension'] / 1e3:9.1f}"
                     f"{shown[1]:>7}{row['mudline_tension'] / 1e3:9.1f}"
                     f"{row['embedded_length']:10.1f}{row['padeye_slip']:8.3f}")
    comp = results["comparison"]
    lines.append(f"ordering Case 2 > Case 1 > Case 3: {comp['ordering_holds']} (Case 2 {100 * comp['case2_over_case1']:+.1f} %, "
                 f"Case 3 {100 * comp['case3_under_case1']:+.1f} % of Case 1; paper +14.6 %, -7.6 %)")
    if "bearing_factor" in results:
        lines += ["", "bearing factor N_c: fairlead / padeye tension [kN], resting depth of the lying chain [m]",
                  f"{'N_c':>6}{'t_f/w':>7}" + "".join(f"{case:>22}" for case in CASES)]
        for factor, row in results["bearing_factor"].items():
            lines.append(f"{factor:>6}{row['friction_ratio']:7.3f}" + "".join(
                f"{row[c]['fairlead_tension'] / 1e3:9.1f} /{row[c]['padeye_tension'] / 1e3:6.1f} /{row[c]['resting_depth']:4.2f}"
                for c in CASES))
    if "mesh" in results:
        lines += ["", "mesh: fairlead / padeye tension [kN] at the default mesh (P1, 1 m then 5 m), halved, P2"]
        for case in CASES:
            cells = [results["cases"][case]] + [results["mesh"][k][case] for k in ("refined", "p2")]
            lines.append(f"{case:<8}" + "".join(f"{c['fairlead_tension'] / 1e3:10.2f} /{c['padeye_tension'] / 1e3:7.2f}"
                                                for c in cells))
    if "three_lines" in results:
        lines.append("three-line scene, Case 1 fairlead tensions [kN]: "
                     + ", ".join(f"{t / 1e3:.3f}" for t in results["three_lines"]))
    lines.append(f"wall time {results['wall_time_s']:.1f} s")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="the cases only, no sensitivity or mesh runs")
    parser.add_argument("--full", action="store_true", help="also the three-line scene")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for results.json and PNGs")
    args = parser.parse_args(argv)
    results = run(fast=args.fast, full=args.full)
    print(table(results))
    from .figures import figures

    path = write_json(args.out / "results.json", results)
    print(f"wrote {path}, {', '.join(figures(results, args.out))}")


if __name__ == "__main__":
    main()
