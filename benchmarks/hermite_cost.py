"""What a Hermite line costs against a Lagrange P2 line of as many unknowns (issue 34's cost item).

The desire2023 flume chain in its dynamic motion (``cablefem.model.builtin.flume_scene``, flat seabed,
frictionless) on n P2 elements (2n + 1 rows of unknowns) and on n Hermite elements (2n + 2 rows:
positions and tangents), without bending (EI = 0: the element alone) and with EI = 1e5 N m² (the
bending load too; the chain's shape and the step count change a little). Each run is the compiled
march of the integrator from the static start (``cablefem.study.start_line``), no files written;
CPU time per step and per Newton iteration, each divided by the unknowns (3 per row). The three
settings alternate in one process, ``--repeats`` rounds, medians reported: ratios measured side by
side.

    python -m benchmarks.hermite_cost [--elements 40] [--duration 12] [--dt 0.01] [--repeats 3]

Last measured (``--duration 60 --repeats 5``, 40 elements, on the shared 2-core VM; medians of 5):

    setting                    unknowns  CPU [s]  steps  Newton us/step/unk  vs P2 us/iter/unk  vs P2
    P2                              237    0.803   6193   16338      0.5470   1.00      0.2074   1.00
    Hermite, EI = 0                 240    0.981   6057   14852      0.6748   1.23      0.2752   1.33
    Hermite, EI = 1e5 N m^2         240    1.414   6005   14249      0.9813   1.79      0.4135   1.99

A Hermite element has 4 rows to P2's 3, 4 full points to 3 and Simpson's 3 reduced points to 2,
and a wider band (a vertex is two rows); the bending load adds r'' and the moment's four blocks
at every full point. The default 12 s run gave 1.46x and 2.15x per step and unknown: the ratios
spread by ~0.2 between runs on this machine.
"""

import argparse
import time
from dataclasses import replace

import numpy as np

from cablefem.model.builtin import flume_scene
from cablefem.study import start_line

SETTINGS = (("P2", None), ("Hermite, EI = 0", 0.0), ("Hermite, EI = 1e5 N m^2", 1e5))


def scene_of(elements, dt, duration, EI):
    """The flume scene on n P2 elements (``EI`` None) or n Hermite elements with that EI."""
    scene = flume_scene("flat", "dynamic", elements=elements, order=2, duration=duration, dt=dt)
    if EI is None:
        return scene
    line = replace(scene.lines[0], element="hermite").with_types(lambda t: replace(t, EI=EI))
    return replace(scene, lines=[line])


def time_setting(elements, dt, duration, EI):
    """One run: CPU seconds of the march, steps, Newton iterations, residual evaluations, unknowns."""
    scene = scene_of(elements, dt, duration, EI)
    integ = start_line(scene)
    times = dt * np.arange(1, int(round(duration / dt)) + 1)
    begin = time.process_time()
    integ.march(times)
    cpu = time.process_time() - begin
    return {"cpu_s": cpu, "steps": integ.steps, "newton_iterations": integ.newton_iterations, "nfev": integ.nfev,
            "unknowns": 3 * len(integ.fem.free_dofs)}


def run(elements=40, duration=12.0, dt=0.01, repeats=3):
    for _, EI in SETTINGS:  # compile (or load) every kernel first
        time_setting(4, dt, 5 * dt, EI)
    rounds = {name: [] for name, _ in SETTINGS}
    for _ in range(repeats):
        for name, EI in SETTINGS:
            rounds[name].append(time_setting(elements, dt, duration, EI))
    rows = []
    for name, runs in rounds.items():
        cpu = float(np.median([r["cpu_s"] for r in runs]))
        first = runs[0]
        rows.append({"setting": name, "elements": elements, "unknowns": first["unknowns"], "cpu_s": cpu,
                     "steps": first["steps"], "newton_iterations": first["newton_iterations"], "nfev": first["nfev"],
                     "us_per_step_unknown": 1e6 * cpu / first["steps"] / first["unknowns"],
                     "us_per_iteration_unknown": 1e6 * cpu / first["newton_iterations"] / first["unknowns"]})
    base = rows[0]
    for row in rows:
        row["per_step_unknown_vs_p2"] = row["us_per_step_unknown"] / base["us_per_step_unknown"]
        row["per_iteration_unknown_vs_p2"] = row["us_per_iteration_unknown"] / base["us_per_iteration_unknown"]
    return rows


def table(rows):
    lines = [f"{'setting':26s} {'unknowns':>8s} {'CPU [s]':>8s} {'steps':>6s} {'Newton':>7s} "
             f"{'us/step/unk':>11s} {'vs P2':>6s} {'us/iter/unk':>11s} {'vs P2':>6s}"]
    for r in rows:
        lines.append(f"{r['setting']:26s} {r['unknowns']:8d} {r['cpu_s']:8.3f} {r['steps']:6d} "
                     f"{r['newton_iterations']:7d} {r['us_per_step_unknown']:11.4f} {r['per_step_unknown_vs_p2']:6.2f} "
                     f"{r['us_per_iteration_unknown']:11.4f} {r['per_iteration_unknown_vs_p2']:6.2f}")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--elements", type=int, default=40)
    parser.add_argument("--duration", type=float, default=12.0, help="simulated seconds per run")
    parser.add_argument("--dt", type=float, default=0.01)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    print(table(run(args.elements, args.duration, args.dt, args.repeats)))


if __name__ == "__main__":
    main()
