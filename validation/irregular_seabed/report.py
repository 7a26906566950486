"""The tables of validation/irregular_seabed's results, as text."""

from validation.irregular_seabed.model import MEAN_DEPTH, METHODS, SNAPSHOT_T


def print_report(results):
    """The comparison table, the findings with PASS/FAIL, and Table 6."""
    mn = 1e6
    print(f"desire2023 Sec. 5: irregular seabed, three ways ({'fast' if results['fast'] else 'full'} variant; "
          f"{results['settings']['elements']} P1 elements, dt = {results['settings']['dt']} s, "
          f"{results['settings']['duration']:g} s simulated)")
    print("\nseed  surface (rms / range about its plane)  method      dyn.peak  total peak  mean     "
          f"steady dyn.  touchdown x @{SNAPSHOT_T:g}s  grounded  wall     halved steps")
    for entry in results["seeds"]:
        surface = entry["surface"]
        for m in METHODS:
            r = entry["methods"][m]
            head = (f"{entry['seed']:>4}  {surface['roughness_rms_m']:5.2f} / {surface['roughness_range_m']:5.1f} m"
                    if m == "general" else f"{'':4}  {'':16}")
            if not r.get("completed"):
                print(f"{head}{'':23}{m:<11} FAILED: {r['error'] or r['status']}")
                continue
            print(f"{head}{'':23}{m:<11} {r['dynamic_peak_N'] / mn:6.3f}   {r['total_peak_N'] / mn:6.3f}    "
                  f"{r['mean_N'] / mn:6.3f}   {r['steady_dynamic_peak_N'] / mn:6.3f}       {r['touchdown_x_m']:8.1f} m"
                  f"          {r['grounded_length_m']:6.1f} m  {r['wall_time_s']:5.1f} s  {r['rejected_steps']:3d}")
    print("paper (Fig. 20 text)                                general    0.5      2.8\n"
          "                                                    inclined  <0.4      2.2\n"
          "                                                    horizontal<0.4      2.4   [MN]")
    print("\nfindings of desire2023 Sec. 5, per seed (primary seed first):")
    order = sorted(results["seeds"], key=lambda e: e["seed"] != results["primary_seed"])
    for name, label in (("general_highest_dynamic_peak", "general projection has the highest dynamic peak"),
                        ("horizontal_total_above_inclined", "horizontal total peak > inclined total peak"),
                        ("general_highest_total", "general projection has the highest total peak"),
                        ("touchdowns_differ", "the three touchdown points differ (> 1 m)"),
                        ("inclined_touchdown_nearer_fairlead_than_horizontal",
                         "inclined touchdown nearer the fairlead than horizontal")):
        marks = []
        for entry in order:
            f = entry["findings"].get(name)
            marks.append("n/a" if f is None else ("PASS" if f["passed"] else "FAIL"))
        passed, total = results["robustness"].get(name, (0, 0))
        print(f"  {label:<58} {' '.join(f'{x:>4}' for x in marks)}   ({passed}/{total} seeds)")
    sweep = results["static_sweep"]
    print(f"\nstatics at the largest surge (fairlead x = {sweep['fairlead_x_m']:g} m), many realisations: "
          f"inclined {sweep['inclined']['tension_N'] / mn:.3f} MN, horizontal {sweep['horizontal']['tension_N'] / mn:.3f} MN")
    print("amplitude  seeds  roughness rms    general: median  [min, max] MN    > inclined  > horizontal  > both")
    for r in sweep["amplitudes"]:
        print(f"{r['amplitude_m']:7.0f} m  {r['seeds']:5d}  {r['roughness_rms_m'][0]:4.1f}-{r['roughness_rms_m'][1]:3.1f} m"
              f"      {r['general_median_N'] / mn:6.3f}  [{r['general_range_N'][0] / mn:.3f}, {r['general_range_N'][1] / mn:.3f}]"
              f"        {r['fraction_above_inclined']:5.0%}      {r['fraction_above_horizontal']:5.0%}      "
              f"{r['fraction_above_both']:4.0%}" + (f"   ({len(r['failures'])} failed)" if r["failures"] else ""))
    if "table6" in results:
        print_table6(results["table6"])
    print(f"\ntotal wall time {results['total_wall_time_s']:.0f} s")


def print_table6(c):
    """Table 6: wall and CPU times of the two horizontal-seabed models, their ratio, the tensions."""
    print(f"\nTable 6: horizontal seabed z = -{MEAN_DEPTH} m, {c['duration_s']:g} s simulated, "
          f"{c['elements']} elements, dt = {c['dt']} s; triangulated with {c['triangles']} triangles")
    for path, data in c["paths"].items():
        print(f"  {path}: " + ("the compiled kernel, as `cablefem run` (frames and tensions.csv written)"
                               if path == "run_scene" else "the reference numpy assembly, time loop only"))
        print("  repeat  wall: Horizontal  general [s]  ratio   CPU: Horizontal  general [s]  ratio"
              "   max rel. tension diff.  load average")
        for r in data["rows"]:
            h, g = r["horizontal"], r["general"]
            if not (h["completed"] and g["completed"]):
                print(f"  {r['repeat']:>6}  FAILED: {h['error'] or g['error']}")
                continue
            print(f"  {r['repeat']:>6}  {h['wall_time_s']:16.2f}  {g['wall_time_s']:11.2f}  {r['ratio']:5.3f}"
                  f"  {h['cpu_time_s']:15.2f}  {g['cpu_time_s']:11.2f}  {r['cpu_ratio']:5.3f}"
                  f"   {r['max_relative_tension_difference']:.2e}               "
                  f"{h['load_average']:.1f} / {g['load_average']:.1f}")
        print(f"  ratio general / horizontal: wall {data['ratio_mean']:.3f} (min {data['ratio_min']:.3f}, "
              f"max {data['ratio_max']:.3f}), CPU {data['cpu_ratio_mean']:.3f} (min {data['cpu_ratio_min']:.3f}, "
              f"max {data['cpu_ratio_max']:.3f}); paper {c['paper_ratio']:.3f} (11236 s vs 13488 s)")
    print(f"one projection call ({c['elements'] + 1} points, derivatives): plane "
          f"{c['projection_call_s']['horizontal'] * 1e6:.1f} us, triangulated "
          f"{c['projection_call_s']['general'] * 1e6:.1f} us (x{c['projection_call_ratio']:.1f})")
    if c.get("tree_changed_during_measurement"):
        print("  WARNING: cablefem/ changed while Table 6 was measured; the times mix two versions")
    same = c["max_relative_tension_difference"] <= 1e-8
    print(f"same tensions on both (<= 1e-8 relative): {'PASS' if same else 'FAIL'} "
          f"({c['max_relative_tension_difference']:.1e})")
