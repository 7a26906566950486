"""Wall time per simulated second of the six desire2023 flume cases (issue 4's benchmark).

Each case (flat, gentle 4 deg and steep 19 deg seabed; quasi-static 17 s / 2.5 m / 15 m
drift and dynamic 6 s / 5 m motions, ``cablefem.model.builtin.flume_scene``) is run through
``cablefem.runs.run.run_scene`` exactly as ``cablefem run`` does it, output frames every 0.1 s
included, at a few settings of element order, element count and time step. The table gives
wall time per simulated second (static start and file writing included) and the largest
fairlead tension, whose spread over the settings shows what the cheaper ones give up.

    python -m benchmarks.flume_cost [--duration T] [--json FILE]

Timings are of this machine and its load at the time; ratios between rows of one run are
what to read. numba's first compilation of the step kernel is done before timing.

Last measured on an idle 2-core machine, 18 s simulated (wall seconds per simulated second;
entries move by about +-0.003 between runs, and by several times on a loaded machine):

    settings                     flat q-s  flat dyn  gentle q-s  gentle dyn  steep q-s  steep dyn  Newton/step
    P1 x 40, dt 0.01 (default)   0.013     0.014     0.015       0.016       0.014      0.016      1.7 - 2.2
    P1 x 80, dt 0.005            0.022     0.035     0.029       0.038       0.029      0.036      1.8 - 2.1
    P2 x 20, dt 0.01             0.011     0.014     0.014       0.016       0.014      0.016      1.7 - 2.1
    P2 x 40, dt 0.005            0.022     0.032     0.027       0.035       0.027      0.032      1.8 - 2.1
    P3 x 14, dt 0.01             0.013     0.016     0.015       0.018       0.015      0.018      1.7 - 2.2

At dt 0.01 s the steps are under a third of such a run (flat dynamic P1 x 40, 18 s: the steps
0.09 s, the 180 VTU frames 0.11 s, of 0.32 s).
"""

import argparse
import json
import tempfile
import time

from cablefem.runs.run import run_scene
from cablefem.model.builtin import FLUME_MOTIONS, FLUME_SEABEDS, flume_scene

#: (order, elements, dt [s]); the first is the built-in scene's
SETTINGS = ((1, 40, 0.01), (1, 80, 0.005), (2, 20, 0.01), (2, 40, 0.005), (3, 14, 0.01))


def time_case(seabed, motion, order, elements, dt, duration):
    """(wall seconds per simulated second, largest fairlead tension [N], steps, status)."""
    scene = flume_scene(seabed, motion, elements=elements, order=order, duration=duration, dt=dt)
    with tempfile.TemporaryDirectory(prefix="cablefem-bench-") as out:
        start = time.perf_counter()
        summary = run_scene(scene, out, progress=False)
        wall = time.perf_counter() - start
    extremes = next(iter(summary["tension_extremes"].values()))
    return {"seabed": seabed, "motion": motion, "order": order, "elements": elements, "dt": dt,
            "duration_s": duration, "wall_s": wall, "wall_per_simulated_s": wall / duration,
            "fairlead_tension_max_N": extremes["fairlead_tension_max"], "steps": summary["steps"],
            "newton_iterations": summary["newton_iterations"], "status": summary["status"]}


def run(duration=18.0, settings=SETTINGS):
    time_case("flat", "dynamic", 1, 10, 0.05, 0.2)  # compile (or load) the numba kernel
    rows = []
    for seabed in FLUME_SEABEDS:
        for motion in FLUME_MOTIONS:
            for order, elements, dt in settings:
                rows.append(time_case(seabed, motion, order, elements, dt, duration))
    return rows


def table(rows):
    lines = [f"{'seabed':7s} {'motion':13s} {'order':>5s} {'elems':>5s} {'dt [s]':>7s} "
             f"{'wall/sim':>9s} {'steps':>6s} {'Newton/step':>11s} {'max T [MN]':>10s}  status"]
    for r in rows:
        lines.append(f"{r['seabed']:7s} {r['motion']:13s} {r['order']:5d} {r['elements']:5d} {r['dt']:7.3f} "
                     f"{r['wall_per_simulated_s']:9.3f} {r['steps']:6d} "
                     f"{r['newton_iterations'] / max(r['steps'], 1):11.2f} "
                     f"{r['fairlead_tension_max_N'] / 1e6:10.4f}  {r['status']}")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=18.0, help="simulated seconds per run")
    parser.add_argument("--json", help="write the rows to this JSON file")
    args = parser.parse_args(argv)
    rows = run(args.duration)
    print(table(rows))
    if args.json:
        with open(args.json, "w") as handle:
            json.dump(rows, handle, indent=1)


if __name__ == "__main__":
    main()
