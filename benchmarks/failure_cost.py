"""What a line failure costs a run (issue 36): the flume chain of examples/flume_failure.toml, side by side
in one process: intact; its anchor letting go at 20 s; a tension watched that is never reached; and a
tension that is reached. With a tension to watch, each output interval's fixed steps are marched in
one compiled call from a snapshot of the groups; where a step before the last is over the threshold,
the groups go back to the snapshot and march one step per call to it (``cablefem.runs.run``,
``_march_to_tension``), so that the end lets go after the first step over its threshold.

Each run goes through ``cablefem.runs.run.run_scene`` as ``cablefem run`` does, once to compile (or
load) the kernels, then ``--repeats`` times, alternating, the fastest kept; the table gives its
``wall_time_s``, the ratio to the intact run and when the end let go.

    python -m benchmarks.failure_cost [--duration T] [--repeats N]

Last measurement (30 s of the flume chain's snap motion, dt 0.01 s, frames every 0.5 s, 5 repeats, the
shared 2-core machine under load, where times of one run vary by ~5 %): intact 0.912 s; letting go at
20 s 1.05x; a tension watched 0.99x; letting go above 0.8 MN (at 2.61 s) 0.98x. Before the snapshot,
marching every step in its own call while a tension was watched cost 2.48x.
"""

import argparse
import os
import tempfile
from dataclasses import replace

from cablefem.io import load_scene
from cablefem.model.failure import Failure
from cablefem.runs.run import run_scene

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples", "flume_failure.toml")


def scenes(duration):
    """name -> the example's scene: intact, its anchor letting go at 20 s, a tension of 1e9 N watched."""
    example = load_scene(EXAMPLE)
    example = replace(example, solver=replace(example.solver, duration=duration))
    (timed,) = example.failures
    return {"intact": replace(example, failures=()),
            "lets go at 20 s": example,
            "tension watched": replace(example, failures=(replace(timed, time=None, tension=1e9),)),
            "lets go at 0.8 MN": replace(example, failures=(replace(timed, time=None, tension=8e5),))}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=30.0, help="simulated time [s]")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    runs = scenes(args.duration)
    best, released = {name: float("inf") for name in runs}, {}
    with tempfile.TemporaryDirectory(prefix="failure-cost-") as folder:
        run_scene(runs["intact"], folder, progress=False)  # compile or load the kernels
        for _ in range(args.repeats):
            for name, scene in runs.items():
                summary = run_scene(scene, folder, progress=False)
                best[name] = min(best[name], summary["wall_time_s"])
                released[name] = (summary.get("failures") or [{}])[0].get("released_at")
    print(f"{'run':18s} {'wall s':>8s} {'ratio':>6s} {'let go at s':>12s}")
    for name, wall in best.items():
        at = "" if released[name] is None else f"{released[name]:.2f}"
        print(f"{name:18s} {wall:8.3f} {wall / best['intact']:6.2f} {at:>12s}")
    return best


if __name__ == "__main__":
    main()
