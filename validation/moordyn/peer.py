"""MoorDyn-C (PyPI ``moordyn``, v2.7) as a peer: run an input file with prescribed motions of its
coupled points and return the time series of the forces on them.

    result = run_moordyn("mooring.dat", motion, duration=60.0, dt_out=0.01,
                         dtM=1e-4, segments=80)
    result["t"]            # (n,) [s], n = duration / dt_out + 1, t[0] = 0
    result["forces"]       # (n, k, 3) [N], force the lines exert on each coupled point
    result["tensions"]     # (n, k) [N], |forces|
    result["wall_time_s"]  # Init (MoorDyn's static solve) + stepping [s]
    result["end_mass"]     # (n, k, 3, 3) [kg], mass matrix of the line end nodes at each point
    result["initial_state"]  # bytes (moordyn.Serialize) of the state after the initial-condition solve;
                             # run_moordyn(..., initial_state=...) starts another run from it
    result["probes"]       # (n, ...) with probe=f: f(moordyn, system) at every coupling time, e.g. the
                           # position of a free point or the force of a line's anchor node

The force MoorDyn-C returns for a coupled point is the net force on the end nodes of its lines
(tension of the end segments, half-segment weight, drag, seabed), *without* their inertia: the
end node moves with the point, and its mass (structural and added) is left to the caller. The
force the lines exert on a point moving with acceleration a is ``forces - end_mass @ a``; the
difference vanishes as the segments shrink (cablefem's FEM reaction includes the inertia of its
consistent mass row).

``motion(t)`` returns the positions (k, 3) [m] and velocities (k, 3) [m/s] of the file's k
coupled points (POINTS rows attached ``Coupled``/``Vessel``/``Fairlead``, in file order, which
is MoorDyn's order of its coupled degrees of freedom when the file has no bodies or rods).

Coupling. Between two calls of ``moordyn.Step(x, xd, t, dt)`` MoorDyn-C moves a coupled point
along the straight line x + xd (t' - t) (``Point::updateFairlead``). With ``coupling="secant"``
(the default) xd is the secant (x(t + dt_out) - x(t)) / dt_out, so the point follows the
piecewise-linear interpolant of the motion, continuous at every coupling time: its velocity
differs from the true one by O(dt_out^2). With ``coupling="tangent"`` xd is the velocity
``motion`` returns (as OpenFAST passes it); the position then jumps at each coupling time by
~a dt_out^2 / 2, which a stiff chain turns into tension spikes (EA / l times that jump).

Overrides rewrite a copy of the file in a temporary folder (MoorDyn writes its .out and .log
files next to its input, so the caller's folders stay clean): ``dtM`` [s], ``segments``
(NumSegs of every line, or a dict line ID -> NumSegs), ``options`` (dict OPTIONS name -> value,
replaced where the file has it, added otherwise), and a relative ``SeafloorFile`` is made
absolute. MoorDyn prints a progress line per step on file descriptor 1; it is sent to
/dev/null while MoorDyn runs.
"""

import contextlib
import math
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from cablefem.geometry.readers import is_number

COUPLED = ("COUPLED", "VESSEL", "VES", "CPLD", "FAIRLEAD")


@contextlib.contextmanager
def silenced_stdout():
    """Send file descriptor 1 to /dev/null inside the block (MoorDyn's C++ progress lines)."""
    sys.stdout.flush()
    saved = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(devnull)


def _sections(lines):
    """(name, first row index, end row index) of each '---' section of a MoorDyn file's rows."""
    heads = [i for i, row in enumerate(lines) if "---" in row]
    found = []
    for k, i in enumerate(heads):
        title = " ".join(lines[i].replace("-", " ").split()).upper()
        end = heads[k + 1] if k + 1 < len(heads) else len(lines)
        found.append((title, i + 1, end))
    return found


