"""Time-domain runs of a scene: static start, implicit steps, outputs written as the run goes.

A run writes DIR/<name>.pvd with one .vtu per output frame, DIR/seabed.vtu,
DIR/tensions.csv (one row per time step) and DIR/summary.json (docs/outputs.md).
Frames and rows are written while the run goes, so memory does not grow
with the duration, and each is written whole or not at all
(``cablefem.io.output``): a run stopped by Ctrl-C, SIGTERM, a solver failure
or a full disk still leaves a valid .pvd listing every complete frame, the
whole rows computed so far and a summary saying where it stopped; one killed
outright leaves all of that but the summary.
"""

import contextlib
import json
import os
import sys
import time

import numpy as np

from cablefem.dynamics.group import Group, junction_groups
from cablefem.dynamics.integrator import Integrator
from cablefem.dynamics.registry import INTEGRATORS, integrator_options
from cablefem.errors import ConvergenceError, InputError, OutputError
from cablefem.io.checks import check_names, check_run
from cablefem.io.output import (RowsFile, deferred_signals, failure as write_failure, inside, prepare_folder,
                                remove_partials, tidy, write_atomic)
from cablefem.io.vtk import TimeSeriesWriter, polyline_mesh, series_files
from cablefem.model.network import anchor_path, boundary_path
from cablefem.runs.network_output import NetworkRows, body_reference, frame_marks
from cablefem.runs.bending_rows import BendingRows
from cablefem.runs.failures import Failures
from cablefem.runs.results import LineSampler, line_fields
from cablefem.runs.surface import NAME as SURFACE, SurfaceFrames
from cablefem.statics.scene import run_start


#: the files every run writes in its folder, beside its frames and their .pvd
RUN_FILES = ("seabed.vtu", "tensions.csv", "summary.json")

#: largest rho_inf of generalised-alpha that stayed bounded on a stiff taut line at omega dt >> 1
SAFE_RHO_INF = 0.5


def setting_warnings(scene, dt=None):
    """Warnings about solver settings known to fail on this scene, said before the run starts.

    Generalised-alpha with rho_inf above ``SAFE_RHO_INF`` pumps energy into a line whose
    highest axial frequency, omega = (2 / h) sqrt(EA / m) for the shortest element h, is
    not resolved by the step (omega dt > 1): verification/stability, case 7b."""
    solver = scene.solver
    dt = float(solver.dt if dt is None else dt)
    warnings = []
    if solver.integrator == "generalized-alpha" and solver.rho_inf > SAFE_RHO_INF:
        omega = max(2.0 / (seg.length / seg.elements / line.order) * np.sqrt(seg.type.EA / seg.type.mass)
                    for line in scene.lines for seg in line.segments)
        if omega * dt > 1.0:
            warnings.append(
                f"generalized-alpha with rho_inf = {solver.rho_inf:g} > {SAFE_RHO_INF:g} at omega dt = "
                f"{omega * dt:.3g}: this scheme can pump energy into a stiff line going taut "
                f"(nonlinear instability); use rho_inf <= {SAFE_RHO_INF:g} or integrator = \"bdf2\"")
    return warnings


def _bounds(scene, margin=0.1):
    points = np.array([p for line in scene.lines for p in (line.anchor, line.fairlead)])
    lo, hi = points[:, :2].min(axis=0), points[:, :2].max(axis=0)
    pad = margin * max(float(np.max(hi - lo)), 1.0)
    return ((lo[0] - pad, hi[0] + pad), (lo[1] - pad, hi[1] + pad))


