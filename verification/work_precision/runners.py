"""The runs of verification/work_precision in this process: cablefem on the flat flume scene (the
warm-up and the profile), MoorDyn-C with its time in ``moordyn.Step`` clocked, its stable time
steps per segment count."""

import cProfile
import contextlib
import io
import pstats
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from cablefem.model.builtin import flume_scene, table5_chain

from validation.moordyn.inputs import FLUME_FILE_SEGMENTS, FLUME_LENGTH
from validation.moordyn.runners import COUPLING_DT, run_moordyn_case
from verification.work_precision.runs import CablefemSettings, run_cablefem_scene

MOORDYN_FILE = Path(__file__).resolve().parents[2] / "validation" / "moordyn" / "inputs" / "flume_flat.dat"
#: study name -> cablefem.model.builtin motion name
MOTIONS = {"slow-surge": "quasi-static", "snap": "dynamic"}

#: MoorDyn time steps tried: divisors of the coupling step, so that every substep has the same dtM
DTM_DIVISORS = (1, 2, 4, 5, 8, 10, 16, 20, 25, 32, 40, 50, 64, 80, 100, 125, 160, 200)


@dataclass(frozen=True)
class MoordynSettings:
    """One MoorDyn run: segments and dtM [s]."""

    segments: int
    dtM: float

    def label(self):
        return f"{self.segments} segments, dtM {self.dtM:.3g}"


def run_cablefem(motion, duration, settings):
    """cablefem on the flat flume scene with ``settings`` (``runs.run_cablefem_scene``: t, tension,
    wall time and counters, or ``failed``); for the warm-up and the profile, in this process."""
    s = settings
    scene = flume_scene("flat", MOTIONS[motion], s.elements, s.order, duration, s.dt)
    scene.solver = replace(scene.solver, integrator=s.integrator, adaptive=s.adaptive,
                           error_tolerance=s.error_tolerance, rho_inf=s.rho_inf, tolerance=s.tolerance,
                           newton=s.newton)
    return run_cablefem_scene(scene)


@contextlib.contextmanager
def moordyn_step_clock():
    """Inside the block, ``moordyn.Step`` adds the seconds it spends to the yielded list's item 0."""
    import moordyn

    step = moordyn.Step
    spent = [0.0]

    def timed(*args):
        begin = time.perf_counter()
        try:
            return step(*args)
        finally:
            spent[0] += time.perf_counter() - begin

    moordyn.Step = timed
    try:
        yield spent
    finally:
        moordyn.Step = step


def run_moordyn(motion, duration, settings, tension_limit=np.inf, initial_condition=False):
    """MoorDyn-C on the flat flume file with ``settings``, its initial-condition solve skipped
    (with ``initial_condition``: the file's, threshIC 1e-5): dict of t (n,) [s],
    tension (n,) [N] on the fairlead point (end-node inertia subtracted: the force cablefem
    reports), tension_raw (MoorDyn's own), wall_time_s (Init + inside Step), peer_wall_time_s
    (the peer's whole loop), or {"stable": False} when MoorDyn fails, returns a non-finite
    tension or one above ``tension_limit`` [N]."""
    scene = flume_scene("flat", MOTIONS[motion])
    factor = settings.segments / FLUME_FILE_SEGMENTS
    with moordyn_step_clock() as spent:
        try:
            result = run_moordyn_case(MOORDYN_FILE, scene, duration,
                                      {"segments": factor, "dtM": settings.dtM, "ic_dtM": None},
                                      options={} if initial_condition else {"TmaxIC": 0.0})
        except Exception:  # MoorDyn raises on NaN node positions
            return {"stable": False, "wall_time_s": spent[0]}
    tension = np.linalg.norm(result["forces_on_point"][:, 0], axis=1)
    stable = bool(np.all(np.isfinite(tension)) and tension.max() <= tension_limit)
    own = result["init_time_s"] + spent[0]
    # t = 0 dropped: with its IC skipped MoorDyn reports no force before its first step
    return {"stable": stable, "t": result["t"][1:], "tension": tension[1:],
            "tension_raw": result["tensions"][1:, 0], "wall_time_s": own,
            "peer_wall_time_s": result["wall_time_s"]}


def moordyn_candidates(segments):
    """dtM [s] to try for ``segments``, largest first: the coupling step's divisors below twice
    the time an axial wave takes to cross a segment."""
    chain = table5_chain()
    crossing = FLUME_LENGTH / segments / np.sqrt(chain.EA / chain.mass)
    return [COUPLING_DT / k for k in DTM_DIVISORS if COUPLING_DT / k <= 2.0 * crossing]


def warm_up():
    """A few steps of every element order and of MoorDyn in this process (where MoorDyn's timed runs
    and the profile run), so that numba's compile (cached on disk after the first run ever) and
    first-call costs stay out of the timings; the Dask workers warm themselves (cablefem.sweeps)."""
    for order in (1, 2, 3):
        run_cablefem("snap", 0.1, CablefemSettings(order, 4, 0.05))
    run_moordyn("snap", 0.1, MoordynSettings(20, 0.005))


def profile_run(motion="snap", settings=CablefemSettings(2, 80, 0.01), duration=12.0, top=12):
    """cProfile of one cablefem run: wall time and the functions with the most own time."""
    profiler = cProfile.Profile()
    profiler.enable()
    result = run_cablefem(motion, duration, settings)
    profiler.disable()
    stats = pstats.Stats(profiler, stream=io.StringIO())
    total = stats.total_tt
    rows = []
    for (path, line, name), (_, calls, own, cumulative, _) in sorted(stats.stats.items(), key=lambda kv: -kv[1][2])[:top]:
        rows.append({"function": f"{Path(path).name}:{line}({name})", "calls": calls, "own_s": own,
                     "cumulative_s": cumulative, "own_fraction": own / total})
    return {"run": settings.label(), "motion": motion, "duration_s": duration, "profiled_s": total,
            "steps": result["steps"], "newton_iterations": result["newton_iterations"], "nfev": result["nfev"],
            "nlu": result["nlu"], "top": rows}
