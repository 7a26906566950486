"""The tables of verification/stability's results, as text."""


def _f(value, spec):
    return "-" if value is None else format(value, spec)


def _status(row):
    return "ok" if row["status"] == "completed" else row["status"]


def _energy(row):
    e = row.get("energy")
    if not e:
        return "-"
    return (f"W {e['fairlead_work_J'] / 1e6:8.3f} MJ  dE {e['mechanical_change_J'] / 1e6:8.3f}  "
            f"D {sum(e['dissipated_J'].values()) / 1e6:7.3f}  W_am {e['added_mass_work_J'] / 1e6:7.3f}  "
            f"E_num {e['numerical_relative']:+.1e} of {e['throughput_J'] / 1e6:.3g} MJ  "
            f"min P_diss {e['least_dissipation_relative']:+.0e}")


def report_text(results):
    """The tables, as text."""
    out = []
    for key, table in TABLES.items():
        if key in results:
            out += table(results[key])
    out.append(f"wall time {results['wall_time_s']:.1f} s")
    return "\n".join(out)


def _stiff_table(r):
    """Lines of case 1. the stiff line."""
    out = []
    lim = r["explicit_limits"]
    out += [f"1. Batista-Perkovic stiffness: EA 5.055e11 N, G_K 3e14 N/m^3, P1 x 31 ({lim['element_m']:.1f} m), "
            f"fairlead swept H 3.5 -> 4.5 -> 3.5 MN over {r['period_s']:g} s (ran {r['duration_s']:g} s)",
            f"   an explicit code needs dt < h/sqrt(EA/m) = {lim['axial_cfl_s']:.2e} s (axial wave) and "
            f"< 2/sqrt(G_K d/m) = {lim['seabed_spring_s']:.2e} s (seabed spring)",
            "   static FEM vs closed form along the motion: "
            + ", ".join(f"{s['error']:+.1e}" for s in r["statics"]),
            "   integrator   dt [s]  max|dT| loading  unloading  vs finest  T range [MN]  peak KE [J]  rejected  "
            "wall [s]  status"]
    for row in r["rows"]:
        out.append(f"   {row['integrator']:17s} {row['dt']:5.3f}  {row['max_error_loading']:9.1e}  "
                   f"{_f(row['max_error_unloading'], '9.1e')}  {row['max_difference_to_finest_loading']:9.1e}  "
                   f"{row['least_tension'] / 1e6:5.2f}-{row['peak_tension'] / 1e6:<6.2f}  "
                   f"{row['peak_kinetic_J']:10.3g}  {row['rejected']:6d}  {row['wall_time_s']:7.1f}  {_status(row)}")
    out.append("")
    return out


def _snap_table(r):
    """Lines of case 2. snap loads."""
    out = []
    out += [f"2. Snap loads: flume flat floor, {r['amplitude_m']:g} m / 6 s surge, {r['duration_s']:g} s",
            "   dt [s]   peak T [MN]  vs finest  min T [MN]  slack  rejected  wall [s]  energy balance"]
    for row in r["rows"]:
        out.append(f"   {row['dt']:6.4f}  {row['peak_tension'] / 1e6:9.4f}  {row['peak_error_vs_finest']:+9.2e}  "
                   f"{row['least_tension'] / 1e6:8.4f}  {row['slack_fraction']:5.2f}  {row['rejected']:5d}  "
                   f"{row['wall_time_s']:7.1f}  {_energy(row)}  {'' if row['completed'] else _status(row)}")
    out.append("   peak per 6 s period [MN]: " + "; ".join(
        f"dt {row['dt']:g}: " + " ".join(f"{p / 1e6:.3f}" for p in row["peak_per_period"]) for row in r["rows"]))
    out.append("")
    return out


def _edge_table(r):
    """Lines of case 3. the steep step's edge."""
    out = []
    out += ["3. Steep 19 deg step, convex edge at x = -200 m",
            "   motion        dt [s]  peak T [MN]  vs finest  min T [MN]  rejected  worst in one step  "
            "max Newton/step  edge flips/step  energy balance"]
    for row in r["rows"]:
        out.append(f"   {row['motion']:12s}  {row['dt']:5.3f}  {row['peak_tension'] / 1e6:9.4f}  "
                   f"{row['peak_difference_vs_finest']:+9.2e}  {row['least_tension'] / 1e6:8.4f}  {row['rejected']:5d}  "
                   f"{row['worst_rejections_in_one_step']:5d}  {row['most_newton_iterations_in_one_step']:5d}  "
                   f"{row['edge_changes_per_step']:8.3f}  {_energy(row)}  {'' if row['completed'] else _status(row)}")
    out.append("")
    return out


