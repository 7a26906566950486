"""What waves cost a run: the same line and fairlead motion in still water, in a regular wave and
in irregular seas of 50 and 200 components, run side by side (issue 35's target: a run in waves at
most 1.3x the same run without).

The line is a 100 m deep chain catenary (P1 elements, generalised-alpha, the fairlead surging
+-2 m over 10 s), run through ``cablefem.runs.run.run_scene`` as ``cablefem run`` does it (frames and
the free surface's frames every ``--every`` s included: each frame in waves is two files); CPU time
of the process per run, rounds alternating between the cases, medians over the rounds, and the
ratio to still water's run in the same round.

    python -m benchmarks.waves_cost [--duration T] [--rounds N] [--elements N] [--every S] [--json FILE]

Last measured: verification/waves/README.md, "What waves cost a run".
"""

import argparse
import json
import tempfile
import time

import numpy as np

from cablefem.geometry import Horizontal
from cablefem.model.line import Line, LineType, Segment
from cablefem.model.scene import Environment, Motion, Output, Scene, Solver
from cablefem.runs.run import run_scene
from cablefem.waves import Sea
from cablefem.waves.spectra import irregular

CHAIN = LineType("chain", diameter=0.15, mass=130.0, EA=1.2e9, damping=0.01, Cd_normal=1.2,
                 Cd_tangential=0.4, Ca_normal=1.0, Ca_tangential=0.5)
DEPTH = 100.0
CASES = {"still water": None,
         "regular (1 component)": lambda: Sea.regular(3.0, 10.0, 0.0, 0.0, DEPTH),
         "irregular, 50 components": lambda: irregular(6.0, 11.0, DEPTH, components=50, seed=1),
         "irregular, 200 components": lambda: irregular(6.0, 11.0, DEPTH, components=200, seed=1)}


def scene(sea, elements, duration, dt, every=10.0):
    line = Line("chain", [-480.0, 0.0, -DEPTH], [0.0, 0.0, -15.0], (Segment(CHAIN, 550.0, elements),), 1)
    return Scene("cost", [line], Horizontal(DEPTH), environment=Environment(waves=sea),
                 motion=Motion("harmonic", amplitude=(2.0, 0.0, 0.0), period=10.0, ramp=10.0),
                 solver=Solver(integrator="generalized-alpha", dt=dt, duration=duration),
                 output=Output(every=every))


def time_case(sea, elements, duration, dt, every=10.0):
    """(CPU seconds, steps, Newton iterations) of one run."""
    with tempfile.TemporaryDirectory(prefix="cablefem-waves-cost-") as out:
        start = time.process_time()
        summary = run_scene(scene(sea, elements, duration, dt, every), out, progress=False)
        return time.process_time() - start, summary["steps"], summary["newton_iterations"]


def run(duration=300.0, rounds=5, elements=40, dt=0.05, every=10.0):
    seas = {name: make() if make else None for name, make in CASES.items()}
    for sea in seas.values():  # compile (or load) the kernels, build the seas' arrays
        time_case(sea, 10, 1.0, dt)
    times = {name: [] for name in seas}
    counts = {}
    for _ in range(rounds):
        for name, sea in seas.items():
            cpu, steps, iterations = time_case(sea, elements, duration, dt, every)
            times[name].append(cpu)
            counts[name] = (steps, iterations)
    still = np.array(times["still water"])
    return [{"case": name, "cpu_s_median": float(np.median(values)),
             "ratio_median": float(np.median(np.array(values) / still)),
             "ratio_range": [float(np.min(np.array(values) / still)), float(np.max(np.array(values) / still))],
             "steps": counts[name][0], "newton_iterations": counts[name][1]} for name, values in times.items()]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=300.0)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--elements", type=int, default=40)
    parser.add_argument("--every", type=float, default=10.0, help="s between frames")
    parser.add_argument("--json")
    args = parser.parse_args(argv)
    rows = run(args.duration, args.rounds, args.elements, every=args.every)
    print(f"{'case':28s} {'CPU [s]':>8s} {'ratio':>6s} {'range':>13s} {'steps':>6s} {'Newton':>7s}")
    for r in rows:
        print(f"{r['case']:28s} {r['cpu_s_median']:8.2f} {r['ratio_median']:6.2f} "
              f"{r['ratio_range'][0]:6.2f}-{r['ratio_range'][1]:5.2f} {r['steps']:6d} {r['newton_iterations']:7d}")
    if args.json:
        with open(args.json, "w") as handle:
            json.dump(rows, handle, indent=1)


if __name__ == "__main__":
    main()
