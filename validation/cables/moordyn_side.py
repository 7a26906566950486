"""MoorDyn-C (PyPI ``moordyn``) on the lazy wave: its static solve and its run under the hang-off's motion.

MoorDyn finds its static shape by dynamic relaxation (``ICgenDynamic 1``: the lines let go with their
drag scaled up until the line tensions change by less than ``threshIC`` over ``dtIC``); its quasi-static
solver stalled on this cable (3.5 m/s^2 of residual acceleration after 88 s). Relaxing from its own
straight start costs ~40 s at 100 segments and grows with the square of the segment count, so the
relaxation starts instead from a given shape (``start``: cablefem's static solution, sampled at
MoorDyn's nodes), written into MoorDyn's own state file (``SaveState`` of ``Init_NoIC``, the node
positions found by their values) and read as its ``fileIC``: the equilibrium is still MoorDyn's, the
relaxation runs until its own test passes.

The hang-off is a Coupled Rod: ``Step`` moves it along the straight line between coupling times
(MoorDyn's linear coupled kinematics) with the secant velocity of the motion, as validation/moordyn's
peer does. Outputs per coupling time: the force (3,) and moment (3,) the cable exerts on the Rod
(``GetRodForce``; the Rod is 1 cm long and weightless), and the largest node curvature
(``GetLineNodeCurv``: 4 / l sin(phi / 2), its ``GetCurvature``) away from the hang-off.
"""

import contextlib
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from validation.cables import case
from validation.moordyn.peer import silenced_stdout

#: the dynamic relaxation of MoorDyn's static solve
IC = {"writeLog": 2, "ICgenDynamic": 1, "ICDfac": 5.0, "dtIC": 1.0, "TmaxIC": 300.0, "threshIC": 1e-4}
#: the curvature peak is looked for this far [m] from the hang-off and beyond (its boundary layer)
CLEAR = 10.0


def _node_arc_lengths(segments):
    """Unstretched arc length [m] of every node of each MoorDyn line, [(n + 1,), ...]."""
    out, start = [], 0.0
    for (_, length), n in zip(case.SECTIONS, segments):
        out.append(start + np.linspace(0.0, length, n + 1))
        start += length
    return out


def write_start(path, segments, positions):
    """MoorDyn's state file at ``path`` with every line node at ``positions(s)`` ((n, 3) at unstretched
    arc lengths s (n,)) and the joints at the sections' ends, at rest. The offsets of the positions in
    MoorDyn's state are found by the values ``Init_NoIC`` put there (its straight lines)."""
    import moordyn

    with tempfile.TemporaryDirectory() as tmp:
        model = Path(tmp) / "model.dat"
        model.write_text(case.moordyn_text(segments, 1e-4))
        state = Path(tmp) / "state.bin"
        with silenced_stdout():
            system = moordyn.Create(str(model))
            moordyn.Init_NoIC(system, list(case.HANG_OFF) + [0.0] * 3, [0.0] * 6)
            moordyn.SaveState(system, str(state))
            raw = bytearray(state.read_bytes())
            for k, s in enumerate(_node_arc_lengths(segments)):
                line = moordyn.GetLine(system, k + 1)
                target = positions(s)
                for i in range(1, len(s) - 1):  # the interior nodes are the line's state
                    old = np.array(moordyn.GetLineNodePos(line, i), dtype=float).tobytes()
                    at = raw.find(old)
                    raw[at:at + 24] = np.asarray(target[i], dtype=float).tobytes()
                    raw[at + 24:at + 48] = np.zeros(3).tobytes()
            ends = [s[-1] for s in _node_arc_lengths(segments)][:-1]
            for k, s in enumerate(ends):  # the joints: free zero-length Rods 2 and 3
                old = np.array(moordyn.GetRodNodePos(moordyn.GetRod(system, k + 2), 0), dtype=float).tobytes()
                at = raw.find(old)
                raw[at:at + 24] = np.asarray(positions(np.array([s]))[0], dtype=float).tobytes()
            moordyn.Close(system)
    Path(path).write_bytes(bytes(raw))


