"""Both codes' runs of validation/waves: MoorDyn-C on a case's file (``validation.moordyn.peer``, the
fairlead held still, wave_frequencies.txt beside the file), cablefem on the same file read as a
scene, each line's fairlead tension sampled every ``SAMPLE`` s; and the comparison."""

import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from cablefem.dynamics.registry import INTEGRATORS
from cablefem.fem.system import build_system
from cablefem.model.network import boundary_path
from cablefem.statics.scene import start_states
from validation.moordyn import peer
from validation.waves.case import FREQUENCIES

SAMPLE = 0.05  # s between samples (MoorDyn's coupling calls)


def run_moordyn(path, duration, segments_factor=1, dtM=2.5e-4):
    """MoorDyn-C's fairlead tension (n,) [N] at t (n,) with every line's NumSegs times ``segments_factor``."""
    path = Path(path)
    text = path.read_text()
    segments = {line: n * segments_factor for line, n in peer.line_segments(text).items()}
    _, points = peer.coupled_points(path)
    result = peer.run_moordyn(path, lambda t: (points, np.zeros_like(points)), duration, SAMPLE, dtM=dtM,
                              segments=segments, files={"wave_frequencies.txt": FREQUENCIES})
    return {"t": result["t"], "tension": result["tensions"][:, 0], "wall_time_s": result["wall_time_s"],
            "segments": result["segments"]}


def scene_of(path, elements_factor=1, dt=0.01):
    """The case's MoorDyn file read as a cablefem scene on its own mesh (P1 x NumSegs), its elements times ``elements_factor``, generalised-alpha
    steps of dt [s]."""
    from cablefem.io.checks import check_scene
    from cablefem.io.moordyn_input import read_moordyn

    # the file's mesh (MoorDyn's NumSegs as P1 elements), not the P2 one cablefem's defaults give it
    scene = check_scene(read_moordyn(str(path), defaults=False))
    if elements_factor != 1:
        scene = replace(scene, lines=[line.with_elements(sum(s.elements for s in line.segments) * elements_factor)
                                      if len(line.segments) == 1 else _refined(line, elements_factor)
                                      for line in scene.lines])
    return replace(scene, solver=replace(scene.solver, integrator="generalized-alpha", dt=dt, tolerance=1e-8))


def _refined(line, factor):
    return replace(line, segments=tuple(replace(s, elements=s.elements * factor) for s in line.segments))


def run_cablefem(scene, duration, point_fluid_inertia=True):
    """cablefem's fairlead tension (n,) [N] at t (n,) (every SAMPLE s); ``point_fluid_inertia`` False:
    the points without (1 + Ca) rho V a_w, as MoorDyn-C's points have them."""
    start = time.perf_counter()
    line = scene.lines[0]
    system = build_system(scene, line)
    for load in system.loads:
        if not point_fluid_inertia and getattr(load, "name", "") == "points":
            load.fluid = np.zeros_like(load.fluid)
    states, _ = start_states(scene, systems=[system])
    solver = scene.solver
    integ = INTEGRATORS[solver.integrator](system, states[0], boundary_path(scene, line), dt=solver.dt,
                                           tolerance=solver.tolerance, rho_inf=solver.rho_inf)
    steps = np.arange(1, int(round(duration / solver.dt)) + 1) * solver.dt
    forces = integ.march(steps)
    every = int(round(SAMPLE / solver.dt))
    t = np.concatenate(([0.0], steps[every - 1::every]))
    tension = np.concatenate(([np.linalg.norm(-system.residual(states[0])[system.fem.fairlead_dof])],
                              np.linalg.norm(forces[every - 1::every, 0], axis=1)))
    return {"t": t, "tension": tension, "wall_time_s": time.perf_counter() - start,
            "elements": sum(s.elements for s in line.segments), "newton_iterations": integ.newton_iterations}


def compare(reference, other, t_from):
    """Fairlead tension of ``other`` against ``reference`` over t >= t_from [s] (both sampled alike):
    the reference's mean and wave-driven standard deviation [N], the RMS difference as fractions of
    each, the differences of mean, peak and trough over the mean."""
    window = reference["t"] >= t_from - 1e-9
    a = reference["tension"][window]
    b = np.interp(reference["t"][window], other["t"], other["tension"])
    mean, std = float(a.mean()), float(a.std())
    rms = float(np.sqrt(np.mean((b - a) ** 2)))
    return {"mean_N": mean, "std_N": std, "rms_N": rms, "rms_of_std": rms / std, "rms_of_mean": rms / mean,
            "mean_difference": float(b.mean() - mean) / mean, "peak_difference": float(b.max() - a.max()) / mean,
            "trough_difference": float(b.min() - a.min()) / mean}
