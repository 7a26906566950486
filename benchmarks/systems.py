"""The systems users run, both codes side by side in one process (issue 33): time per simulated
second and the error of the fairlead tensions against fine references.

Systems (``SYSTEMS``):

- ``oc4-semi``: the OC4-DeepCwind semisubmersible's three chains (``examples/oc4_semi.dat``, 20
  segments each, dtM 1 ms) with the platform surging 5 m at a 10 s period for 100 s
  (``examples/oc4_semi.toml``).
- ``flume-snap``: the flume chain of desire2023 (635 m, 100 m of water, frictionless) as the
  MoorDyn file ``benchmarks/flume_snap_20.dat`` (20 segments, dtM 5 ms, no initial-condition
  solve) under verification/work_precision's snap motion, 5 m at 6 s, for 36 s
  (``benchmarks/flume_snap_defaults.toml``).
- ``semi-taut``: validation/networks' semi-taut system, three chain-polyester-chain lines with a
  clump and a buoy on each, the fairleads on a coupled platform moving in surge, heave, pitch and
  yaw at 14.9 s, for four periods (``validation/networks/inputs/semitaut.toml``; MoorDyn-C on the
  file written from the same description, its BODY driven through the coupling API:
  ``validation.networks.dynamics.run_moordyn``). The scene sets P1 elements at MoorDyn's segments
  and dt 0.005 s, so those are its "defaults" row; its "best" is the one setting tried, P2 at half
  the segments (rounded up) and dt 0.05 s.

- ``lazy-wave``: validation/cables' lazy-wave power cable (EI on Hermite elements, a buoyancy
  section, touchdown, its top clamped on a hang-off in surge and heave at 12 s, 34 s); its rows and
  references are ``benchmarks.systems_lazy_wave``'s (validation/cables' file and its finest runs).

Rows, each run as a user runs it, in this process:

- ``MoorDyn-C, the file``: PyPI ``moordyn`` on the file as it is (its segments, dtM and
  initial-condition solve), the coupled points following the scene's motion, coupled every 0.01 s
  (``validation.moordyn.runners.run_moordyn_case``).
- ``cablefem, defaults``: ``cablefem.runs.run.run_scene`` on the scene as it is (what ``cablefem
  run examples/oc4_semi.toml`` does, its outputs written to a temporary folder), with the defaults
  its physics chooses (docs/scene.md, "Defaults by physics": P2 x NumSegs / 2 up to NumSegs 20, fixed steps of 1/40
  and frames every 1/10 of the motion's period); the label names them.
- ``cablefem, best``: the same with the element order, element count, fixed step and Newton tolerance
  of ``SYSTEMS[...]["best"]`` (frames as at the defaults), picked with verification/work_precision's findings (P2 elements,
  few of them, large BDF2 steps, Newton tolerance 1e-4): the cheapest run tried whose error is
  no larger than MoorDyn-C's. OC4: P2 x 7 per line, dt 0.4 s, of P2 x 5, 7, 8, 10, 14 and P3 x 5
  at dt 0.05-0.4 s. Flume snap: P1 x 14, dt 0.17 s (work_precision's pick at MoorDyn's
  20-segment level, ``benchmarks/flume_snap.toml``), of that and P2 x 7-20, P3 x 7 at dt
  0.04-0.16 s, all of which are more accurate (7.4-13 %) and costlier.

Times are CPU seconds of this process (``time.process_time``) per simulated second, the median of
``--repeats`` rounds, each round running every row in turn (the machine is shared; contention
hits both codes alike). Two times per row: ``steps``, the time inside the stepping calls
(MoorDyn-C's ``Step``; cablefem's ``_march``, the compiled loops of every line), and ``run``, the
whole in-process run (MoorDyn-C's ``Create``, ``Init`` with its initial-condition solve, and
``Step``, the peer's Python bookkeeping between the calls left out in MoorDyn's favour;
cablefem's whole ``run_scene``: statics, set-up, steps, tensions.csv and the VTK frames). The
ratio is cablefem's run time over MoorDyn-C's. numba's kernels are compiled and loaded before
timing (a fresh process: ``benchmarks/startup.py``).

Error (``error``, as verification/work_precision defines it): the RMS over the last two periods
of the difference between a run's fairlead tension and the reference's (interpolated to the
run's times), relative to the reference's mean over that window; the largest over the lines.
MoorDyn-C's tension is the force on the coupled point with its lines' end-node inertia subtracted
(``forces_on_point``), the force cablefem's FEM reaction gives.

References, cached in ``systems.json`` next to this script (``--reference`` recomputes them,
~8 min for OC4, ~2 min for the flume), one per code:

- OC4: MoorDyn-C at 8x the file's segments (160 per line, dtM 1e-4 s, its initial-condition
  solve at 4e-4 s) and cablefem P2 x 80 per line at dt 0.005 s. They are 2.8 % RMS apart, all of
  it in line 2, which goes slack (105 kN) and snaps (2.58 MN in MoorDyn-C, 2.54 MN in cablefem)
  every period; lines 1 and 3 agree to 0.16 %. Each is nearer converged than that: from 80 to
  160 segments MoorDyn-C moves 1.36 %, from P2 x 40 at dt 0.01 s cablefem moves 0.62 %; the
  rest is the two models' physics in the snap (not aligned here as in validation/moordyn_aligned).
  That is more than the errors measured, so each code is measured against its own reference
  (``error``), as verification/work_precision does, and against the other's (``other``).
- Flume snap: MoorDyn-C at 32x the file's segments (640, dtM 1.25e-4 s) and cablefem P2 x 320 at
  dt 0.00125 s, 1.6 % apart (at 8x, 160 segments and P2 x 80, they were 10.6 % apart: MoorDyn-C
  moved 9.4 % and cablefem 6.8 % on doubling; from 320 to 640 segments MoorDyn-C moves 3.4 %,
  from P2 x 160 to 320 cablefem 3.1 %). The snap's tension bursts converge slowly; the errors
  measured (18-28 %) are well above that.

- Semi-taut: MoorDyn-C at 2x the file's segments (dtM 2.5e-4 s, its initial-condition solve at
  1e-3 s) and cablefem P2 at 2x them, dt 0.0025 s (validation/networks' reference settings); 0.41 %
  apart.

    python -m benchmarks.systems [--reference] [--repeats N] [--systems oc4-semi] [--json FILE]

Last measured on the shared 2-core machine (load ~6), CPU s per simulated second, medians of 3
rounds, all systems in one run; errors in % RMS against the code's own reference and against the
other's:

    oc4-semi (100 s)                              run     steps   error  other  run ratio  steps ratio
    MoorDyn-C, the file (20 segments, dtM 1e-3)   0.0152  0.0122   2.84   1.88   1.00       1.00
    cablefem, defaults (P2 x 10, dt 0.25)         0.0032  0.0019   1.99   4.06   0.21       0.15
    cablefem, best (P2 x 7, dt 0.4, tol 1e-4)     0.0025  0.0013   2.41   3.33   0.17       0.10

    semi-taut (59.6 s)                            run     steps   error  other  run ratio  steps ratio
    MoorDyn-C, the file (dtM 5e-4)                0.7588  0.0727   1.02   1.00   1.00       1.00
    cablefem, the scene (P1 x NumSegs, dt 0.005)  0.0777  0.0493   0.73   0.87   0.10       0.68
    cablefem, best (P2 x NumSegs / 2, dt 0.05)    0.0387  0.0192   0.68   1.01   0.05       0.26

    flume-snap (36 s)                             run     steps   error  other  run ratio  steps ratio
    MoorDyn-C, the file (20 segments, dtM 5e-3)   0.0018  0.0018  28.39  28.39   1.00       1.00
    cablefem, defaults (P2 x 10, dt 0.15)         0.0023  0.0008  11.89  11.76   1.29       0.46
    cablefem, best (P1 x 14, dt 0.17, tol 1e-4)   0.0020  0.0006  18.77  18.95   1.12       0.34

    lazy-wave (34 s; its own run, 3 rounds)       run     steps   error  other  run ratio  steps ratio
    MoorDyn-C, the file (52 segments, dtM 1e-4)   0.5726  0.1373   2.37   2.38   1.00       1.00
    cablefem, defaults (Hermite x 52, dt 0.25)    0.0240  0.0065   0.72   0.92   0.04       0.05
    cablefem, best (Hermite x 26, dt 0.25)        0.0114  0.0034   1.72   1.84   0.02       0.03

(the lazy wave's references 0.40 % apart). The lazy-wave file's run is mostly MoorDyn-C's dynamic
relaxation (76 % of its in-process time), though it starts from cablefem's static shape. The
semi-taut file's run is mostly MoorDyn-C's initial-condition solve (dynamic relaxation of the
clumps and buoys at dtM: 90 % of its in-process time).

Issue 33's target for OC4 at the defaults (error no larger than MoorDyn-C's in <= 0.25x its
in-process time) is met: 1.99 % against 2.84 % in 0.21x (the steps alone 0.15x). Beyond the steps,
0.13 s of the 0.32 s run is the statics, the set-up and the 100 frames (each ends a compiled
march). The best settings found, frames as at the defaults, take 0.17x. A fresh
``cablefem run examples/oc4_semi.toml`` took 1.91 and 1.75 s of CPU (user + system, two runs),
1.15-1.26x MoorDyn-C's in-process 1.52 s (the issue's target: <= 1.5x). The flume file is MoorDyn-C's
cheapest case (21 nodes, dtM 5 ms: 0.07 s for 36 s), where cablefem's statics and set-up alone
cost about that.
"""