def run_scene(scene, out_dir=None, duration=None, dt=None, progress=None):
    """Run a scene in the time domain and write its outputs; returns the summary dict.

    Before any work: the scene's names and run size are checked (``cablefem.io.checks``) and
    the output folder is made and probed (``OutputError`` if it cannot be written). Every
    output is written whole or not at all (``cablefem.io.output``); a run stopped by Ctrl-C,
    SIGTERM (``raise_on_sigterm``), a solver failure or an output fault still leaves a .pvd
    listing every complete frame, whole rows of tensions.csv, and a summary.json saying why."""
    from cablefem.geometry.export import write_seabed_vtu

    check_names(scene)
    check_run(scene, duration, dt)
    water = scene.environment.waves
    sea = water if water is not None and water.count else None  # waves (a current alone has no surface)
    if sea is not None and scene.name == SURFACE:
        raise InputError(f"a scene in waves may not be named '{SURFACE}': its frames and the free surface's would "
                         f"both be {SURFACE}.pvd", key="name", file=scene.where("name")[0])
    solver = scene.solver
    duration = float(solver.duration if duration is None else duration)
    dt = float(solver.dt if dt is None else dt)
    out_dir = prepare_folder(out_dir or scene.output.dir)
    remove_partials(out_dir, (f"{scene.name}_", f"{scene.name}.pvd", *RUN_FILES)
                    + ((f"{SURFACE}_", f"{SURFACE}.pvd") if sea is not None else ()))
    remove_earlier_run(out_dir, scene.name)
    if sea is not None:  # the free surface of an earlier run in waves
        remove_earlier_run(out_dir, SURFACE, files=())
    start = time.perf_counter()
    summary = {"scene": scene.name, "seabed": scene.seabed.describe(),
               "notes": list(scene.notes) + setting_warnings(scene, dt), "dt": dt, "duration": duration,
               **({"waves": sea.describe()} if sea is not None else {}),
               **({"current": water.current.describe()} if water is not None and water.current is not None else {})}
    integrators, outputs, status = [], {}, "completed"
    failures = Failures(scene, dt)
    tracker = _Extremes([line.name for line in scene.lines], NetworkRows(scene) if scene.points else None, sea,
                        BendingRows(scene.lines))
    try:
        seabed_vtu = inside(out_dir, "seabed.vtu")
        try:
            write_seabed_vtu(scene.seabed, seabed_vtu, _bounds(scene))
        except OSError as error:
            raise write_failure(error, seabed_vtu) from None
        integrator_class = INTEGRATORS[solver.integrator]
        options = integrator_options(solver)
        systems, states, summary["static_newton_iterations"] = run_start(scene)
        integrators += [integrator_class(system, X0, boundary_path(scene, line), dt=dt,
                                         anchor=anchor_path(scene, line), **options)
                        for system, line, X0 in zip(systems, scene.lines, states)]
        groups = _groups(scene, integrators)
        outputs["frames"] = TimeSeriesWriter(out_dir, scene.name)
        tracker.bending.attach(integrators)
        if sea is not None:
            outputs["surface"] = SurfaceFrames(sea, _bounds(scene), out_dir)
        outputs["table"] = RowsFile(inside(out_dir, "tensions.csv"),
                                    _columns(scene, tracker.network, sea, tracker.bending))
        outputs["bar"] = _progress(progress, duration)
        _advance(scene, integrators, groups, outputs, tracker, duration, dt, failures)
    except KeyboardInterrupt:
        status = "interrupted"
        raise
    except Exception as error:
        status = f"stopped: {error}"
        raise
    finally:
        if scene.failures:
            summary["failures"] = failures.summary()
        _finish(summary, status, integrators, outputs, tracker, start, out_dir,
                reraise=status == "completed")
    return summary


def remove_earlier_run(out_dir, name, files=RUN_FILES):
    """Remove what an earlier run of a scene called ``name`` wrote in ``out_dir`` (its frames and
    .pvd, the pictures ``cablefem render`` made of them there, and the folder's ``files``: seabed.vtu,
    tensions.csv and summary.json, which every run writes), so that the folder holds this run's
    outputs only; no other file is touched."""
    from cablefem.post import picture_files

    for path in series_files(out_dir, name) + picture_files(out_dir, name) + [inside(out_dir, f) for f in files]:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(path)


def _groups(scene, integrators):
    """The groups that step the lines (``cablefem.dynamics.group``): the strings that meet at junctions
    together, every other line alone."""
    groups = junction_groups(scene, integrators)
    joined = {id(m) for group in groups for m in group.members}
    return groups + [Group([integ]) for integ in integrators if id(integ) not in joined]


