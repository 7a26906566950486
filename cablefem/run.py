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

import json
import sys
import time

import numpy as np

from .dynamics import INTEGRATORS, Integrator, integrator_options
from .errors import ConvergenceError, InputError, OutputError
from .io.checks import check_names, check_run
from .io.output import (RowsFile, deferred_signals, failure as write_failure, inside, prepare_folder,
                        remove_partials, write_atomic)
from .io.vtk import TimeSeriesWriter, polyline_mesh
from .motion import fairlead_motion
from .coupled_steps import junction_steps
from .network import check_no_coupling, coupling, dynamic_lines, line_paths
from .network_output import NetworkRows, body_reference, frame_marks
from .results import LineSampler, line_fields
from .statics import solve_static
from .system import LineSystem


def build_system(scene, line, dynamic=True, fem=None):
    """The ``LineSystem`` of one line of a scene, its loads from the catalog; ``dynamic`` adds
    friction, drag and added mass; ``fem`` shares the FEM of another system of the same line."""
    return LineSystem(line, scene.seabed, scene.contact, scene.environment, assembly=scene.solver.assembly,
                      friction=scene.friction if dynamic else None, fem=fem, dynamic=dynamic,
                      sections=scene.load_settings)


class FairleadPath:
    """The fairlead's prescribed path: path(t) -> (position, velocity, acceleration), each (3,);
    path.positions(times) -> positions (m, 3), in one vectorised call."""

    def __init__(self, motion, fairlead):
        self.motion = motion
        self.fairlead = np.asarray(fairlead, dtype=float)

    def __call__(self, t):
        d, v, a = fairlead_motion(self.motion, t)
        return self.fairlead + d, v, a

    def positions(self, times):
        return self.fairlead + fairlead_motion(self.motion, times)[0]


def boundary_path(scene, line):
    """The fairlead end's prescribed path of ``line`` in ``scene``: a ``FairleadPath`` following
    [motion], or the path of the network point it names (``cablefem.network.line_paths``)."""
    if line.ends == (None, None):
        return FairleadPath(scene.motion, line.fairlead)
    return line_paths(scene, line)[1]


def anchor_path(scene, line):
    """The anchor end's prescribed path of ``line`` (None: fixed where the line has it)."""
    return None if line.ends[0] is None else line_paths(scene, line)[0]


def start_states(scene, t0=0.0, systems=None):
    """Static equilibrium of every line with its prescribed ends where their paths put them at t0
    (a network's junctions solved with their strings: ``cablefem.coupling``); ``systems``: the
    lines' dynamic systems, whose FEM the static ones share and which start from the statics'
    history of the points."""
    check_no_coupling(scene)
    network = None
    if any(coupling(scene.lines, scene.points, scene.bodies)):
        from .coupling import solve_network

        network = solve_network(scene, lambda line: build_system(scene, line, dynamic=False),
                                tolerance=scene.solver.tolerance,
                                max_iterations=scene.solver.max_iterations)
    states, iterations = [], 0 if network is None else network.iterations
    for k, line in enumerate(scene.lines):
        if network is not None and network.states[k] is not None:
            static, X = network.systems[k], network.states[k]
        else:
            anchor = anchor_path(scene, line)
            moved = line.with_ends(line.anchor if anchor is None else anchor(t0)[0],
                                   boundary_path(scene, line)(t0)[0])
            fem = None if systems is None else systems[k].fem
            static = build_system(scene, moved, dynamic=False, fem=fem)
            if "soil" in scene.load_settings:  # a line in soil starts where its pretension path ends
                from .pretension import solve_pretension

                result = solve_pretension(static, scene.solver.tolerance, scene.solver.max_iterations)
            else:
                result = solve_static(static, tolerance=scene.solver.tolerance,
                                      max_iterations=scene.solver.max_iterations)
            X, iterations = result.X, iterations + result.iterations
        if systems is not None:
            for rule, (old, new) in static.history.items():
                systems[k].history[rule][0][...] = old
                systems[k].history[rule][1][...] = old
        states.append(X)
    return states, iterations


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
    from .geometry.export import write_seabed_vtu

    check_names(scene)
    check_run(scene, duration, dt)
    solver = scene.solver
    if solver.adaptive and solver.integrator != "bdf2":
        raise InputError("adaptive steps need integrator = \"bdf2\"", key="solver.adaptive")
    duration = float(solver.duration if duration is None else duration)
    dt = float(solver.dt if dt is None else dt)
    out_dir = prepare_folder(out_dir or scene.output.dir)
    remove_partials(out_dir, (f"{scene.name}_", f"{scene.name}.pvd", "seabed.vtu", "tensions.csv",
                              "summary.json"))
    start = time.perf_counter()
    summary = {"scene": scene.name, "seabed": scene.seabed.describe(),
               "notes": list(scene.notes) + setting_warnings(scene, dt), "dt": dt, "duration": duration}
    integrators, outputs, status = [], {}, "completed"
    step_control = StepControl(solver, dt)
    tracker = _Extremes([line.name for line in scene.lines], NetworkRows(scene) if scene.points else None)
    try:
        seabed_vtu = inside(out_dir, "seabed.vtu")
        try:
            write_seabed_vtu(scene.seabed, seabed_vtu, _bounds(scene))
        except OSError as error:
            raise write_failure(error, seabed_vtu) from None
        integrator_class = INTEGRATORS[solver.integrator]
        options = integrator_options(solver)
        systems = [build_system(scene, line) for line in dynamic_lines(scene)]
        states, summary["static_newton_iterations"] = start_states(scene, systems=systems)
        integrators += [integrator_class(system, X0, boundary_path(scene, line), dt=dt,
                                         anchor=anchor_path(scene, line), **options)
                        for system, line, X0 in zip(systems, scene.lines, states)]
        junction_steps(scene, integrators)
        outputs["frames"] = TimeSeriesWriter(out_dir, scene.name)
        outputs["table"] = RowsFile(inside(out_dir, "tensions.csv"), _columns(scene, tracker.network))
        outputs["bar"] = _progress(progress, duration)
        _advance(scene, integrators, outputs, step_control, tracker, duration, dt)
    except KeyboardInterrupt:
        status = "interrupted"
        raise
    except Exception as error:
        status = f"stopped: {error}"
        raise
    finally:
        _finish(summary, status, integrators, outputs, step_control, tracker, start, out_dir,
                reraise=status == "completed")
    return summary


