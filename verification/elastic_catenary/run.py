"""Elastic catenary on a flat and on an inclined seabed: FEM against the closed form.

The closed forms of ``cablefem.statics.catenary`` (``elastic_catenary``: Jonkman 2007,
the model of MAP++ and MoorPy; ``inclined_catenary`` with finite EA: Batista &
Perkovic 2019 made elastic) against cablefem's statics for the desire2023
Table 5 chain (EA = 3.15e9 N), frictionless, with the anchor on the seabed and
the fairlead 100 m above it, 635 m of line:

- flat: anchor (-595, 0, -100), the flume geometry of ``cablefem.model.builtin``;
- inclined: the seabed rises 5 deg from the anchor towards the fairlead,
  anchor (-615, 0, -100): taut to the anchor (a frictionless up-slope would
  let slack line slide down and pile at the anchor).

For P1, P2, P3 and a range of element counts, on a uniform mesh, on the mesh
cablefem fits to the touchdown (``solve_line``) and on a mesh with a vertex
at the exact touchdown: fairlead and anchor tension, touchdown arc length and
position errors, observed orders, wall times. Run ``python -m
verification.elastic_catenary.run [--fast] [--out DIR] [--stiffness G_K]``;
``run(fast=True)`` returns what tests/test_verification_statics.py asserts.
"""

import argparse
import math
import time
from pathlib import Path

import numpy as np

from cablefem.statics.catenary import elastic_catenary, inclined_catenary
from cablefem.geometry import Horizontal, Plane
from cablefem.model.line import Line, Segment
from cablefem.runs.results import report
from cablefem.model.scene import Contact, Environment
from cablefem.model.builtin import table5_chain
from cablefem.study import observed_orders, position_errors, solve_on_mesh, write_json

HERE = Path(__file__).resolve().parent

LENGTH = 635.0  # m
DEPTH = 100.0  # m, fairlead above the anchor
WATER_DENSITY = 1025.0  # kg/m^3
GRAVITY = 9.81  # m/s^2
#: G_K [N/m^3]: stiff enough that the resting penetration moves the fairlead tension by ~1e-9
#: (``stiffness_table``), soft enough that a rounding of a position is a negligible force
STIFFNESS = 3e11
STIFFNESSES = (3e5, 3e9, 3e10, 3e11, 3e12, 3e14)  # the table that justifies the choice
CASES = {"flat": {"span": 595.0, "slope_deg": 0.0}, "inclined": {"span": 615.0, "slope_deg": 5.0}}
ELEMENTS = (5, 10, 20, 40, 80, 160)
FAST_ELEMENTS = (10, 20, 40)
ORDERS = (1, 2, 3)
MESHES = ("uniform", "fitted", "exact-vertex")
TARGET = {"case": "flat", "order": 2, "elements": 40, "mesh": "fitted", "tension": 1e-6}
TENSION_FLOOR = 1e-8  # below: penetration and round-off, not discretisation
POSITION_FLOOR = 1e-6  # m
CONVERGED_RESIDUAL = 1e-3  # a solve ending above this stopped on Newton's step test: flagged


def chain():
    """The desire2023 Table 5 chain."""
    return table5_chain()


def weight():
    """Submerged weight per unit length [N/m]."""
    return chain().submerged_weight(WATER_DENSITY, GRAVITY)