def _reactions(integrators, groups):
    """Every line's (fairlead, anchor) forces [N] in scene order, as its group reports them."""
    forces = {}
    for group in groups:
        forces.update({id(m): f for m, f in zip(group.members, group.reactions())})
    return [forces[id(integ)] for integ in integrators]


def step_times(t, stop, dt):
    """The times (m,) of fixed steps of dt [s] from t to ``stop``, landing on it: a step within
    ``Integrator.STRETCH`` of what is left takes all of it (never a sliver before a stop), one
    under twice dt takes half."""
    times = []
    while stop - t > 1e-9 * dt:
        left = stop - t
        h = left if left <= dt * (1 + Integrator.STRETCH) else (left / 2 if left < 2 * dt else dt)
        t = stop if h == left else t + h
        times.append(t)
    return np.array(times)


def _advance(scene, integrators, groups, outputs, tracker, duration, dt, failures):
    """March every line to ``duration`` [s], writing a row of tensions.csv per step (a batch per
    output interval) and a VTK frame every ``output.every`` [s]. Ctrl-C and SIGTERM take effect
    between output intervals (``deferred_signals``; a compiled march does not see them sooner
    anyway), so that the rows and frames always hold every step taken. The steps land on the
    failures' times; with a failure's tension to watch, fixed steps stop after the first step over
    it (``_march_to_tension``); where a failure is due a line end lets go (``cablefem.runs.failures``)."""
    solver, frames, table, bar = scene.solver, outputs["frames"], outputs["table"], outputs["bar"]
    surface = outputs.get("surface")
    samplers = [LineSampler(integ.system) for integ in integrators]  # the frames' points, once
    marks, body_marks = frame_marks(scene)
    every = scene.output.every if solver.adaptive else max(scene.output.every, dt)
    near = 1e-6 * dt  # times closer than this are the same time
    frame = 0  # frames fall at frame * every, not at a sum of steps carrying round-off

    def record(rows):
        """Write the rows (t, forces) and, if one is due, a frame; the time [s] of the last row."""
        nonlocal frame
        table.write(tracker.rows(rows))
        t = rows[-1][0]
        if t >= frame * every - near:
            bodies = [(body_reference(scene.bodies[name], t), rows) for name, rows in body_marks]
            frames.write(t, polyline_mesh([line_fields(i.system, i.X, i.V, sampler=sampler, ends=ends)
                                           for i, sampler, ends in zip(integrators, samplers, rows[-1][1])],
                                          marks, bodies))
            if surface is not None:
                surface.write(t)
            frame = int(np.floor((t + near) / every)) + 1
        return t

    def write(rows):
        table.write(tracker.rows(failures.zero(rows)))

    def release(row):
        """Let go of the ends whose failures are due at ``row``; their lines' groups and samplers anew."""
        before = list(integrators)
        for k in failures.release_due(row, scene, integrators):
            _regroup(groups, before[k], integrators[k])
            samplers[k] = LineSampler(integrators[k].system)

    tracker.bending.measure(integrators[0].t)
    first = [(integrators[0].t, _reactions(integrators, groups))]
    t = record(first)
    if scene.failures:
        release(first[-1])
    while t < duration - near:
        with deferred_signals():
            stop = min(duration, frame * every, failures.next_time(t))
            # fixed steps to the next output time, or adaptive ones (``policy.advance``): each group in one call
            times = np.array([stop]) if solver.adaptive else step_times(t, stop, dt)
            if tracker.bending and times.size > 1:  # a bending line's end moments: its state after every step
                rows = []
                for each in times:
                    rows += _march(integrators, groups, np.array([each]), write)
                    tracker.bending.measure(rows[-1][0])
                    if failures.due(rows[-1]):  # a line end lets go after this step
                        break
            elif failures.watching_tension and not solver.adaptive:
                rows = _march_to_tension(integrators, groups, times, write, failures)
            else:
                rows = _march(integrators, groups, times, write)
                tracker.bending.measure(rows[-1][0])
            rows = failures.zero(rows)
            if bar is not None:
                bar.update(rows[-1][0] - t)
            t = record(rows)
            if scene.failures:
                release(rows[-1])