def _section(lines, keyword):
    """(first, end) row indices of the first section whose title holds ``keyword``, or None."""
    for title, first, end in _sections(lines):
        if keyword in title:
            return first, end
    return None


def coupled_points(path):
    """IDs (k,) and positions (k, 3) [m] of the coupled points of a MoorDyn v2 file, in file order."""
    lines = Path(path).read_text().splitlines()
    where = _section(lines, "POINT") or _section(lines, "CONNECTION") or _section(lines, "NODE")
    if where is None:
        raise ValueError(f"{path}: no POINTS section")
    ids, positions = [], []
    for row in lines[where[0]:where[1]]:
        fields = row.split()
        if len(fields) >= 5 and fields[0].isdigit() and fields[1].upper() in COUPLED:
            ids.append(int(fields[0]))
            positions.append([float(v) for v in fields[2:5]])
    return ids, np.array(positions, dtype=float).reshape(-1, 3)


def _lines_section(lines):
    return _section(lines, "LINES") or _section(lines, "LINE LIST") or _section(lines, "LINE PROPERTIES")


def _line_rows(lines):
    """Indices of the data rows of the LINES section (ID LineType AttachA AttachB UnstrLen NumSegs)."""
    where = _lines_section(lines)
    if where is None:
        return []
    return [i for i in range(*where)
            if len(lines[i].split()) >= 6 and is_number(lines[i].split()[4]) and lines[i].split()[5].isdigit()]


def line_segments(text):
    """NumSegs of each line of MoorDyn file text: dict line ID (str) -> int."""
    lines = text.splitlines()
    return {lines[i].split()[0]: int(lines[i].split()[5]) for i in _line_rows(lines)}


def line_ends(text):
    """Line ends of MoorDyn file text: dict point ID -> list of (line ID (int), "A" | "B")."""
    lines = text.splitlines()
    ends = {}
    for i in _line_rows(lines):
        fields = lines[i].split()
        for token, end in ((fields[2], "A"), (fields[3], "B")):
            if token.isdigit():
                ends.setdefault(int(token), []).append((int(fields[0]), end))
    return ends


def option_value(text, name):
    """The value (str) of OPTIONS ``name`` (case-insensitive) in MoorDyn file text, or None."""
    lines = text.splitlines()
    where = _section(lines, "OPTIONS")
    for row in (lines[where[0]:where[1]] if where else []):
        fields = row.split()
        if len(fields) >= 2 and fields[1].lower() == name.lower():
            return fields[0]
    return None


def rewrite_input(text, dtM=None, segments=None, options=None, base_dir="."):
    """MoorDyn file ``text`` with dtM [s], NumSegs (int for every line, or dict line ID -> int) and
    OPTIONS values (dict name -> value) replaced or added, and a relative SeafloorFile made
    absolute against ``base_dir``; returns the new text."""
    lines = text.splitlines()
    settings = dict(options or {})
    if dtM is not None:
        settings["dtM"] = dtM
    if segments is not None:
        for i in _line_rows(lines):
            fields = lines[i].split()
            count = segments if isinstance(segments, int) else segments.get(fields[0], int(fields[5]))
            fields[5] = str(int(count))
            lines[i] = "  ".join(fields)
    where = _section(lines, "OPTIONS")
    if where is None:
        raise ValueError("no OPTIONS section to write the options into")
    first, end = where
    lowered = {name.lower(): name for name in settings}
    for i in range(first, end):
        fields = lines[i].split()
        if len(fields) < 2:
            continue
        name = fields[1].lower()
        if name in lowered:
            lines[i] = f"{_token(settings[lowered.pop(name)]):<22} {fields[1]}"
        elif name == "seafloorfile" and not os.path.isabs(fields[0]):
            lines[i] = f"{os.path.abspath(os.path.join(base_dir, fields[0]))}  SeafloorFile"
    added = [f"{_token(settings[key]):<22} {key}" for key in lowered.values()]
    lines[end:end] = added
    if not any("---" in row for row in lines[end + len(added):]):
        lines.append("--------------------- (MoorDyn 2.7 crashes on a file ending in OPTIONS) ---")
    return "\n".join(lines) + "\n"