import argparse
import contextlib
import importlib
import json
import math
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

ROOT = Path(__file__).resolve().parents[1]
CACHE = Path(__file__).resolve().with_name("systems.json")
COUPLING_DT = 0.01  # s between MoorDyn-C's coupling calls; the references are kept on this grid

#: per system: the scene, the MoorDyn file, the window's periods, the fine references, the best settings
SYSTEMS = {
    "oc4-semi": {
        "scene": ROOT / "examples" / "oc4_semi.toml",
        "moordyn": ROOT / "examples" / "oc4_semi.dat",
        "period": 10.0, "window_periods": 2,
        "moordyn_reference": {"segments": 8, "dtM": 1e-4, "ic_dtM": 4e-4},
        "cablefem_reference": {"order": 2, "elements": 80, "dt": 0.005},
        "best": {"order": 2, "elements": 7, "dt": 0.4, "tolerance": 1e-4},
        "target": True,  # issue 33: at defaults, error <= MoorDyn-C's in <= 0.25x its in-process time
    },
    "semi-taut": {
        "scene": ROOT / "validation" / "networks" / "inputs" / "semitaut.toml",
        "network": "semitaut", "peer": "bodies", "duration": 4 * 14.9,
        "period": 14.9, "window_periods": 2,
        "moordyn_reference": {"segments": 2, "dtM": 2.5e-4, "ic_dtM": 1e-3},
        "cablefem_reference": {"order": 2, "factor": 2, "dt": 0.0025},
        "best": {"order": 2, "factor": 0.5, "dt": 0.05, "tolerance": 1e-4},
    },
    "flume-snap": {
        "scene": ROOT / "benchmarks" / "flume_snap_defaults.toml",
        "moordyn": ROOT / "benchmarks" / "flume_snap_20.dat",
        "period": 6.0, "window_periods": 2,
        "moordyn_reference": {"segments": 32, "dtM": 1.25e-4},
        "cablefem_reference": {"order": 2, "elements": 320, "dt": 0.00125},
        "best": {"order": 1, "elements": 14, "dt": 0.17, "tolerance": 1e-4},
    },
    "lazy-wave": {"module": "benchmarks.systems_lazy_wave", "period": 12.0, "window_periods": 2},
}


