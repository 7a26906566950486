"""What a junction costs a run (issue 18): a crowfoot, one line from a moving platform to a free
point carrying a clump, two legs from there to anchors (the junction joins three line ends), run
with ``cablefem.dynamics.junctions.JunctionSteps`` as ``cablefem run`` does (compiled:
``cablefem.compiled.junctions``), against each of its lines alone (its junction end fixed where the
statics put it, the compiled BDF2 march of one line) and, with ``--python``, against the Python loop
of the same steps. Wall time per simulated second, the runs alternated and repeated in one
process, medians; prints a table.

    python benchmarks/network_cost.py [--repeats 3] [--duration 20] [--python]

Last measured (a 20-element chain from a surging platform to the junction, two 30-element legs,
dt 0.05 s; medians of 5, three runs on the shared 2-core machine, absolute times varying 2x with
its load, the ratios less): the network costs 0.014-0.028 s per simulated second, 0.72-0.91x its
three lines alone summed, 0.86-1.11x the costliest of them and 9.7-13.7x a leg alone (three
strings at 3.2 Newton iterations a step, where a leg held at its junction end takes one); the
Python loop of the same steps 4-6x the compiled one. The target, a 3-line network at most 3.5x one of its lines
alone, holds against the costliest line, not against the cheapest.
"""

import argparse
import statistics
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from cablefem.dynamics.registry import INTEGRATORS
from cablefem.io import load_scene
from cablefem.model.network import Point, dynamic_lines
from cablefem.model.network import anchor_path, boundary_path
from cablefem.fem.system import build_system
from cablefem.runs.run import junction_steps
from cablefem.statics.scene import start_states
from cablefem.dynamics.schemes import integrator_options

SCENE = Path(__file__).with_name("crowfoot.toml")


def network_run(scene, duration, compiled=True):
    """Wall time [s] of ``duration`` simulated seconds of the whole network (its junction steps
    ``compiled`` or in the Python loop), its Newton iterations and its start states."""
    systems = [build_system(scene, line) for line in dynamic_lines(scene)]
    states, _ = start_states(scene, systems=systems)
    options = integrator_options(scene.solver)
    integrators = [INTEGRATORS["bdf2"](s, X, boundary_path(scene, line), dt=scene.solver.dt,
                                       anchor=anchor_path(scene, line), **options)
                   for s, line, X in zip(systems, scene.lines, states)]
    junction_steps(scene, integrators).compiled = compiled
    times = np.arange(1, int(round(duration / scene.solver.dt)) + 1) * scene.solver.dt
    start = time.perf_counter()
    for integ in integrators:
        integ.march(times)
    wall = time.perf_counter() - start
    return wall, sum(int(integ.counters[1]) for integ in integrators), states


def alone_run(scene, k, X0, duration):
    """Wall time [s] of line k alone: the junction made a fixed point where the statics put it
    (the compiled march of one line)."""
    line = scene.lines[k]
    points = {}
    for name, row in zip(line.ends, (0, -1)):
        point = scene.points[name]
        points[name] = point if point.kind != "free" else Point(name, "fixed", X0[row])
    vertices = X0[:len(line.node_arc_lengths())]
    lone = replace(scene, lines=(replace(line, prescribed=(True, True)).with_ends(vertices[0], vertices[-1]),),
                   points=points)
    system = build_system(lone, lone.lines[0])
    (X,), _ = start_states(lone, systems=[system])
    integ = INTEGRATORS["bdf2"](system, X, boundary_path(lone, lone.lines[0]), dt=scene.solver.dt,
                                anchor=anchor_path(lone, lone.lines[0]), **integrator_options(scene.solver))
    times = np.arange(1, int(round(duration / scene.solver.dt)) + 1) * scene.solver.dt
    start = time.perf_counter()
    integ.march(times)
    return time.perf_counter() - start, int(integ.counters[1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--duration", type=float, default=20.0)
    parser.add_argument("--python", action="store_true", help="also the junction steps' Python loop")
    args = parser.parse_args()
    scene = load_scene(SCENE)
    network_run(scene, 1.0)  # compile and warm
    networks = {"network": True, **({"python loop": False} if args.python else {})}
    rows = {**{name: [] for name in networks}, **{line.name: [] for line in scene.lines}}
    iterations = {}
    for _ in range(args.repeats):
        for name, compiled in networks.items():
            wall, iterations[name], states = network_run(scene, args.duration, compiled)
            rows[name].append(wall / args.duration)
        for k, line in enumerate(scene.lines):
            wall, iterations[line.name] = alone_run(scene, k, states[k], args.duration)
            rows[line.name].append(wall / args.duration)
    median = {name: statistics.median(values) for name, values in rows.items()}
    alone = [median[line.name] for line in scene.lines]
    steps = args.duration / scene.solver.dt
    print(f"{'run':<12} {'wall per simulated s':>21} {'Newton its per step':>20} {'us per string-iteration':>24}")
    for name, value in median.items():
        strings = len(scene.lines) if name in networks else 1
        per = 1e6 * value * args.duration / max(iterations[name], 1)
        print(f"{name:<12} {value:21.4f} {iterations[name] / steps / strings:20.2f} {per:24.1f}")
    for name in networks:
        print(f"{name}: / its costliest line alone {median[name] / max(alone):.2f}, / its lines alone summed "
              f"{median[name] / sum(alone):.2f}, / its cheapest line alone {median[name] / min(alone):.2f}")


if __name__ == "__main__":
    main()
