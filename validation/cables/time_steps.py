"""The lazy wave's hang-off tension against the time step, BDF2 and generalised-alpha, against
MoorDyn-C's finest run (validation/cables/README.md, "Time steps").

    python -m validation.cables.time_steps [--elements-length 5.0] [--results validation/cables/results.json]

Prints the RMS error of the hang-off tension |F| over t >= 10 s (after the ramp) relative to its
mean, against MoorDyn-C's 416 segments stored in results.json, for each integrator and step; for
generalised-alpha also the force of its loads at the state X_{n+1} (``at state``), the end force it
reported before it read its balance (``cablefem.dynamics.generalized_alpha.GeneralizedAlpha``).
"""

import argparse
import json
import tempfile
from pathlib import Path

import numpy as np

from cablefem.dynamics.bdf2 import BDF2
from cablefem.dynamics.generalized_alpha import GeneralizedAlpha
from cablefem.fem.system import build_system
from cablefem.model.network import boundary_path
from cablefem.statics.solve import solve_static
from validation.cables import case

HERE = Path(__file__).resolve().parent
STEPS = (0.3, 0.15, 0.05, 0.025, 0.01)  # s; each divides the output interval
OUTPUT = 0.3  # s between the compared forces (MoorDyn-C's series interpolated there)
DURATION, AFTER = 34.0, 10.0  # s: the run, and where the comparison starts (the ramp's end)


def tensions(scene, cls, dt):
    """|F| (m,) at every ``OUTPUT`` after ``AFTER``, as the integrator reports it, and (m,) from its
    loads at the state X_{n+1} (the reactions evaluated again there)."""
    line = scene.lines[0]
    static = build_system(scene, line, dynamic=False)
    X0 = solve_static(static).X
    integ = cls(build_system(scene, line, dynamic=True, fem=static.fem), X0, boundary_path(scene, line), dt=dt)
    times = OUTPUT * np.arange(1, int(round(DURATION / OUTPUT)) + 1)
    reported, at_state = [], []
    for t in times:
        integ.march(np.linspace(integ.t, t, int(round((t - integ.t) / dt)) + 1)[1:])
        reported.append(np.linalg.norm(integ.reactions()[0]))
        integ.residual_rows = None  # the reactions then evaluate the loads at the state
        at_state.append(np.linalg.norm(integ.reactions()[0]))
    after = times >= AFTER - 1e-9
    return times[after], np.array(reported)[after], np.array(at_state)[after]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--elements-length", type=float, default=5.0, help="element length [m] (5: 52 elements)")
    parser.add_argument("--results", default=str(HERE / "results.json"), help="the study's results.json")
    args = parser.parse_args()
    series = json.loads(Path(args.results).read_text())["lazy_wave"]["moordyn"][-1]["series"]
    with tempfile.TemporaryDirectory() as folder:
        elements = case.segments_for(args.elements_length)
        scene = case.cablefem_scene(elements, folder)
        print(f"{sum(elements)} Hermite elements; RMS error of |F| over t >= {AFTER:g} s against MoorDyn-C's finest run")
        print(f"{'dt [s]':>7} {'BDF2':>8} {'gen-alpha':>10} {'at state':>10}")
        for dt in STEPS:
            row = []
            for cls in (BDF2, GeneralizedAlpha):
                times, reported, at_state = tensions(scene, cls, dt)
                reference = np.interp(times, series["t"], series["tension"])
                rms = [np.sqrt(np.mean((T - reference) ** 2)) / reference.mean() for T in (reported, at_state)]
                row += rms if cls is GeneralizedAlpha else rms[:1]
            print(f"{dt:7.3g} {100 * row[0]:7.2f}% {100 * row[1]:9.2f}% {100 * row[2]:9.1f}%", flush=True)


if __name__ == "__main__":
    main()