def error(t, tension, t_ref, reference, t_from):
    """RMS over t >= t_from [s] of ``tension`` (n, lines) [N] at times t (n,) minus ``reference``
    (m, lines) at times t_ref (m,) interpolated to t, relative to the reference's mean over that
    window; the largest over the lines."""
    t, tension, reference = np.asarray(t), np.atleast_2d(np.asarray(tension).T).T, np.asarray(reference)
    reference = np.atleast_2d(reference.T).T
    window = t >= t_from - 1e-9
    worst = 0.0
    for k in range(tension.shape[1]):
        on_run = np.interp(t[window], t_ref, reference[:, k])
        worst = max(worst, float(np.sqrt(np.mean((tension[window, k] - on_run) ** 2)) / on_run.mean()))
    return worst


@contextlib.contextmanager
def clocked(module, names):
    """Inside the block, each function ``module.name`` adds the CPU seconds it spends to the yielded
    dict's item ``name``."""
    saved = {name: getattr(module, name) for name in names}
    spent = dict.fromkeys(names, 0.0)

    def timer(name, function):
        def timed(*args, **kwargs):
            begin = time.process_time()
            try:
                return function(*args, **kwargs)
            finally:
                spent[name] += time.process_time() - begin
        return timed

    for name, function in saved.items():
        setattr(module, name, timer(name, function))
    try:
        yield spent
    finally:
        for name, function in saved.items():
            setattr(module, name, function)


