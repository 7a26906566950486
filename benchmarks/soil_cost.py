"""What the soil costs a dynamic run (issue 17): the same line, mesh, motion and time step with and
without ``[soil]``, side by side in one process.

The line is rui2025's Case 3 (``validation.rui2025.run``: 850 m of chain, padeye on the mudline,
218 P1 elements), its fairlead surging harmonically (``AMPLITUDE`` m every ``PERIOD`` s). Without
soil the seabed is the contact spring, frictionless (the conventional model) or with isotropic friction
(mu 0.3: the model that also resists the lying chain's sliding); with soil the macro-element of
``cablefem.loads.soil`` replaces both. The ratio is to the frictionless contact. Each run goes through ``cablefem.runs.run.run_scene`` as
``cablefem run`` does (frames every 10 s), once to compile (or load) the kernels, then
``--repeats`` times, alternating, the fastest kept. The static start is timed apart (the soil's is
the pretension path, ``cablefem.statics.pretension``) and taken off: the table's "march" is the time
stepping alone.

    python -m benchmarks.soil_cost [--duration T] [--repeats N] [--json FILE]

Timings are of this machine and its load at the time; the ratio between the rows of one run is what
to read. The last measurement is in validation/rui2025/README.md ("Cost").
"""

import argparse
import json
import tempfile
import time
from dataclasses import replace

from cablefem.runs.run import run_scene
from cablefem.statics.scene import start_states
from cablefem.model.scene import Friction, Motion, Output

from validation.rui2025 import run as study

AMPLITUDE, PERIOD, DT = 6.0, 30.0, 0.1  # [m], [s], [s]


#: the models: name -> (with [soil], the [friction] model without it)
MODELS = {"contact": (False, "none"), "contact + friction": (False, "isotropic"), "soil": (True, None)}


def scene(model, duration):
    """Case 3's line as ``model`` (``MODELS``), surging for ``duration`` [s]."""
    soil, friction = MODELS[model]
    base = study.scene("case3", study.SOIL if soil else None)
    extra = {} if soil else {"friction": Friction(model=friction, mu=0.3)}
    return replace(base, name=model.replace(" + ", "-"),
                   motion=Motion(kind="harmonic", amplitude=(-AMPLITUDE, 0.0, 0.0), period=PERIOD, ramp=PERIOD),
                   solver=replace(base.solver, dt=DT, duration=duration), output=Output(every=10.0), **extra)


def time_run(model, duration):
    """(wall seconds of run_scene, of its static start, its summary)."""
    built = scene(model, duration)
    start = time.perf_counter()
    start_states(built)
    static = time.perf_counter() - start
    with tempfile.TemporaryDirectory(prefix="cablefem-soil-cost-") as out:
        start = time.perf_counter()
        summary = run_scene(built, out, progress=False)
        wall = time.perf_counter() - start
    return wall, static, summary


def run(duration=120.0, repeats=3):
    """Rows of the table: per model the fastest of ``repeats`` runs."""
    for name in MODELS:
        time_run(name, 2 * DT)  # compile or load the kernels
    best = {}
    for _ in range(repeats):
        for name in MODELS:
            wall, static, summary = time_run(name, duration)
            if name not in best or wall - static < best[name]["march_s"]:
                best[name] = {"model": name, "wall_s": wall, "static_s": static, "march_s": wall - static,
                              "steps": summary["steps"], "newton_iterations": summary["newton_iterations"],
                              "status": summary["status"]}
    rows = list(best.values())
    for row in rows:
        row["march_ratio"] = row["march_s"] / rows[0]["march_s"]
        row["per_step_ms"] = 1e3 * row["march_s"] / max(row["steps"], 1)
    return rows


def table(rows, duration):
    """The rows as text."""
    lines = [f"Case 3's line (218 P1 elements), surge {AMPLITUDE:g} m / {PERIOD:g} s, dt {DT:g} s, {duration:g} s:",
             f"{'model':<20}{'march [s]':>10}{'ratio':>7}{'ms/step':>9}{'Newton/step':>12}{'static [s]':>11}  status"]
    for r in rows:
        lines.append(f"{r['model']:<20}{r['march_s']:10.2f}{r['march_ratio']:7.3f}{r['per_step_ms']:9.3f}"
                     f"{r['newton_iterations'] / max(r['steps'], 1):12.2f}{r['static_s']:11.2f}  {r['status']}")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=120.0, help="simulated seconds per run")
    parser.add_argument("--repeats", type=int, default=3, help="runs of each model, the fastest kept")
    parser.add_argument("--json", help="write the rows to this JSON file")
    args = parser.parse_args(argv)
    rows = run(args.duration, args.repeats)
    print(table(rows, args.duration))
    if args.json:
        with open(args.json, "w") as handle:
            json.dump(rows, handle, indent=1)


if __name__ == "__main__":
    main()