def _advance(scene, integrators, outputs, step_control, tracker, duration, dt):
    """March every line to ``duration`` [s], writing a row of tensions.csv per step (a batch per
    output interval) and a VTK frame every ``output.every`` [s]. Ctrl-C and SIGTERM take effect
    between output intervals (``deferred_signals``; a compiled march does not see them sooner
    anyway), so that the rows and frames always hold every step taken."""
    solver, frames, table, bar = scene.solver, outputs["frames"], outputs["table"], outputs["bar"]
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
            frames.write(t, polyline_mesh([line_fields(i.system, i.X, i.V, sampler=sampler)
                                           for i, sampler in zip(integrators, samplers)], marks, bodies))
            frame = int(np.floor((t + near) / every)) + 1
        return t

    t = record([(integrators[0].t, [integ.reactions() for integ in integrators])])
    while t < duration - near:
        with deferred_signals():
            stop = min(duration, frame * every)
            if solver.adaptive:
                step_control.advance(integrators, stop - t)
                rows = [(integrators[0].t, [integ.reactions() for integ in integrators])]
            else:  # fixed steps to the next output time, each line in one call
                rows = _march(integrators, step_control.times(t, stop), lambda rows: table.write(tracker.rows(rows)))
            if bar is not None:
                bar.update(rows[-1][0] - t)
            t = record(rows)


def _finish(summary, status, integrators, outputs, step_control, tracker, start, out_dir, reraise):
    """Close the collection and tensions.csv and write summary.json, with SIGINT and SIGTERM held
    until they are done. A failure to write (a full disk) is raised if nothing else failed
    (``reraise``), else that other failure is the one reported."""
    errors = []
    with deferred_signals(reraise=reraise):
        for name in ("frames", "table"):
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
            "wall_time_s": time.perf_counter() - start,
            "steps": sum(s["steps"] for s in stats),
            "newton_iterations": sum(s["newton_iterations"] for s in stats),
            "integrator": stats, "tension_extremes": tracker.as_dict(),
            **({"network_extremes": tracker.network.extremes} if tracker.network is not None else {}),
            "adaptive": {"accepted": step_control.accepted, "rejected": step_control.rejected}
            if step_control.adaptive else None})
        summary.setdefault("static_newton_iterations", 0)
        try:
            write_atomic(inside(out_dir, "summary.json"), json.dumps(summary, indent=1))
        except OutputError as error:
            errors.append(error)
    if errors and reraise:
        raise errors[0]