def scene_of(system, order=None, elements=None, dt=None, tolerance=None, factor=None):
    """The system's scene, every line's element order, element count (per segment; or each
    segment's count times ``factor``, rounded up), the step dt [s] and Newton's tolerance replaced
    where given."""
    from cablefem.io import load_scene
    from cablefem.model.line import Segment

    scene = load_scene(str(SYSTEMS[system]["scene"]))
    if order is not None or elements is not None or factor is not None:
        def count(s):
            return elements or (max(1, math.ceil(factor * s.elements)) if factor else s.elements)
        lines = [replace(line, order=order or line.order,
                         segments=tuple(Segment(s.type, s.length, count(s), s.syrope) for s in line.segments))
                 for line in scene.lines]
        scene = replace(scene, lines=lines)
    solver = {key: value for key, value in (("dt", dt), ("tolerance", tolerance),
                                            ("duration", SYSTEMS[system].get("duration"))) if value is not None}
    if dt is not None:  # a step given: fixed steps of it, as a scene's [solver] dt alone
        solver["adaptive"] = False
    return replace(scene, solver=replace(scene.solver, **solver)) if solver else scene


def run_cablefem(scene, duration=None):
    """``run_scene`` on ``scene``: t (n,) [s], fairlead tensions (n, lines) [N] after each step,
    CPU seconds of the whole run and of its steps (inside ``_march``)."""
    import cablefem.runs.run as runs

    rows, spent, march = [], [0.0], runs._march

    def timed(*args):
        begin = time.process_time()
        marched = march(*args)
        spent[0] += time.process_time() - begin
        rows.extend(marched)
        return marched

    runs._march = timed
    try:
        with tempfile.TemporaryDirectory(prefix="cablefem-systems-") as out:
            start = time.process_time()
            runs.run_scene(scene, out, duration=duration, progress=False)
            run_s = time.process_time() - start
    finally:
        runs._march = march
    t = np.array([row[0] for row in rows])
    tension = np.array([[np.linalg.norm(forces[0]) for forces in row[1]] for row in rows])
    return {"t": t, "tension": tension, "run_s": run_s, "steps_s": spent[0]}


def run_moordyn(system, scene, segments=1, dtM=None, ic_dtM=None, duration=None):
    """MoorDyn-C on the system's file, NumSegs times ``segments``, dtM and the initial-condition
    solve's step [s] as given (default: the file's), coupled every 0.01 s under the scene's motion:
    t (n,) [s], tensions (n, lines) [N] at the fairleads in the scene's line order (end-node inertia
    subtracted), CPU seconds of Create + Init + Step (``run_s``) and of Step (``steps_s``). A system
    whose fairleads are on a coupled body (``"peer": "bodies"``) drives the body
    (``validation.networks.dynamics.run_moordyn``)."""
    import moordyn

    duration = scene.solver.duration if duration is None else duration
    with clocked(moordyn, ["Create", "Init", "Step"]) as spent:
        if SYSTEMS[system].get("peer") == "bodies":
            tension = _moordyn_bodies(system, scene, segments, dtM, ic_dtM, duration)
        else:
            from validation.moordyn.runners import run_moordyn_case

            result = run_moordyn_case(SYSTEMS[system]["moordyn"], scene, duration,
                                      {"segments": segments, "dtM": dtM, "ic_dtM": ic_dtM}, coupling_dt=COUPLING_DT)
            tension = np.linalg.norm(result["forces_on_point"], axis=2)
    t = np.arange(len(tension)) * COUPLING_DT
    return {"t": t, "tension": tension, "run_s": sum(spent.values()), "steps_s": spent["Step"]}