def _token(value):
    """An OPTIONS value as MoorDyn reads it: numbers in full precision, text as is."""
    return value if isinstance(value, str) else repr(float(value)) if isinstance(value, float) else str(value)


def run_moordyn(path, motion, duration, dt_out, dtM=None, segments=None, options=None,
                coupling="secant", ic_dtM=None, line_nodes=False, initial_state=None, probe=None, files=None):
    """Run MoorDyn on ``path`` for ``duration`` [s], coupling every ``dt_out`` [s], the coupled
    points following ``motion(t) -> (positions (k, 3), velocities (k, 3))``; returns a dict with
    t (n,), forces (n, k, 3) [N], tensions (n, k) [N], positions (n, k, 3) [m] of the points as
    MoorDyn reports them, end_mass (n, k, 3, 3) [kg], probes (n, ...) (``probe(moordyn, system)``
    returns an array at every coupling time; None without a probe), wall_time_s,
    init_time_s, dtM [s] and segments (dict line ID -> NumSegs) as run, and, with
    ``line_nodes``, the final node positions of every line (list of (N+1, 3) arrays).

    ``ic_dtM`` [s]: the time step of MoorDyn's initial-condition solve (its stationary solver
    steps with dtM, so its cost grows as 1/dtM); the run then steps with dtM (``moordyn.SetDt``).
    The state it stops at depends on the step only within its convergence threshold (threshIC).

    ``initial_state``: bytes of ``moordyn.Serialize`` taken right after the initial-condition solve
    of a run of the same lines and segments (its ``result["initial_state"]``): the run skips its
    own solve (``Init_NoIC``) and starts from that state, e.g. a frictionless equilibrium for a run
    with friction, whose relaxation would stop wherever friction arrests it.

    ``files``: {name: text} of data files MoorDyn-C reads from the input file's folder (a WaveKin's
    wave_frequencies.txt, ...), written beside the working copy."""
    import moordyn

    if coupling not in ("secant", "tangent"):
        raise ValueError(f"coupling must be 'secant' or 'tangent', got {coupling!r}")
    path = Path(path).resolve()
    ids, _ = coupled_points(path)
    k = len(ids)
    steps = int(round(duration / dt_out))
    if steps < 0 or not math.isclose(steps * dt_out, duration, rel_tol=1e-9, abs_tol=1e-12):
        raise ValueError(f"duration {duration} s is not a whole number of dt_out = {dt_out} s")
    text = rewrite_input(path.read_text(), dtM, segments, options, base_dir=path.parent)
    dtM = None if option_value(text, "dtM") is None else float(option_value(text, "dtM"))
    if ic_dtM is not None:
        text = rewrite_input(text, ic_dtM)
    t = np.arange(steps + 1) * dt_out
    forces = np.empty((steps + 1, k, 3))
    positions = np.empty((steps + 1, k, 3))
    end_mass = np.zeros((steps + 1, k, 3, 3))
    ends = line_ends(text)
    with tempfile.TemporaryDirectory(prefix="moordyn-") as folder:
        work = Path(folder) / path.name
        work.write_text(text)
        for name, content in (files or {}).items():
            (Path(folder) / name).write_text(content)
        x, v = (np.asarray(a, dtype=float).reshape(k, 3) for a in motion(0.0))
        with silenced_stdout():
            start = time.perf_counter()
            system = moordyn.Create(str(work))
            try:
                _initialise(moordyn, system, x, v, initial_state, dtM if ic_dtM is not None else None)
                state = moordyn.Serialize(system)
                initialised = finished = time.perf_counter()
                points = [moordyn.GetPoint(system, i) for i in ids]
                attached = _end_nodes(moordyn, system, ids, ends)
                forces[0] = [moordyn.GetPointForce(p) for p in points]
                probes = None if probe is None else [np.asarray(probe(moordyn, system), dtype=float)]
                end_mass[0] = _end_masses(moordyn, attached)
                positions[0] = x
                for n in range(steps):
                    x_next, v_next = (np.asarray(a, dtype=float).reshape(k, 3) for a in motion(t[n + 1]))
                    rate = (x_next - x) / dt_out if coupling == "secant" else v
                    forces[n + 1] = np.reshape(moordyn.Step(system, x.ravel(), rate.ravel(), t[n], dt_out), (k, 3))
                    end_mass[n + 1] = _end_masses(moordyn, attached)
                    positions[n + 1] = [moordyn.GetPointPos(p) for p in points]  # where MoorDyn put them
                    if probe is not None:
                        probes.append(np.asarray(probe(moordyn, system), dtype=float))
                    x, v = x_next, v_next
                finished = time.perf_counter()
                nodes = _line_nodes(moordyn, system) if line_nodes else None
            finally:
                moordyn.Close(system)
    result = {"t": t, "forces": forces, "tensions": np.linalg.norm(forces, axis=2), "positions": positions,
              "end_mass": end_mass, "probes": None if probe is None else np.array(probes),
              "wall_time_s": finished - start, "init_time_s": initialised - start,
              "dtM": dtM, "ic_dtM": ic_dtM, "initial_state": state,
              "segments": line_segments(text)}
    if line_nodes:
        result["line_nodes"] = nodes
    return result



