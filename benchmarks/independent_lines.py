"""What a system of lines that share no unknowns costs against its lines alone (issue 33,
deliverable 2: a system of N lines costs <= 1.2x the sum of its lines alone).

``cablefem run`` steps each string that shares no unknowns with another as a group of its own
(``cablefem.runs.run._groups``): between two output times, each group's steps are one compiled call
(``Group.march``), so the Python work per string is one call per output interval, not per step.
This script runs a scene as ``cablefem run`` does (``run_scene``) and, in turn, each of its lines
alone (the scene with that line and the points it names), and prints CPU seconds of the whole run
and of its steps (inside ``_march``, as benchmarks/systems.py times them), medians of ``--repeats``
rounds, the runs alternated in one process (compiled before timing).

    python -m benchmarks.independent_lines [--scene examples/oc4_semi.toml] [--duration 50] [--repeats 3]

The ratio printed is the system's time over the sum of its lines' times: steps alone, and the
whole run (statics, set-up, outputs). docs/architecture.md ("What holds the layout") holds the last
measurement and its target.
"""

import argparse
import statistics
import sys
from dataclasses import replace
from pathlib import Path

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.systems import run_cablefem  # noqa: E402
from cablefem.io import load_scene  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def alone(scene, line):
    """The scene with ``line`` only, and the points it names."""
    points = {name: point for name, point in scene.points.items() if name in line.ends}
    return replace(scene, lines=[line], points=points)


def measure(scene, duration, repeats):
    """{label: (median run CPU s, median steps CPU s)} of the system and of each line alone."""
    runs = {"system": scene} | {line.name: alone(scene, line) for line in scene.lines}
    for each in runs.values():  # compile and load the kernels before timing
        run_cablefem(each, duration=min(duration, 1.0))
    samples = {label: [] for label in runs}
    for _ in range(repeats):
        for label, each in runs.items():
            result = run_cablefem(each, duration=duration)
            samples[label].append((result["run_s"], result["steps_s"]))
    return {label: (statistics.median(s[0] for s in rows), statistics.median(s[1] for s in rows))
            for label, rows in samples.items()}


def table(scene, result, duration):
    rows = [f"{scene.name}, {duration:g} s simulated, CPU s     run     steps",
            *(f"  {label:<34}{run:8.3f}{steps:9.3f}" for label, (run, steps) in result.items())]
    lines = [label for label in result if label != "system"]
    total_run = sum(result[label][0] for label in lines)
    total_steps = sum(result[label][1] for label in lines)
    rows.append(f"  {'sum of the lines alone':<34}{total_run:8.3f}{total_steps:9.3f}")
    rows.append(f"  {'system / sum':<34}{result['system'][0] / total_run:8.2f}"
                f"{result['system'][1] / total_steps:9.2f}")
    return "\n".join(rows)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default=str(ROOT / "examples" / "oc4_semi.toml"))
    parser.add_argument("--duration", type=float, default=50.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    scene = load_scene(args.scene)
    print(table(scene, measure(scene, args.duration, args.repeats), args.duration))


if __name__ == "__main__":
    main()