def _moordyn_bodies(system, scene, segments, dtM, ic_dtM, duration):
    """Fairlead tensions (n, strings) [N] of MoorDyn-C on a network whose fairleads sit on coupled
    bodies (validation/networks: the file written from the network's one description at ``segments``
    x its NumSegs), in the order of cablefem's strings, end-node inertia subtracted."""
    from cablefem.model.network import dynamic_lines
    from validation.moordyn import peer
    from validation.networks import systems as networks
    from validation.networks.dynamics import run_moordyn as run_bodies
    from validation.networks.dynamics import without_end_inertia
    from validation.networks.run import watch_list

    net = getattr(networks, SYSTEMS[system]["network"])(segments)
    watch = watch_list(net)
    text = networks.moordyn_text(net, **({"dtM": dtM} if dtM else {}))
    dtM = float(peer.option_value(text, "dtM"))  # the file's where none is given
    with tempfile.TemporaryDirectory(prefix="cablefem-systems-") as folder:
        path = Path(folder) / f"{system}.dat"
        path.write_text(text)
        md = run_bodies(path, scene, duration, COUPLING_DT, dtM, ic_dtM or dtM, watch)
    forces = without_end_inertia(md, scene, watch["fairlead_names"])["fairleads"]
    order = [watch["fairlead_names"].index(line.ends[1]) for line in dynamic_lines(scene)]
    return np.linalg.norm(forces[:, order], axis=2)


def references(system, recompute=False):
    """The system's two fine runs on the coupling grid over the error window, from ``systems.json``
    (computed and stored there if missing or ``recompute``): {"moordyn": {...}, "cablefem": {...}},
    each with settings, t (m,) and tension (m, lines)."""
    cached = json.loads(CACHE.read_text()) if CACHE.exists() else {}
    if recompute or system not in cached:
        spec, scene = SYSTEMS[system], scene_of(system)
        t_from = window_start(system, scene)
        grid = np.arange(round(t_from / COUPLING_DT), round(scene.solver.duration / COUPLING_DT) + 1) * COUPLING_DT
        fine = {"moordyn": run_moordyn(system, scene, **spec["moordyn_reference"]),
                "cablefem": run_cablefem(scene_of(system, **spec["cablefem_reference"]))}
        cached[system] = {name: {"settings": spec[f"{name}_reference"], "cpu_s": run["run_s"], "t": grid.tolist(),
                                 "tension": np.column_stack([np.interp(grid, run["t"], column)
                                                             for column in run["tension"].T]).round(3).tolist()}
                          for name, run in fine.items()}
        CACHE.write_text(json.dumps(cached, indent=None) + "\n")
    return {name: {**ref, "t": np.array(ref["t"]), "tension": np.array(ref["tension"])}
            for name, ref in cached[system].items()}


def window_start(system, scene):
    """Start [s] of the error window: the last ``window_periods`` periods of the run."""
    spec = SYSTEMS[system]
    return scene.solver.duration - spec["window_periods"] * spec["period"]


def rows_of(system):
    """(label, runner) of the system's rows: MoorDyn-C on the file, cablefem at its defaults and at
    its best settings."""
    best = SYSTEMS[system]["best"]
    mesh = best["elements"] if "elements" in best else f"{best['factor']:g} NumSegs"
    label = f"cablefem, best (P{best['order']} x {mesh}, dt {best['dt']:g}, tol {best['tolerance']:g})"
    scene = scene_of(system)
    line, solver = scene.lines[0], scene.solver
    steps = f"adaptive <= {solver.dt:g}" if solver.adaptive else f"dt {solver.dt:g}"
    defaults = f"cablefem, defaults (P{line.order} x {sum(s.elements for s in line.segments)}, {steps})"
    return [("MoorDyn-C, the file", lambda: run_moordyn(system, scene_of(system))),
            (defaults, lambda: run_cablefem(scene_of(system))),
            (label, lambda: run_cablefem(scene_of(system, **best)))]