def _march_to_tension(integrators, groups, times, write, failures):
    """``_march`` to ``times``, stopping after the first step at whose end a failure's tension is
    exceeded: the steps are marched in one call; where a row before the last is over a threshold, the
    groups go back to where they were (``Group.restore``) and march again one step at a time to that
    row, so that an end lets go after the first step over its threshold (the steps taken twice are
    counted twice). A march that fails is taken again step by step too: an end may let go before."""
    saved = [group.snapshot() for group in groups]
    try:
        rows = _march(integrators, groups, times, lambda rows: None)
        k = failures.first_due(rows)
        if k is None or k == len(rows) - 1:
            return rows
    except ConvergenceError:  # the intact line failed where it might have let go before: step by step
        k = len(times) - 1
    for group, snapshot in zip(groups, saved):
        group.restore(snapshot)
        group.marched = None
        for member in group.members:
            member.contraction = -1.0  # the kept factors are of a later state
    rows = []
    try:
        for tk in times[:k + 1]:
            rows += _march(integrators, groups, [tk], write)
            if failures.due(rows[-1]):
                break
    except ConvergenceError:
        if rows:  # the steps taken before the one that failed
            write(rows)
        raise
    return rows


def _regroup(groups, old, new):
    """The group that stepped integrator ``old`` made again with ``new`` in its place (a line end let
    go: ``cablefem.runs.failures``), the accelerations of its other members kept (a junction's group
    starts them at rest)."""
    for g, group in enumerate(groups):
        if any(m is old for m in group.members):
            members = [new if m is old else m for m in group.members]
            kept = [m.A.copy() for m in members]
            groups[g] = Group(members, group.junctions)
            for m, A in zip(members, kept):
                m.A[...] = A


def _finish(summary, status, integrators, outputs, tracker, start, out_dir, reraise):
    """Close the collection and tensions.csv and write summary.json, with SIGINT and SIGTERM held
    until they are done. A failure to write (a full disk) is raised if nothing else failed
    (``reraise``), else that other failure is the one reported."""
    errors = []
    with deferred_signals(reraise=reraise):
        for name in ("frames", "surface", "table"):
            if name in outputs:
                try:
                    outputs[name].close()
                except OutputError as error:
                    errors.append(error)
        if outputs.get("bar") is not None:
            outputs["bar"].close()
        stats = [integ.statistics() for integ in integrators]
        summary.update({
            "status": status, "completed": status == "completed",
            "simulated_time_s": integrators[0].t if integrators else 0.0,
            "frames": outputs["frames"].listed if "frames" in outputs else 0,
            **({"surface_frames": outputs["surface"].listed} if "surface" in outputs else {}),
            "wall_time_s": time.perf_counter() - start,
            "steps": sum(s["steps"] for s in stats),
            "newton_iterations": sum(s["newton_iterations"] for s in stats),
            "integrator": stats, "tension_extremes": tracker.as_dict(),
            **({"curvature_extremes": tracker.bending.extremes} if tracker.bending else {}),
            **({"network_extremes": tracker.network.extremes} if tracker.network is not None else {}),
            "adaptive": {"accepted": sum(s["steps"] for s in stats), "rejected": sum(s["rejected"] for s in stats)}
            if integrators and integrators[0].adaptive else None})
        summary.setdefault("static_newton_iterations", 0)
        try:
            write_atomic(inside(out_dir, "summary.json"), json.dumps(tidy(summary), indent=1))
        except OutputError as error:
            errors.append(error)
    if errors and reraise:
        raise errors[0]


def _march(integrators, groups, times, write):
    """Every group marched to ``times``: rows (t, [(fairlead, anchor) force per line]). If a group
    fails, the rows every line reached are given to ``write`` before the error goes on."""
    forces = {}
    for g, group in enumerate(groups):
        try:
            marched = group.march(times)
        except ConvergenceError as error:
            reached = len(error.forces) if g == len(groups) - 1 else 0  # the groups before it have all the rows
            forces.update({id(m): error.forces[:, k] for k, m in enumerate(group.members)})
            if reached:
                write([(times[k], [forces[id(integ)][k] for integ in integrators]) for k in range(reached)])
            raise
        forces.update({id(m): marched[:, k] for k, m in enumerate(group.members)})
    return [(tk, [forces[id(integ)][k] for integ in integrators]) for k, tk in enumerate(times)]