def _curvature_peak(moordyn, system, arcs):
    """The largest node curvature [1/m] farther than ``CLEAR`` from the hang-off, and its arc length."""
    best, where = 0.0, None
    for k, s in enumerate(arcs):
        line = moordyn.GetLine(system, k + 1)
        for i, si in enumerate(s):
            if si > case.LENGTH - CLEAR:
                continue
            kappa = moordyn.GetLineNodeCurv(line, i)
            if kappa > best:
                best, where = kappa, float(si)
    return best, where


@contextlib.contextmanager
def initialised(path, x=(), v=()):
    """MoorDyn's system of the file at ``path`` after ``Init`` (its static solve) at the coupled state x,
    v, run in the file's folder (MoorDyn writes its files beside it) with its output silenced:
    yields (moordyn, system, Init's wall time [s]); closed after."""
    import moordyn

    cwd = os.getcwd()
    try:
        os.chdir(Path(path).parent)
        with silenced_stdout():
            system = moordyn.Create(str(path))
            begin = time.perf_counter()
            moordyn.Init(system, list(x), list(v))
            yield moordyn, system, time.perf_counter() - begin
            moordyn.Close(system)
    finally:
        os.chdir(cwd)


def run(segments, dtM, start, duration=0.0, dt_out=0.05, motion=None, keep=None, every=1, options=None, files=None):
    """MoorDyn's static solve from ``start`` (positions(s) -> (n, 3)) and, with ``duration``, its run under
    ``motion`` (t -> hang-off position (3,)); a dict: the static hang-off force (3,), moment (3,) and
    curvature peak (value, arc length), the relaxation's wall time; with a run, the times (m,), the
    force (m, 3), moment (m, 3) and curvature peak (m,) at every ``every``-th coupling time, and the
    wall time of its ``Step`` calls (the outputs read between them not counted). ``keep``: a folder to
    leave MoorDyn's files in; ``options``: more OPTIONS (name -> value: a ``WaveKin``); ``files``:
    {name: text} of data files written beside the input (its ``wave_frequencies.txt``)."""
    folder = Path(keep or tempfile.mkdtemp(prefix="cables-moordyn-"))
    folder.mkdir(parents=True, exist_ok=True)
    write_start(folder / "start.bin", segments, start)
    path = folder / "lazy_wave.dat"
    path.write_text(case.moordyn_text(segments, dtM, {**IC, "fileIC": "start.bin", **(options or {})}))
    for name, text in (files or {}).items():
        (folder / name).write_text(text)
    arcs = _node_arc_lengths(segments)
    hang = np.array(case.HANG_OFF, dtype=float)
    out = {"segments": list(segments), "dtM": dtM}
    with initialised(path, list(hang) + [0.0] * 3, [0.0] * 6) as (moordyn, system, wall):
        out["static_wall_time_s"] = wall
        rod = moordyn.GetRod(system, 1)
        force = np.array(moordyn.GetRodForce(rod), dtype=float)
        out["force"], out["moment"] = force[:3], force[3:]
        out["curvature_peak"] = _curvature_peak(moordyn, system, arcs)
        out["hang_off_curvature"] = moordyn.GetLineNodeCurv(moordyn.GetLine(system, 3), segments[-1])
        if duration:
            times = dt_out * np.arange(int(round(duration / dt_out)) + 1)
            positions = np.array([motion(t) for t in times])
            velocities = np.diff(positions, axis=0) / dt_out
            kept = times[::every]
            forces, peaks = np.zeros((len(kept), 6)), np.zeros(len(kept))
            forces[0], peaks[0] = force, out["curvature_peak"][0]
            stepping = 0.0
            for k in range(1, len(times)):
                x, v = list(positions[k - 1]) + [0.0] * 3, list(velocities[k - 1]) + [0.0] * 3
                begin = time.perf_counter()
                moordyn.Step(system, x, v, float(times[k - 1]), float(dt_out))
                stepping += time.perf_counter() - begin
                if k % every == 0:
                    forces[k // every] = np.array(moordyn.GetRodForce(rod), dtype=float)
                    peaks[k // every] = _curvature_peak(moordyn, system, arcs)[0]
            out["run_wall_time_s"] = stepping
            out.update(times=kept, run_force=forces[:, :3], run_moment=forces[:, 3:], run_peak=peaks)
    return out