class Case:
    """Closed form, seabed, anchor (-X, 0, -100) and fairlead at the origin of one case."""

    def __init__(self, name, stiffness=STIFFNESS):
        self.name = name
        self.span = CASES[name]["span"]
        self.slope = math.radians(CASES[name]["slope_deg"])
        self.stiffness = stiffness
        self.exact = self.closed_form(self.span, DEPTH)
        self.anchor = np.array([-self.span, 0.0, -DEPTH])
        self.fairlead = np.zeros(3)
        self.seabed = Horizontal(DEPTH) if self.slope == 0.0 else Plane.from_slope(self.anchor, self.slope)

    def closed_form(self, span, height, length=LENGTH):
        """The closed form for a fairlead at (span, height) [m] from the anchor."""
        if self.slope == 0.0:
            return elastic_catenary(span, height, length, chain().EA, weight(), friction=0.0)
        return inclined_catenary(span, height, length, weight(), self.slope, chain().EA)

    def penetration(self, stiffness=None):
        """Resting penetration w n_z / (G_K d) [m]."""
        return weight() * self.seabed.normal[2] / ((stiffness or self.stiffness) * chain().diameter)

    def line(self, order, elements, touchdown=None):
        """The FEM line anchored at the resting depth, uniform or with a vertex at ``touchdown``."""
        anchor = self.anchor - self.penetration() * self.seabed.normal
        if touchdown is None:
            segments = [Segment(chain(), LENGTH, elements)]
        else:
            lying = min(max(1, round(elements * touchdown / LENGTH)), elements - 1)
            segments = [Segment(chain(), touchdown, lying), Segment(chain(), LENGTH - touchdown, elements - lying)]
        return Line(self.name, anchor, self.fairlead, segments, order)

    def reference_points(self, s):
        """Closed-form positions (n, 3) [m] at unstretched arc lengths s (n,)."""
        x, z = self.exact.profile(s)
        return self.anchor + np.column_stack([x, np.zeros_like(x), z])


def stiffness_table(case):
    """Per G_K: resting penetration [m], its effect on the fairlead tension (closed form with the
    fairlead moved by it along the normal) and the contact force of one rounding of a position
    (G_K d eps |r|) against the weight per unit length."""
    rows = []
    n = case.seabed.normal
    reach = float(np.abs(case.anchor).max())
    for stiffness in STIFFNESSES:
        depth = case.penetration(stiffness)
        moved = case.closed_form(case.span + depth * n[0], DEPTH + depth * n[2])
        roundoff = stiffness * chain().diameter * np.finfo(float).eps * reach
        rows.append({"stiffness": stiffness, "penetration_m": depth,
                     "tension_effect": moved.fairlead_tension / case.exact.fairlead_tension - 1.0,
                     "roundoff_force_per_weight": roundoff / weight()})
    return rows


def solve(case, order, elements, mesh, tolerance=1e-8):
    """(system, StaticResult, wall time [s]); mesh "uniform", "fitted" (``solve_line``) or
    "exact-vertex" (a vertex at the closed-form touchdown)."""
    return solve_on_mesh(lambda vertex: case.line(order, elements, vertex), case.seabed,
                         Contact(stiffness=case.stiffness), Environment(water_density=WATER_DENSITY, gravity=GRAVITY),
                         mesh, case.exact.touchdown_s, tolerance)


def measure(case, system, result, wall):
    """Errors of one solve against the closed form (JSON-ready)."""
    rep = report(system, result.X)
    fem = system.fem
    nodes, curve = position_errors(fem, result.X, case.reference_points, LENGTH)
    return {"order": fem.order, "elements": fem.n_elements, "nodes": int(fem.n_dofs),
            "iterations": int(result.iterations), "residual": float(result.residual),
            "converged": bool(result.residual <= CONVERGED_RESIDUAL), "wall_time_s": wall,
            "fairlead_tension": rep.fairlead_tension, "anchor_tension": rep.anchor_tension,
            "fairlead_tension_error": rep.fairlead_tension / case.exact.fairlead_tension - 1.0,
            "anchor_tension_error": rep.anchor_tension / case.exact.anchor_tension - 1.0,
            "touchdown_s": rep.touchdown_s,
            "touchdown_error_m": None if rep.touchdown_s is None else rep.touchdown_s - case.exact.touchdown_s,
            "node_position_error_m": nodes, "curve_position_error_m": curve}


QUANTITIES = (("fairlead_tension_error", TENSION_FLOOR), ("anchor_tension_error", TENSION_FLOOR),
              ("touchdown_error_m", POSITION_FLOOR), ("node_position_error_m", POSITION_FLOOR),
              ("curve_position_error_m", POSITION_FLOOR))


