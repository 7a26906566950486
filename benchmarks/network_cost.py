"""What a junction costs a run (issue 18): a crowfoot, one line from a moving platform to a free
point carrying a clump, two legs from there to anchors (the junction joins three line ends), run
with ``cablefem.dynamics.group.Group`` as ``cablefem run`` does (compiled:
``cablefem.compiled.steps``), against each of its lines alone (its junction end fixed where the
statics put it, the compiled march of one line with the same integrator) and, with ``--python``, against the Python loop
of the same steps. Wall time per simulated second, the runs alternated and repeated in one
process, medians; prints a table.

    python benchmarks/network_cost.py [--repeats 3] [--duration 20] [--python]
        [--integrator generalized-alpha] [--adaptive]

The last measurement and the target it is held to are in docs/architecture.md ("What holds the
layout").
"""

import argparse
import statistics
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from cablefem.dynamics.registry import INTEGRATORS
from cablefem.errors import ConvergenceError
from cablefem.io import load_scene
from cablefem.model.network import Point, dynamic_lines
from cablefem.model.network import anchor_path, boundary_path
from cablefem.fem.system import build_system
from cablefem.dynamics.group import junction_groups
from cablefem.statics.scene import start_states
from cablefem.dynamics.registry import integrator_options

SCENE = Path(__file__).with_name("crowfoot.toml")


def network_run(scene, duration, compiled=True):
    """Wall time [s] of ``duration`` simulated seconds of the whole network (its junction steps
    ``compiled`` or in the Python loop), its Newton iterations and its start states."""
    systems = [build_system(scene, line) for line in dynamic_lines(scene)]
    states, _ = start_states(scene, systems=systems)
    options = integrator_options(scene.solver)
    integrators = [INTEGRATORS[scene.solver.integrator](s, X, boundary_path(scene, line), dt=scene.solver.dt,
                                       anchor=anchor_path(scene, line), **options)
                   for s, line, X in zip(systems, scene.lines, states)]
    group = junction_groups(scene, integrators)[0]
    if not compiled:
        group.packer = None  # the policy on the Python ops
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
    integ = INTEGRATORS[scene.solver.integrator](system, X, boundary_path(lone, lone.lines[0]), dt=scene.solver.dt,
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
    parser.add_argument("--integrator", default="bdf2", choices=sorted(INTEGRATORS))
    parser.add_argument("--adaptive", action="store_true", help="error-controlled steps, network and lines alike")
    args = parser.parse_args()
    scene = load_scene(SCENE)
    scene = replace(scene, solver=replace(scene.solver, integrator=args.integrator, adaptive=args.adaptive))
    network_run(scene, 1.0)  # compile and warm
    networks = {"network": True, **({"python loop": False} if args.python else {})}
    rows = {**{name: [] for name in networks}, **{line.name: [] for line in scene.lines}}
    iterations, failed = {}, {}
    for _ in range(args.repeats):
        for name, compiled in networks.items():
            wall, iterations[name], states = network_run(scene, args.duration, compiled)
            rows[name].append(wall / args.duration)
        for k, line in enumerate(scene.lines):
            try:
                wall, iterations[line.name] = alone_run(scene, k, states[k], args.duration)
            except ConvergenceError as error:  # a line alone, both ends held, may snap where the network does not
                failed[line.name] = str(error)
                continue
            rows[line.name].append(wall / args.duration)
    for name, reason in failed.items():
        print(f"{name} alone failed: {reason}")
        del rows[name]
    median = {name: statistics.median(values) for name, values in rows.items()}
    alone = [median[line.name] for line in scene.lines if line.name in median]
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
