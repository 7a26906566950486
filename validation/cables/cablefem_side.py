"""cablefem on the lazy wave: its static solve and its run under the hang-off's motion, with the same
outputs as ``moordyn_side``: the force (3,) the cable exerts on the hang-off, the clamp's moment (3,)
and the curvature peak farther than ``moordyn_side.CLEAR`` from the hang-off
(``cablefem.runs.curvature.curvature_peak``; MoorDyn reads its node curvatures there)."""

import time

import numpy as np

from cablefem.fem import clamp
from cablefem.fem.system import build_system
from cablefem.runs.curvature import curvature_peak
from cablefem.statics.solve import solve_static
from validation.cables import case
from validation.cables.moordyn_side import CLEAR

WITHIN = (0.0, case.LENGTH - CLEAR)  # where the curvature peak is looked for


def statics(scene):
    """The static solve of the scene's cable: (system, X, a dict of the hang-off force, the clamp's moment,
    the curvature peak (value, arc length), the wall time [s] and Newton's iterations)."""
    system = build_system(scene, scene.lines[0], dynamic=False)
    begin = time.perf_counter()
    result = solve_static(system)
    wall = time.perf_counter() - begin
    force = -system.residual(result.X)[system.fem.fairlead_dof]
    return system, result.X, {"force": force, "moment": clamp.reaction_moments(system, result.X)[1],
                              "curvature_peak": curvature_peak(system, result.X, WITHIN),
                              "static_wall_time_s": wall, "iterations": result.iterations}


def run(scene, duration, dt_out=0.05, dt=None, integrator="generalized-alpha", **options):
    """The static solve and a run of ``duration`` [s] with the scene's motion (step dt [s], a divisor
    of ``dt_out``, default ``dt_out``), the outputs of ``statics`` and at every ``dt_out``: times (m,),
    the hang-off force (m, 3), the clamp's moment (m, 3), the curvature peak (m,) and the least strain
    along the line (m,) (< 0: a part pushes, as a line with EI does and MoorDyn's lines do not); the
    wall time [s] of the march calls (the outputs read between them not counted)."""
    from cablefem.dynamics.registry import INTEGRATORS
    from cablefem.dynamics.registry import integrator_options
    from cablefem.model.network import boundary_path

    system, X, out = statics(scene)
    dynamic = build_system(scene, scene.lines[0], dynamic=True, fem=system.fem)
    cls = INTEGRATORS[integrator]
    settings = {**integrator_options(scene.solver, cls.name), **options}
    integ = cls(dynamic, X, boundary_path(scene, scene.lines[0]), dt=dt or dt_out, **settings)
    times = dt_out * np.arange(int(round(duration / dt_out)) + 1)
    forces, moments, peaks = np.zeros((len(times), 3)), np.zeros((len(times), 3)), np.zeros(len(times))
    strain = np.full(len(times), float(np.min(system.tension_strain(X))))  # the least, along the line
    forces[0], moments[0], peaks[0] = out["force"], out["moment"], out["curvature_peak"][0]
    substeps = max(1, int(round(dt_out / (dt or dt_out))))
    stepping = 0.0
    for k in range(1, len(times)):
        begin = time.perf_counter()
        integ.march(times[k - 1] + (times[k] - times[k - 1]) * np.arange(1, substeps + 1) / substeps)
        stepping += time.perf_counter() - begin
        forces[k] = integ.reactions()[0]
        moments[k] = integ.clamp_moments()[1]
        peaks[k] = curvature_peak(dynamic, integ.X, WITHIN)[0]
        strain[k] = float(np.min(dynamic.tension_strain(integ.X)))
    out.update(run_wall_time_s=stepping, times=times, run_force=forces, run_moment=moments,
               run_peak=peaks, run_least_strain=strain, steps=integ.steps, newton_iterations=integ.newton_iterations)
    return out