def _row(t, forces, tensions, extra=()):
    """A tensions.csv row: t, then per line fairlead_tension, anchor_tension, fx, fy, fz, from each
    line's (fairlead, anchor) forces and their ``tensions`` (lines, 2), then the network's ``extra``
    values."""
    values = [t]
    for (fairlead, _), (T_fairlead, T_anchor) in zip(forces, tensions):
        values += [T_fairlead, T_anchor, *fairlead]
    return [f"{x + 0.0:.10g}" for x in [*values, *extra]]  # + 0.0: no "-0"


def _columns(scene, network=None, sea=None, bending=None):
    names = ["fairlead_tension", "anchor_tension", "fx", "fy", "fz"]
    extra = ([] if bending is None else bending.columns(len(scene.lines) > 1)) + \
        ([] if network is None else network.columns()) + ([] if sea is None else ["eta"])
    if len(scene.lines) == 1:
        return ["t"] + names + extra
    return ["t"] + [f"{line.name}:{n}" for line in scene.lines for n in names] + extra


def _progress(progress, duration):
    show = sys.stderr.isatty() if progress is None else progress
    if not show:
        return None
    from tqdm import tqdm

    return tqdm(total=duration, unit="s", desc="cablefem run", bar_format="{l_bar}{bar}| {n:.1f}/{total:.1f} s [{elapsed}<{remaining}]")


class _Extremes:
    """Largest and smallest fairlead and anchor tensions per line, with their times, the
    network's columns and extremes (``network``: a ``NetworkRows`` or None), in waves (``sea``) the
    elevation at the origin, and the bending lines' end moments and curvature extremes (``bending``:
    a ``BendingRows``)."""

    def __init__(self, names, network=None, sea=None, bending=None):
        self.names = names
        self.table = {n: {} for n in names}
        self.network = network
        self.sea = sea
        self.bending = bending

    def rows(self, rows):
        """The tensions.csv rows of ``rows`` (t, forces per line), the extremes updated."""
        times = np.array([t for t, _ in rows])
        tensions = np.linalg.norm(np.array([forces for _, forces in rows], dtype=float).reshape(len(rows), -1, 2, 3),
                                  axis=-1)  # (rows, lines, 2): each row's fairlead and anchor tension
        self.update(times, tensions)
        extra = [[] for _ in rows] if self.network is None else \
            self.network.values(list(times), [forces for _, forces in rows])
        if self.bending:  # a row a step: the moments at the state each step reached (``_advance``)
            extra = [[*self.bending.values(), *values] for values in extra]
        if self.sea is not None:
            extra = [list(values) + [eta] for values, eta in zip(extra, self.sea.elevation(0.0, 0.0, times))]
        return [_row(t, forces, T, values) for (t, forces), T, values in zip(rows, tensions, extra)]

    def update(self, times, tensions):
        """The extremes after rows at ``times`` (m,) with ``tensions`` (m, lines, 2); the first time of
        an extreme is kept."""
        for name, line in zip(self.names, np.moveaxis(tensions, 1, 0)):
            entry = self.table[name]
            for key, values in (("fairlead_tension", line[:, 0]), ("anchor_tension", line[:, 1])):
                high, low = int(np.argmax(values)), int(np.argmin(values))
                if f"{key}_max" not in entry or values[high] > entry[f"{key}_max"]:
                    entry[f"{key}_max"], entry[f"{key}_max_t"] = float(values[high]), float(times[high])
                if f"{key}_min" not in entry or values[low] < entry[f"{key}_min"]:
                    entry[f"{key}_min"], entry[f"{key}_min_t"] = float(values[low]), float(times[low])

    def as_dict(self):
        return self.table