class StepControl:
    """Fixed steps of dt (``times``), or (``solver.adaptive``, BDF2; ``advance``) steps chosen
    from the local error estimate so that the tension error per step stays near
    ``solver.error_tolerance`` (a fraction of the largest tension), never above dt; all lines
    step together. Either lands on the stops it is given without leaving a sliver before them."""

    def __init__(self, solver, dt):
        self.adaptive = solver.adaptive
        self.tolerance = solver.error_tolerance
        self.max_dt = dt
        self.h = dt / 8 if self.adaptive else dt
        self.accepted = self.rejected = 0

    @staticmethod
    def landing(h, to_stop):
        """The step to take instead of h with ``to_stop`` [s] left: all of it when h would leave
        no more than ``Integrator.STRETCH`` h (never a sliver before a stop), half of it when
        it is under 2 h, else h."""
        if to_stop <= h * (1 + Integrator.STRETCH):
            return to_stop
        return to_stop / 2 if to_stop < 2 * h else h

    def times(self, t, stop):
        """The times (m,) of fixed steps of dt from t to ``stop``, landing on it (``landing``)."""
        times = []
        while stop - t > 1e-9 * self.max_dt:
            h = self.landing(self.max_dt, stop - t)
            t = stop if h == stop - t else t + h
            times.append(t)
        return np.array(times)

    def advance(self, integrators, to_stop):
        """Take one step (retrying smaller ones when adaptive) of at most ``to_stop`` [s]."""
        while True:
            h = self.landing(self.h if self.adaptive else self.max_dt, to_stop)
            snapshots = [integ.snapshot() for integ in integrators]
            first = any(getattr(integ, "previous", True) is None for integ in integrators)
            for integ in integrators:
                integ.step(h)
            if not self.adaptive or first:
                return h
            error = max(integ.error_estimate() for integ in integrators)
            factor = 0.9 * (self.tolerance / error) ** (1 / 3) if error > 0 else 2.0
            if error <= self.tolerance or h <= integrators[0].min_dt:
                self.accepted += 1
                if h >= self.h * (1 - 1e-12):  # not shortened to land on an output time
                    self.h = min(self.max_dt, h * min(2.0, max(0.5, factor)))
                return h
            self.rejected += 1
            for integ, snap in zip(integrators, snapshots):
                integ.restore(snap)
            self.h = h * max(0.2, factor)


def _march(integrators, times, write):
    """Every line marched to ``times``: rows (t, [(fairlead, anchor) force per line]). If a line
    fails, the rows every line reached are given to ``write`` before the error goes on."""
    forces = []
    try:
        for integ in integrators:
            forces.append(integ.march(times))
    except ConvergenceError as error:
        last = len(forces) == len(integrators) - 1  # the lines before it have all the rows
        reached = len(error.forces) if last else 0
        if reached:
            write([(times[k], [f[k] for f in forces + [error.forces]]) for k in range(reached)])
        raise
    return [(tk, [f[k] for f in forces]) for k, tk in enumerate(times)]


def _row(t, forces, extra=()):
    """A tensions.csv row: t, then per line fairlead_tension, anchor_tension, fx, fy, fz, from each
    line's (fairlead, anchor) forces, then the network's ``extra`` values."""
    values = [t]
    for fairlead, anchor in forces:
        values += [np.linalg.norm(fairlead), np.linalg.norm(anchor), *fairlead]
    return [f"{x:.10g}" for x in [*values, *extra]]


def _columns(scene, network=None):
    names = ["fairlead_tension", "anchor_tension", "fx", "fy", "fz"]
    extra = [] if network is None else network.columns()
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
    """Largest and smallest fairlead and anchor tensions per line, with their times, and the
    network's columns and extremes (``network``: a ``NetworkRows`` or None)."""

    def __init__(self, names, network=None):
        self.names = names
        self.table = {n: {} for n in names}
        self.network = network

    def rows(self, rows):
        """The tensions.csv rows of ``rows`` (t, forces per line), the extremes updated."""
        for t, forces in rows:
            self.update(t, forces)
        if self.network is None:
            return [_row(t, forces) for t, forces in rows]
        extra = self.network.values([t for t, _ in rows], [forces for _, forces in rows])
        return [_row(t, forces, values) for (t, forces), values in zip(rows, extra)]

    def update(self, t, forces):
        for name, (fairlead, anchor) in zip(self.names, forces):
            for key, value in (("fairlead_tension", np.linalg.norm(fairlead)),
                               ("anchor_tension", np.linalg.norm(anchor))):
                entry = self.table[name]
                if f"{key}_max" not in entry or value > entry[f"{key}_max"]:
                    entry[f"{key}_max"], entry[f"{key}_max_t"] = float(value), float(t)
                if f"{key}_min" not in entry or value < entry[f"{key}_min"]:
                    entry[f"{key}_min"], entry[f"{key}_min_t"] = float(value), float(t)

    def as_dict(self):
        return self.table
