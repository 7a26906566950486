"""The lazy-wave power cable of validation/cables as a system of ``benchmarks.systems``: its rows and
references (``python -m benchmarks.systems --systems lazy-wave``).

The cable (validation/cables/README.md): 260 m, EI = 2e4 N m², a buoyancy section, touchdown on the
seabed, its top clamped vertical on a hang-off moving 6 m in surge and 2 m in heave at 12 s, ramped
in over 10 s, 34 s in all; the error window is the last two periods, t >= 10 s. The compared value is
the hang-off tension |F|, the force the cable exerts on the hang-off (shear included).

Rows, as the other systems' (``benchmarks.systems``):

- ``MoorDyn-C, the file``: MoorDyn-C on validation/cables' file at its coarse mesh, segments of ~5 m
  (52 in all), dtM 1e-4 s, its static shape by dynamic relaxation (``ICgenDynamic 1``) started from
  cablefem's static shape, coupled every 0.002 s (``validation.cables.moordyn_side``: at 0.01 s the
  coupled Rod's velocity jumps make the clamped cable ring). CPU seconds of its ``Create``, ``Init``
  and ``Step`` calls, and of ``Step``.
- ``cablefem, defaults``: the same file read by cablefem's MoorDyn reader (its lines on Hermite
  elements at NumSegs, the cable welded through its joints, ``case.cablefem_scene``), its steps
  chosen by ``cablefem.model.defaults.step`` and its frames by ``defaults.frames`` as a scene
  that gives the motion and no [solver] dt gets them, run by ``run_scene``.
- ``cablefem, best``: Hermite elements of ~10 m (26 in all) at the defaults' steps, the cheapest
  tried (13, 26 and 52 elements; BDF2 at dt 0.3, 0.15, 0.05, 0.025 and 0.01 s) whose error is no
  larger than MoorDyn-C's.

References: validation/cables' finest runs, read from its results.json (``python -m
validation.cables.run`` recomputes them, ~21 min): MoorDyn-C at 416 segments (dtM 5e-5 s) and
cablefem at 208 Hermite elements (BDF2, dt 0.01 s), sampled every 0.05 s.
"""

import json
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "validation" / "cables" / "results.json"
DURATION = 34.0
PERIOD, WINDOW_PERIODS = 12.0, 2
#: (section length [m] of MoorDyn-C's file, of cablefem's best row)
MOORDYN_LENGTH, BEST_LENGTH = 5.0, 10.0


def scene(length, folder):
    """cablefem's scene of the cable at segments of ~``length`` [m] as a user gets it: the
    defaults' steps and frames for its motion, and the run's duration."""
    from cablefem.model import defaults
    from validation.cables import case

    scene = case.cablefem_scene(case.segments_for(length), folder)
    solver, _ = defaults.step(scene.solver, set(), scene.motion)
    output, _ = defaults.frames(scene.output, set(), solver, scene.motion)
    return replace(scene, solver=replace(solver, duration=DURATION), output=output)


def references():
    """{"moordyn": ..., "cablefem": ...}: each finest run's settings, t (m,) and tension (m, 1)."""
    lazy = json.loads(RESULTS.read_text())["lazy_wave"]
    out = {}
    for code, unit in (("moordyn", "segments"), ("cablefem", "elements")):
        finest = lazy[code][-1]
        series = finest["series"]
        out[code] = {"settings": {unit: finest[unit]}, "t": np.asarray(series["t"]),
                     "tension": np.asarray(series["tension"])[:, None]}
    return out


def run_moordyn(duration=DURATION):
    """MoorDyn-C's row: t (n,), tension (n, 1), CPU s of Create + Init + Step and of Step."""
    import moordyn

    from benchmarks.systems import clocked
    from cablefem.model.motion import FairleadPath
    from validation.cables import case, comparison, moordyn_side

    with tempfile.TemporaryDirectory(prefix="cablefem-systems-") as folder:
        start = comparison.static_start(case.segments_for(1.0), folder)
        path = FairleadPath(scene(MOORDYN_LENGTH, folder).motion, np.array(case.HANG_OFF))
        with clocked(moordyn, ["Create", "Init", "Step"]) as spent:
            out = moordyn_side.run(case.segments_for(MOORDYN_LENGTH), comparison.moordyn_dt(MOORDYN_LENGTH), start,
                                   duration, comparison.COUPLING, lambda t: path(t)[0],
                                   every=int(round(comparison.OUTPUT / comparison.COUPLING)))
    return {"t": out["times"], "tension": np.linalg.norm(out["run_force"], axis=1)[:, None],
            "run_s": sum(spent.values()), "steps_s": spent["Step"]}


def run_cablefem(length, duration=DURATION):
    """cablefem's row at segments of ~``length`` [m] (``benchmarks.systems.run_cablefem``)."""
    from benchmarks.systems import run_cablefem as run

    with tempfile.TemporaryDirectory(prefix="cablefem-systems-") as folder:
        return run(scene(length, folder), duration=duration)


def rows():
    """(label, runner, its own reference) of the rows: MoorDyn-C on the file, cablefem at its defaults and
    at its best."""
    with tempfile.TemporaryDirectory() as folder:
        made, best = scene(MOORDYN_LENGTH, folder), scene(BEST_LENGTH, folder)
    count = sum(s.elements for s in made.lines[0].segments)
    best_count = sum(s.elements for s in best.lines[0].segments)
    return [(f"MoorDyn-C, the file ({count} segments, dtM 1e-4)", run_moordyn, "moordyn"),
            (f"cablefem, defaults (Hermite x {count}, dt {made.solver.dt:g})", lambda: run_cablefem(MOORDYN_LENGTH),
             "cablefem"),
            (f"cablefem, best (Hermite x {best_count}, dt {best.solver.dt:g})", lambda: run_cablefem(BEST_LENGTH),
             "cablefem")]


def frames():
    """The frame interval [s] of the defaults' rows."""
    with tempfile.TemporaryDirectory() as folder:
        return scene(MOORDYN_LENGTH, folder).output.every


def warm():
    """numba's kernels and MoorDyn's library loaded before the rows are timed."""
    begin = time.process_time()
    run_cablefem(MOORDYN_LENGTH, duration=0.6)
    return time.process_time() - begin