def study(name, fast, stiffness=STIFFNESS):
    """One case: every mesh x order x element count, with observed orders."""
    case = Case(name, stiffness)
    elements = FAST_ELEMENTS if fast else ELEMENTS
    runs, orders = [], {}
    for mesh in MESHES:
        for order in ORDERS:
            found = [dict(measure(case, *solve(case, order, n, mesh)), mesh=mesh) for n in elements]
            runs += found
            orders[f"{mesh} P{order}"] = observed_orders(elements, found, dict(QUANTITIES))
    exact = case.exact
    return {"case": name, "slope_deg": CASES[name]["slope_deg"], "span_m": case.span, "stiffness": case.stiffness,
            "exact": {"fairlead_tension": exact.fairlead_tension, "anchor_tension": exact.anchor_tension,
                      "touchdown_s": exact.touchdown_s, "regime": exact.regime},
            "stiffness_table": stiffness_table(case), "elements": list(elements), "runs": runs, "orders": orders}


def run(fast=False, stiffness=STIFFNESS):
    """Both cases; a dict of plain numbers (JSON-ready)."""
    start = time.perf_counter()
    cases = {name: study(name, fast, stiffness) for name in CASES}
    flat = [r for r in cases[TARGET["case"]]["runs"] if r["mesh"] == TARGET["mesh"]
            and r["order"] == TARGET["order"] and r["elements"] == TARGET["elements"]][0]
    target = dict(TARGET, value=flat["fairlead_tension_error"],
                  met=flat["converged"] and abs(flat["fairlead_tension_error"]) <= TARGET["tension"])
    others = {}
    for mesh in MESHES:
        r = [x for x in cases["flat"]["runs"] if x["mesh"] == mesh and x["order"] == 2 and x["elements"] == 40][0]
        others[mesh] = r["fairlead_tension_error"]
    target["P2x40_flat_by_mesh"] = others
    return {"fast": fast, "gravity": GRAVITY, "EA": chain().EA, "weight_N_per_m": weight(),
            "cases": cases, "target": target, "wall_time_s": time.perf_counter() - start}


def _f(value, spec):
    return "-" if value is None else format(value, spec)


def report_text(results):
    """The tables, as text."""
    out = [f"Elastic catenary, Table 5 chain: EA = {results['EA']:.3g} N, w = {results['weight_N_per_m']:.1f} N/m "
           f"(g = {results['gravity']}), L = {LENGTH:g} m, fairlead {DEPTH:g} m above the anchor, frictionless"]
    for name, c in results["cases"].items():
        e = c["exact"]
        out.append("")
        out.append(f"== {name}: seabed slope {c['slope_deg']:+g} deg, span {c['span_m']:g} m; closed form: "
                   f"T_F = {e['fairlead_tension'] / 1e3:.3f} kN, T_A = {e['anchor_tension'] / 1e3:.3f} kN, "
                   f"touchdown s = {e['touchdown_s']:.4f} m ({e['regime']})")
        out.append("  seabed stiffness: resting penetration w n_z/(G_K d) and what it does to T_F; a rounding of a "
                   "position as a contact force")
        for r in c["stiffness_table"]:
            mark = "  <- used" if r["stiffness"] == c["stiffness"] else ""
            out.append(f"    G_K {r['stiffness']:7.0e} N/m^3: penetration {r['penetration_m']:9.2e} m, "
                       f"T_F {r['tension_effect']:+9.1e}, round-off {r['roundoff_force_per_weight']:8.1e} w{mark}")
        out.append("  mesh          P  elems nodes   dT fairlead  dT anchor   touchdown [m]  node err [m] curve err [m]"
                   "  Newton residual  wall [s]")
        for r in c["runs"]:
            out.append(f"  {r['mesh']:12s}  {r['order']}  {r['elements']:4d} {r['nodes']:5d}  "
                       f"{r['fairlead_tension_error']:+10.2e}  {r['anchor_tension_error']:+10.2e}  "
                       f"{_f(r['touchdown_error_m'], '+10.2e')}    {r['node_position_error_m']:10.2e}  "
                       f"{r['curve_position_error_m']:10.2e}    {r['iterations']:4d} {r['residual']:7.1e}"
                       f"{' ' if r['converged'] else '!'} {r['wall_time_s']:7.3f}")
        out.append(f"  ! = ended above a relative residual of {CONVERGED_RESIDUAL:g} (Newton's step-size exit)")
        out.append(f"  observed orders: pairwise | least squares above {TENSION_FLOOR:g} (tension), "
                   f"{POSITION_FLOOR:g} m (positions)")
        for key, orders in c["orders"].items():
            parts = []
            for name_, label in (("fairlead_tension_error", "T_F"), ("anchor_tension_error", "T_A"),
                                 ("touchdown_error_m", "s_td"), ("node_position_error_m", "nodes"),
                                 ("curve_position_error_m", "curve")):
                o = orders[name_]
                parts.append(f"{label} " + " ".join(_f(p, ".1f") for p in o["pairwise"]) + f"|{_f(o['fitted'], '.2f')}")
            out.append(f"    {key:15s} " + "; ".join(parts))
    t = results["target"]
    out.append("")
    out.append(f"target: {t['case']} P{t['order']} x {t['elements']} ({t['mesh']} mesh) fairlead tension "
               f"|{t['value']:.2e}| <= {t['tension']:g}: {'met' if t['met'] else 'NOT met'}; P2 x 40 by mesh: "
               + ", ".join(f"{m} {v:+.1e}" for m, v in t["P2x40_flat_by_mesh"].items()))
    out.append(f"wall time {results['wall_time_s']:.1f} s")
    return "\n".join(out)