def _lying_taut_table(r):
    """Lines of case 4. lying and taut lines."""
    out = []
    out += [f"4. Lying line (fairlead on the floor, {r['lying']['pretension_N'] / 1e3:g} kN, slid "
            f"+-{r['lying']['stroke_m']:g} m along itself over {r['lying']['period_s']:g} s) and taut line "
            f"(chord/stretched {r['taut']['chord_ratios'][0]} -> {r['taut']['chord_ratios'][1]} over "
            f"{r['taut']['period_s']:g} s)",
            "   case   friction  dt [s]  max|T-T_cf|/peak  at start  T_cf peak [MN]  rejected (worst step)  wall [s]  "
            "energy balance"]
    for row in r["rows"]:
        out.append(f"   {row['case']:6s} {str(row['friction']):8s} {row['dt']:5.3f}  "
                   f"{row['max_error_vs_frictionless_closed_form']:9.2e}  {row['error_at_start']:+9.1e}  "
                   f"{row['closed_form_peak'] / 1e6:9.3f}  {row['rejected']:5d} ({row['worst_rejections_in_one_step']:2d})"
                   f"  {row['wall_time_s']:7.1f}  "
                   f"{_energy(row)}  {'' if row['completed'] else _status(row)}")
    out.append("")
    return out


def _stop_table(r):
    """Lines of case 5. the sudden stop."""
    out = []
    out += [f"5. Sudden stop: {r['speed_m_s']:g} m/s for {r['stroke_m']:g} m, dead stop at t = {r['stop_s']:g} s, "
            f"frictionless, {r['duration_s']:g} s",
            "   dt [s]  static T [MN]  overshoot  max|T - T_static| per 5 s after the stop [kN]"
            "                 e-fold [s]  final error  energy balance"]
    for row in r["rows"]:
        env = " ".join(f"{w['max_deviation_N'] / 1e3:7.1f}" for w in row["windows"][:10])
        out.append(f"   {row['dt']:5.3f}  {row['static_tension'] / 1e6:9.4f}  {row['overshoot']:+8.2%}  {env}  "
                   f"{_f(row['envelope_decay_time_s'], '6.2f')}  {row['final_error']:+9.1e}  {_energy(row)}  "
                   f"{'' if row['completed'] else _status(row)}")
    out.append("")
    return out


def _steps_table(r):
    """Lines of case 6. the time steps."""
    out = []
    out += [f"6. Time steps on the snap scene ({r['duration_s']:g} s through run_scene), against fixed steps of "
            f"{r['reference_dt']:g} s (peak {r['reference_peak_tension'] / 1e6:.4f} MN)",
            "   dt [s]   RMS error  peak error  largest T written [MN]  shortest step [s]  steps    Newton  "
            "rejected  wall [s]  NaN  status"]
    for row in r["rows"]:
        out.append(f"   {row['dt']:7.4f}  {row['rms_error_vs_finest']:9.2e}  {row['peak_error_vs_finest']:+9.2e}  "
                   f"{row['largest_tension_written'] / 1e6:12.4g}  {row['shortest_step_written']:14.2e}  "
                   f"{row['steps']:6d}  {row['newton_iterations']:7d}  {row['rejected']:6d}  {row['wall_time_s']:7.1f}  "
                   f"{str(row['nan_in_outputs']):5s}  {_status(row)}")
    out.append("")
    return out


def _reproductions_table(r):
    """Lines of case 7. the reproductions."""
    out = []
    out += ["7a. A 4-element chain (EA 5.055e11 N) laid onto a flat seabed at 0.06 m/s, 30 s: peak kinetic energy",
            "   G_K [N/m^3]  dt [s]   peak KE [J]  rejected  status"]
    for row in r["landing"]:
        out.append(f"   {row['stiffness']:9.0e}  {row['dt']:6.3f}  {row['peak_kinetic_J']:10.3e}  "
                   f"{row['rejected']:5d}  {_status(row)}")
    out += ["7b. The same chain hanging freely, fairlead moved 1 m (smooth, 20 s), dt = 0.01 s: peak kinetic energy",
            "   integrator          rho_inf  EA [N]     peak KE [J]  rejected  status"]
    for row in r["alpha"]:
        out.append(f"   {row['integrator']:18s}  {_f(row['rho_inf'], '5.1f'):5s}  {row['EA']:9.3g}  "
                   f"{row['peak_kinetic_J']:10.3e}  {row['rejected']:5d}  {_status(row)}")
    f = r["frames"]
    out += [f"7c. run_scene at dt = {f['dt']:g} s with frames every {f['every']:g} s (toy chain, EA 3.15e9 N): "
            f"tension {f['first_tension'] / 1e3:.1f} kN at t = 0, largest written {f['largest_tension'] / 1e3:.4g} kN "
            f"at t = {f['time_of_largest']:.4f} s; shortest step written {f['shortest_step_written']:.2e} s; "
            f"status {f['status']}", ""]
    return out


#: per case's results key, the function that makes its lines
TABLES = {"stiff": _stiff_table, "snap": _snap_table, "edge": _edge_table, "lying_taut": _lying_taut_table,
          "stop": _stop_table, "steps": _steps_table, "repro": _reproductions_table}
