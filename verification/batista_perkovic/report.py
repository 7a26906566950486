"""The tables of verification/batista_perkovic's results, as text."""

from verification.batista_perkovic.case import CONVERGED_RESIDUAL, PAPER_TABLE3, PAPER_TABLE4, TABLE3_NODES


def _f(value, spec):
    return "-" if value is None else format(value, spec)


def report_text(results):
    """The tables, as text."""
    out = [f"Batista & Perkovic on a {results['slope_deg']:g} deg seabed (falling from the anchor to the "
           f"fairlead), fairlead {results['height_m']} m above the anchor, w = {results['weight_N_per_m']:.1f} N/m "
           f"(g = {results['gravity']}), EA = {results['EA']:.4g} N, frictionless",
           "Geometry check, Table 4's H column reversed: our inextensible T_A against the paper's",
           "  H [MN]  paper T_A [kN]  ours [kN]   rel. diff   span X [m]  touchdown s [m]  inext/elastic - 1"]
    for r in results["evidence"]:
        out.append(f"  {r['force'] / 1e6:5.1f}   {r['paper_T_A'] / 1e3:10.0f}   {r['inextensible_T'] / 1e3:10.2f}  "
                   f"{r['relative']:+10.1e}  {r['span_m']:10.3f}  {r['touchdown_s_inextensible']:10.3f}"
                   f"       {r['inextensible_vs_elastic']:+.2e}")
    for setup in results["setups"]:
        out.append("")
        out.append(f"(a) Table 3 — {setup['name']}, G_K = {setup['stiffness']:.0e} N/m^3: |Delta| [m] at the "
                   "paper's nodes (arc lengths j L/31)")
        out.append("  H [MN]  against            " + "".join(f"{j:>7d}" for j in TABLE3_NODES) + "    max of 32")
        for row in setup["rows"]:
            H = row["force"]
            out.append(f"  {H / 1e6:4.1f}    paper (as printed) " + "".join(f"{v:7.3f}" for v in PAPER_TABLE3[H]))
            for name in ("inextensible", "elastic"):
                out.append(f"          ours vs {name[:6]:12s}" + "".join(f"{v:7.3f}" for v in row[name]["table3_delta_m"])
                           + f"   {row[name]['max_delta_32_nodes_m']:.4f}")
        out.append(f"(b) Table 4 — {setup['name']}: fairlead tension [kN]; paper with H reversed")
        out.append("  H [MN]   T_N       T_A inext  |T_N-T_A|  dT inext   T_A elastic |T_N-T_A|  dT elastic   paper T_N  T_A  dT"
                   "      touchdown err [m]  residual")
        for row in setup["rows"]:
            paper = PAPER_TABLE4[row["force"]]
            ti, te = row["inextensible"], row["elastic"]
            tn = row["fairlead_tension"]
            out.append(f"  {row['force'] / 1e6:4.1f}  {tn / 1e3:9.2f}  {ti['closed_form_fairlead_tension'] / 1e3:9.2f}"
                       f"  {abs(tn - ti['closed_form_fairlead_tension']) / 1e3:8.3f}  {abs(ti['fairlead_tension_error']):8.1e}"
                       f"  {te['closed_form_fairlead_tension'] / 1e3:10.2f}  {abs(tn - te['closed_form_fairlead_tension']) / 1e3:8.3f}"
                       f"  {abs(te['fairlead_tension_error']):8.1e}     {paper[0]:5d} {paper[1]:5d}  {paper[3]:.4f}"
                       f"      {_f(te['touchdown_error_m'], '+8.3f')}      {row['residual']:.0e}{' ' if row['converged'] else '!'}")
    study = results["convergence"]
    out.append("")
    out.append(f"(c) convergence at H = {study['force'] / 1e6:g} MN against the elastic closed form, "
               f"G_K = {study['stiffness']:.0e} N/m^3")
    for r in study["stiffness_note"]:
        out.append(f"  G_K {r['stiffness']:.0e}: resting penetration {r['penetration_m']:.2e} m -> fairlead tension "
                   f"{r['tension_effect']:+.1e}; one rounding of a position (eps |r|) is a contact force of "
                   f"{r['roundoff_contact_force_per_m']:.2g} N/m = {r['relative_to_weight']:.1e} w")
    out.append("  mesh          P  elems nodes  dT fairlead   dT anchor   node err [m] curve err [m] touchdown err [m]  Newton residual  wall [s]")
    for r in study["runs"]:
        e = r["elastic"]
        out.append(f"  {r['mesh']:12s}  {r['order']}  {r['elements']:4d} {r['nodes']:5d}  {e['fairlead_tension_error']:+10.2e}"
                   f"  {e['anchor_tension_error']:+10.2e}  {e['node_position_error_m']:10.2e}  {e['curve_position_error_m']:10.2e}"
                   f"   {_f(e['touchdown_error_m'], '+10.2e')}      {r['iterations']:4d}  {r['residual']:7.1e}{' ' if r['converged'] else '!'} {r['wall_time_s']:7.3f}")
    out.append(f"  ! = ended above a relative residual of {CONVERGED_RESIDUAL:g} (Newton's step-size exit): "
               "not counted for the targets")
    out.append(f"  observed orders (pairwise; least squares above {study['tension_floor']:g} in tension, "
               f"{study['position_floor_m']:g} m in position)")
    for key, orders in study["orders"].items():
        parts = []
        for name, label in (("fairlead_tension_error", "tension"), ("node_position_error_m", "nodes"),
                            ("curve_position_error_m", "curve")):
            o = orders[name]
            parts.append(f"{label} " + " ".join(_f(p, ".2f") for p in o["pairwise"]) + f" | {_f(o['fitted'], '.2f')}")
        out.append(f"  {key:18s} " + ";  ".join(parts))
    out.append("")
    out.append("(d) targets")
    for name, t in results["targets"].items():
        if isinstance(t, dict) and "value" in t:
            out.append(f"  {name:38s} {t['value']:.2e} <= {t['target']:g}: {'met' if t['met'] else 'NOT met'}")
        elif isinstance(t, dict):
            out.append(f"  {name:38s} |dT| <= {t['target']:g}: "
                       + (f"met from {t['elements_needed']} elements on" if t["met"] else "NOT met at the finest meshes")
                       + f" (first met at {t['first_met']}; missed at {t['misses']})")
        else:
            out.append(f"  {name:38s} ~{t} P1 elements (uniform, from the O(h^2) error)")
    out.append("  why P1 x 31 misses: chords shorter than arcs make the polygon as slack as a line longer by "
               "(h^2/24) int kappa^2 ds")
    out.append("  H [MN]  surplus [m]  predicted dT  P1x31 exact-vertex dT  (node err [m])  P1x31 uniform dT  "
               "(its touchdown err [m])")
    for r in results["p1_diagnosis"]:
        out.append(f"  {r['force'] / 1e6:4.1f}    {r['surplus_m']:8.4f}     {r['predicted']:+9.2e}      "
                   f"{r['exact_vertex']:+9.2e}          ({r['exact_vertex_position_m']:.3f})        "
                   f"{r['uniform']:+9.2e}       ({_f(r['uniform_touchdown_error_m'], '+.3f')})")
    out.append(f"wall time {results['wall_time_s']:.1f} s")
    return "\n".join(out)