def figures(results, out):
    """convergence.png: fairlead tension and position errors against elements, both cases."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    styles = {"uniform": "o-", "fitted": "s--", "exact-vertex": "^:"}
    fig, ax = plt.subplots(2, 2, figsize=(11, 8))
    for row, (name, c) in enumerate(results["cases"].items()):
        for mesh in MESHES:
            for order in ORDERS:
                runs = [r for r in c["runs"] if r["mesh"] == mesh and r["order"] == order]
                n = [r["elements"] for r in runs]
                kw = dict(color=f"C{order - 1}", label=f"P{order} {mesh}")
                ax[row, 0].loglog(n, [max(abs(r["fairlead_tension_error"]), 1e-13) for r in runs], styles[mesh], **kw)
                ax[row, 1].loglog(n, [r["curve_position_error_m"] for r in runs], styles[mesh], **kw)
                for r in runs:
                    if not r["converged"]:  # Newton's step-size exit: marked, not trusted
                        ax[row, 0].loglog(r["elements"], max(abs(r["fairlead_tension_error"]), 1e-13), "kx", ms=9)
                        ax[row, 1].loglog(r["elements"], r["curve_position_error_m"], "kx", ms=9)
        ax[row, 0].axhline(TARGET["tension"], color="k", lw=0.6, ls="--")
        ax[row, 0].set(xlabel="elements", ylabel="|fairlead tension error|", title=f"{name} ({c['slope_deg']:+g} deg)")
        ax[row, 1].set(xlabel="elements", ylabel="max position error on the line [m]", title=name)
    ax[0, 0].legend(fontsize=6, ncol=3, title="x: stopped above residual 1e-3", title_fontsize=6)
    for a in ax.ravel():
        a.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "convergence.png", dpi=120)
    plt.close("all")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="three element counts: a few seconds")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for results.json and the PNG")
    parser.add_argument("--stiffness", type=float, default=STIFFNESS, help="seabed G_K [N/m^3]")
    args = parser.parse_args(argv)
    results = run(fast=args.fast, stiffness=args.stiffness)
    print(report_text(results))
    args.out.mkdir(parents=True, exist_ok=True)
    write_json(args.out / "results.json", results, private=True)
    figures(results, args.out)
    print(f"wrote {args.out / 'results.json'} and convergence.png")


if __name__ == "__main__":
    main()
