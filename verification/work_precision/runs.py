"""The work-precision study's cablefem runs, on the sweep engine (``cablefem.sweeps``, docs/sweep.md).

The runs are the cases of one sweep file (``sweep.toml``, or ``sweep_fast.toml`` for ``--fast``),
tagged by motion (``tag.motion``: snap | slow-surge) and role (``tag.role``: reference | check |
row | time-order | time-order-reference). Each case runs one of two run kinds defined here, in a
Dask worker: ``series`` (one run) or ``timed_series`` (one run, then the repeats of ``REPEATS``
keeping the least wall time). Both time and record what the study always measured
(``run_cablefem_scene``: statics, set-up and steps, no files written in between) and save the
fairlead tension after every step as the case folder's ``series.npz``. The sweep file runs the
timed rows with ``alone = true``: one at a time, nothing else of the sweep running, so that a
wall time is one run's on an otherwise idle cluster, as before the sweep; the untimed runs
(references, their checks, the time-order runs) run in parallel.
"""

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
SWEEPS = {False: HERE / "sweep.toml", True: HERE / "sweep_fast.toml"}
#: what run_cablefem_scene reports besides the series and the wall time
COUNTERS = ("steps", "rejected", "newton_iterations", "nfev", "nlu")
#: cheap runs are repeated and the least wall time kept (the results are deterministic; only the
#: shared machine's load varies): (wall time below [s], runs)
REPEATS = ((0.2, 5), (1.0, 3), (3.0, 2))


@dataclass(frozen=True)
class CablefemSettings:
    """One cablefem run: element order and count, step dt [s] (the largest step when adaptive),
    integrator, adaptive BDF2 with its local tension error tolerance, generalised-alpha's rho_inf,
    Newton's relative tolerance ([solver] tolerance; the scenes' default is 1e-8) and Newton's
    kind ([solver] newton: "full", or "modified", the LU factors kept across iterations and steps
    while they contract; the scenes' "auto" switches between the two, not swept here)."""

    order: int
    elements: int
    dt: float
    integrator: str = "bdf2"
    adaptive: bool = False
    error_tolerance: float = 3e-4
    rho_inf: float = 0.8
    tolerance: float = 1e-8
    newton: str = "full"

    def label(self):
        kind = {"bdf2": "BDF2", "generalized-alpha": f"gen-a {self.rho_inf:g}"}[self.integrator]
        step = f"adaptive {self.error_tolerance:g} (dt <= {self.dt:g})" if self.adaptive else f"dt {self.dt:g}"
        newton = "" if self.tolerance == 1e-8 else f", Newton tol {self.tolerance:g}"
        modified = ", modified Newton" if self.newton == "modified" else ""
        return f"P{self.order} x {self.elements}, {kind}, {step}{newton}{modified}"


def run_cablefem_scene(scene):
    """cablefem on a one-line ``scene`` with its [solver] settings: dict of t (n,) [s], tension (n,)
    [N] at the fairlead after every step, wall_time_s (statics + set-up + steps) and the counters;
    a run whose Newton fails even at the smallest step has ``failed`` (the message) instead."""
    from cablefem.dynamics.registry import INTEGRATORS
    from cablefem.errors import ConvergenceError
    from cablefem.runs.run import step_times
    from cablefem.model.network import boundary_path
    from cablefem.fem.system import build_system
    from cablefem.statics.scene import start_states
    from cablefem.dynamics.registry import integrator_options

    solver, line = scene.solver, scene.lines[0]
    start = time.perf_counter()
    system = build_system(scene, line)
    (X0,), _ = start_states(scene, systems=[system])
    integ = INTEGRATORS[solver.integrator](system, X0, boundary_path(scene, line), dt=solver.dt,
                                           **integrator_options(solver))
    times, tensions = [integ.t], [np.linalg.norm(integ.reactions()[0])]
    try:
        steps = step_times(integ.t, solver.duration, scene.output.every if solver.adaptive else solver.dt)
        times.extend(steps)
        tensions.extend(np.linalg.norm(integ.march(steps)[:, 0], axis=1))
    except ConvergenceError as error:
        return {"failed": str(error), "wall_time_s": time.perf_counter() - start}
    wall = time.perf_counter() - start
    stats = integ.statistics()
    return {"t": np.array(times), "tension": np.array(tensions), "wall_time_s": wall,
            **{key: stats[key] for key in COUNTERS}}


