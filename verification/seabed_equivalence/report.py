"""The tables of verification/seabed_equivalence's results."""

from verification.seabed_equivalence.files import TOLERANCE


def _fmt(spread, digits=3):
    return f"{spread['median']:.{digits}f} [{spread['min']:.{digits}f}, {spread['max']:.{digits}f}]"


def print_tables(results):
    """The three tables of results (a dict as ``run`` returns it)."""
    print("(a) the same plane, five descriptions: errors relative to the plane's answer "
          f"(tolerance {TOLERANCE:g})")
    print(f"{'seabed':<22} {'simplify':>8} {'model':>10} {'against':>16} {'|dF_fair|/|F|':>14} "
          f"{'|dF_anch|/|F|':>14} {'|dX|/L':>10} {'iters':>6}")
    for row in results["equivalence"]:
        print(f"{row['seabed']:<22} {str(row['simplify']).lower():>8} {row['model']:>10} "
              f"{row['compared_with']:>16} {row['fairlead_force_error']:14.2e} "
              f"{row['anchor_force_error']:14.2e} {row['node_error']:10.2e} {row['newton_iterations']:6d}")
    static = results["static_cost"]
    print(f"\n(b) static solve, CPU time relative to the plane's; median [min, max] of "
          f"{len(static['rows'][0]['cpu_s']['values'])} interleaved repeats; mesh of "
          f"{static['mesh_triangles']} triangles")
    print(f"{'case':<28} {'iters':>6} {'CPU s':>8} {'ratio':>24} {'per iteration':>24}")
    for row in static["rows"]:
        print(f"{row['case']:<28} {row['newton_iterations']:6d} {row['cpu_s']['median']:8.4f} "
              f"{_fmt(row['ratio']):>24} {_fmt(row['ratio_per_iteration']):>24}")
    print(f"detection (simplify) alone: {1e3 * static['detection_cpu_s']['median']:.3f} ms")
    dynamic = results["dynamic_cost"]
    print(f"\n(c) flume flat dynamic run, {dynamic['duration_s']:g} s at dt = {dynamic['dt']:g} s, "
          f"time steps only, CPU time; {dynamic['repeats']} interleaved repeats: ratio of the fastest "
          "runs, and median [min, max] of the ratios within a repeat")
    print(f"{'Newton':<9} {'seabed':<32} {'triangles':>9} {'iters':>6} {'CPU s':>7} {'fastest':>8} "
          f"{'CPU ratio':>24} {'wall ratio':>24} {'|dX| end [m]':>12}")
    for row in dynamic["rows"]:
        print(f"{row['newton']:<9} {row['seabed']:<32} {row['triangles'] or '-':>9} "
              f"{row['newton_iterations']:6d} "
              f"{row['cpu_s']['median']:7.3f} {row['ratio_of_fastest']:8.3f} {_fmt(row['ratio']):>24} "
              f"{_fmt(row['wall_ratio']):>24} {row['final_position_difference_m']:12.2e}")
    scene = dynamic["run_scene"]
    print(f"run_scene, {scene['duration_s']:g} s (static start, VTK frames, tensions.csv): "
          f"mesh / horizontal CPU {scene['ratio_of_fastest']:.3f} (fastest), {_fmt(scene['ratio'])}")
    print("seabed.project inside the run:", ", ".join(
        f"{label} {v['us_per_call']:.0f} us/call ({100 * v['share_of_run']:.0f} % of the run)"
        if v["calls"] else f"{label} inside the step kernel"
        for label, v in dynamic["projection_per_call"].items()))