def measure(system, repeats=3, recompute=False):
    """Every row of ``system`` ``repeats`` times, the rows alternating: dict of the rows (label,
    median CPU s per simulated second of run and steps, errors against both references, ratio of
    run times to MoorDyn-C's) and the references' distance apart."""
    spec = SYSTEMS[system]
    if "module" in spec:  # a system of its own module: its references, rows and warm-up
        custom = importlib.import_module(spec["module"])
        refs, duration, runners = custom.references(), custom.DURATION, custom.rows()
        custom.warm()
    else:
        refs = references(system, recompute)
        scene = scene_of(system)
        duration, runners = scene.solver.duration, rows_of(system)
        for settings in ({}, spec["best"]):  # numba's kernels loaded, MoorDyn's library too
            run_cablefem(scene_of(system, **settings), duration=0.1)
        run_moordyn(system, scene, duration=0.1)
    t_from = duration - spec["window_periods"] * spec["period"]
    times = {label: {"run_s": [], "steps_s": []} for label, _ in runners}
    errors = {}
    for _ in range(repeats):
        for label, runner in runners:
            run = runner()
            times[label]["run_s"].append(run["run_s"])
            times[label]["steps_s"].append(run["steps_s"])
            errors[label] = {name: error(run["t"], run["tension"], ref["t"], ref["tension"], t_from)
                             for name, ref in refs.items()}
    rows = [{"label": label, "run_per_s": float(np.median(times[label]["run_s"])) / duration,
             "steps_per_s": float(np.median(times[label]["steps_s"])) / duration,
             "run_s": times[label]["run_s"], "steps_s": times[label]["steps_s"], "errors": errors[label]}
            for label, _ in runners]
    for row, own in zip(rows, ("moordyn", "cablefem", "cablefem")):
        row["ratio"] = row["run_per_s"] / rows[0]["run_per_s"]
        row["steps_ratio"] = row["steps_per_s"] / rows[0]["steps_per_s"]
        row["own_error"] = row["errors"][own]
        row["other_error"] = row["errors"]["cablefem" if own == "moordyn" else "moordyn"]
    apart = error(refs["cablefem"]["t"], refs["cablefem"]["tension"], refs["moordyn"]["t"], refs["moordyn"]["tension"],
                  t_from)
    return {"system": system, "duration_s": duration, "window_from_s": t_from, "repeats": repeats, "rows": rows,
            "references": {name: ref["settings"] for name, ref in refs.items()}, "references_apart": apart}


def table(result):
    """The rows of one system as text, and the issue's target for cablefem at its defaults."""
    refs = result["references"]
    lines = [f"{result['system']}: {result['duration_s']:g} s simulated, CPU s per simulated second (median of "
             f"{result['repeats']}), error % RMS over t >= {result['window_from_s']:g} s against each code's own "
             f"reference (MoorDyn-C {refs['moordyn']}, cablefem {refs['cablefem']}; "
             f"{100 * result['references_apart']:.2f} % apart) and against the other's",
             f"{'row':54s} {'run':>7s} {'steps':>7s} {'error':>6s} {'other':>6s} {'run ratio':>9s} {'steps ratio':>11s}"]
    for row in result["rows"]:
        lines.append(f"{row['label']:54s} {row['run_per_s']:7.4f} {row['steps_per_s']:7.4f} "
                     f"{100 * row['own_error']:6.2f} {100 * row['other_error']:6.2f} "
                     f"{row['ratio']:9.2f} {row['steps_ratio']:11.2f}")
    if not SYSTEMS[result["system"]].get("target"):
        return "\n".join(lines)
    moordyn, defaults = result["rows"][0], result["rows"][1]
    met = defaults["own_error"] <= moordyn["own_error"] and defaults["ratio"] <= 0.25
    lines.append(f"target, cablefem at its defaults: error <= MoorDyn-C's ({100 * defaults['own_error']:.2f} against "
                 f"{100 * moordyn['own_error']:.2f} %) in <= 0.25x its in-process time ({defaults['ratio']:.2f}x): "
                 f"{'met' if met else 'not met'}")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--systems", nargs="+", default=list(SYSTEMS), choices=list(SYSTEMS))
    parser.add_argument("--repeats", type=int, default=3, help="rounds of every row (the median is kept)")
    parser.add_argument("--reference", action="store_true", help="recompute the references (minutes)")
    parser.add_argument("--json", help="write the results to this JSON file")
    args = parser.parse_args(argv)
    results = []
    for system in args.systems:
        results.append(measure(system, args.repeats, args.reference))
        print(table(results[-1]), flush=True)
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1) + "\n")


if __name__ == "__main__":
    main()