def least_time(run, repeats=REPEATS):
    """``run()`` (a dict with wall_time_s), repeated per ``repeats``; wall_time_s (and
    peer_wall_time_s) become the least over the repeats, ``repeats`` says how many."""
    result = run()
    count = next((n for limit, n in repeats if result["wall_time_s"] < limit), 1)
    for _ in range(count - 1):
        again = run()
        for key in ("wall_time_s", "peer_wall_time_s"):
            if key in result:
                result[key] = min(result[key], again[key])
    result["repeats"] = count
    return result


def series(scene, folder):
    """Sweep run kind: one run of ``scene`` (``run_cablefem_scene``), its series saved as
    folder/series.npz; the columns solve_wall_time_s [s], repeats (1) and the counters."""
    return _saved(run_cablefem_scene(scene), folder, repeats=1)


def timed_series(scene, folder):
    """Sweep run kind: as ``series``, then ``least_time`` of the run, repeated per ``REPEATS`` (the
    first run, as before the sweep, loads and warms what the repeats then time)."""
    result = run_cablefem_scene(scene)
    if "failed" not in result:
        result = least_time(lambda: run_cablefem_scene(scene))
    return _saved(result, folder, repeats=result.get("repeats", 1))


def _saved(result, folder, repeats):
    from cablefem.errors import ConvergenceError

    if "failed" in result:
        raise ConvergenceError(result["failed"])
    np.savez(Path(folder) / "series.npz", t=result["t"], tension=result["tension"])
    return {"solve_wall_time_s": result["wall_time_s"], "repeats": repeats,
            **{key: int(result[key]) for key in COUNTERS}}


def settings_of(row):
    """The CablefemSettings of a row of the study's sweep table (its parameter columns)."""
    return CablefemSettings(
        order=int(row["lines[*].order"]), elements=int(row["lines[*].segments[*].elements"]),
        dt=float(row["solver.dt"]), integrator=row["solver.integrator"], adaptive=bool(row["solver.adaptive"]),
        error_tolerance=float(row["solver.error_tolerance"]), rho_inf=float(row["solver.rho_inf"]),
        tolerance=float(row["solver.tolerance"]), newton=row["solver.newton"])


def cablefem_runs(fast, runs_dir, client=None, log=print):
    """Every cablefem run of the study: the sweep file of the mode run into ``runs_dir`` (cases done
    there before are read back); {motion: {role: [(CablefemSettings, result)]}} in the file's
    order, a result as ``run_cablefem_scene``'s (series, wall_time_s, counters, repeats) or
    {"failed": message, "wall_time_s": ...}; and each motion's duration [s]."""
    from cablefem.sweeps import run_sweep_file

    table = run_sweep_file(SWEEPS[fast], out=str(runs_dir), client=client)
    facts = table.attrs["sweep"]
    log(f"cablefem: {facts['runs']} runs ({facts['skipped']} done before) in {facts['wall_time_s']:.0f} s, "
        f"{facts['failed']} failed")
    runs, durations = {}, {}
    for row in table.to_dict("records"):
        motion, role = row["tag.motion"], row["tag.role"]
        durations[motion] = float(row["solver.duration"])
        if row["status"] == "ok":
            saved = np.load(Path(runs_dir) / row["dir"] / "series.npz")
            result = {"t": saved["t"], "tension": saved["tension"], "wall_time_s": row["solve_wall_time_s"],
                      "repeats": int(row["repeats"]), **{key: int(row[key]) for key in COUNTERS}}
        else:
            result = {"failed": row["error"], "wall_time_s": row["wall_time_s"]}
        runs.setdefault(motion, {}).setdefault(role, []).append((settings_of(row), result))
    return runs, durations
