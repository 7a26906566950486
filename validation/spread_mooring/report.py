"""The tables of validation/spread_mooring's results, as text."""

import math

from validation.spread_mooring.lines import HEIGHT, LENGTH
from validation.spread_mooring.spread import name_of_spread


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