def _initialise(moordyn, system, x, v, initial_state=None, dtM=None):
    """MoorDyn's initial condition with the coupled points at x, velocities v (k, 3): its own
    solve, or ``initial_state`` (bytes of ``moordyn.Serialize``) restored; then the step dtM [s]
    when given."""
    if initial_state is None:
        moordyn.Init(system, x.ravel(), v.ravel())
    else:
        moordyn.Init_NoIC(system, x.ravel(), v.ravel())
        moordyn.Deserialize(system, initial_state)
    if dtM is not None:
        moordyn.SetDt(system, dtM)


def _end_nodes(moordyn, system, ids, ends):
    """Per coupled point ``ids``: [(line handle, end node index)] of the line ends ``ends`` attached to it."""
    attached = []
    for i in ids:
        handles = []
        for number, end in ends.get(i, []):
            line = moordyn.GetLine(system, number)
            handles.append((line, 0 if end == "A" else moordyn.GetLineNumberNodes(line) - 1))
        attached.append(handles)
    return attached


def _end_masses(moordyn, attached):
    """Per coupled point: the mass matrices (3, 3) [kg] of the line end nodes attached to it, summed."""
    return [sum((np.array(moordyn.GetLineNodeM(line, node)) for line, node in handles), np.zeros((3, 3)))
            for handles in attached]


def _line_nodes(moordyn, system):
    """Every line's node positions, a list of (N+1, 3) arrays [m]."""
    nodes = []
    for i in range(1, moordyn.GetNumberLines(system) + 1):
        line = moordyn.GetLine(system, i)
        nodes.append(np.array([moordyn.GetLineNodePos(line, j) for j in range(moordyn.GetLineNumberNodes(line))]))
    return nodes


def static_forces(path, positions=None, dtM=None, segments=None, options=None):
    """Forces (k, 3) [N] on the coupled points after MoorDyn's initial-condition solve, with the
    points at ``positions`` (k, 3) [m] (default: as in the file)."""
    _, start = coupled_points(path)
    x = start if positions is None else np.asarray(positions, dtype=float).reshape(-1, 3)
    result = run_moordyn(path, lambda t: (x, np.zeros_like(x)), duration=0.0, dt_out=1.0, dtM=dtM,
                         segments=segments, options=options)
    return result["forces"][0]
