"""Speed against one common reference with seabed friction (issue 16, part 3): ``common.py``'s
study on the flume chain with the friction of validation/moordyn and the work-precision study.

Friction as there: isotropic Coulomb, mu = 0.3, saturating at 0.01 m/s. cablefem: the flume
scene's own friction (``flume_scene``); MoorDyn: the flume file's FrictionCoefficient 0.3 and
FricDamp, scaled with the segment count (``validation.moordyn.runners.run_moordyn_case``) so that
a resting node saturates at 0.01 m/s at every resolution. MoorDyn's friction acts in the
horizontal plane, cablefem's in the seabed's tangent plane: on the flat flume they coincide.
Otherwise aligned as ``validation.moordyn_aligned`` (MoorDyn-C's damping law in cablefem, IC solve
skipped, end-node inertia subtracted).
"""

from dataclasses import replace

import numpy as np

from cablefem.model.builtin import flume_scene
from validation.moordyn.inputs import FLUME_FILE_SEGMENTS
from validation.moordyn.runners import COUPLING_DT, run_moordyn_case
from validation.moordyn_aligned.run import DURATION, FINE_COUPLING, MOORDYN_FILE, MOTIONS, _cached, aligned_scene


def friction_scene(motion, order, elements, dt, duration=None, tolerance=1e-8):
    """The aligned flume scene (MoorDyn-C's damping law) with the flume scene's seabed friction."""
    scene = aligned_scene(motion, order, elements, dt, duration, tolerance)
    return replace(scene, friction=flume_scene("flat", MOTIONS[motion]).friction)


def moordyn_friction_series(motion, segments, dtM, coupling=COUPLING_DT, duration=None):
    """MoorDyn-C with friction, IC solve skipped: dict of t (n,) [s] and tension (n,) [N] on the
    fairlead point (end-node inertia subtracted), and the peer's wall time [s]."""
    scene = flume_scene("flat", MOTIONS[motion])
    run = run_moordyn_case(MOORDYN_FILE, scene, duration or DURATION[motion],
                           {"segments": segments / FLUME_FILE_SEGMENTS, "dtM": dtM, "ic_dtM": None},
                           options={"TmaxIC": 0.0}, coupling_dt=coupling)
    # t = 0 dropped: with its IC skipped MoorDyn reports no force before its first step
    return {"t": run["t"][1:], "tension": np.linalg.norm(run["forces_on_point"][1:, 0], axis=1),
            "wall": run["wall_time_s"]}


def moordyn_friction(motion, segments, dtM, coupling=COUPLING_DT, cache=None):
    """``moordyn_friction_series``, kept in ``cache`` (a folder, or None) under its settings."""
    settings = dict(code="md", motion=motion, N=segments, dtM=dtM, friction=True, coupling=coupling,
                    options={}, scheme=None, duration=DURATION[motion])
    return _cached(cache, settings, lambda: moordyn_friction_series(motion, segments, dtM, coupling))


def cablefem_friction_series(motion, order, elements, dt, tolerance=1e-8, duration=None):
    """cablefem BDF2 on ``friction_scene``: dict of t (n,) [s], tension (n,) [N] at the fairlead,
    wall [s] (statics, set-up and steps)."""
    from verification.work_precision.runs import run_cablefem_scene

    run = run_cablefem_scene(friction_scene(motion, order, elements, dt, duration, tolerance))
    if "failed" in run:
        raise RuntimeError(run["failed"])
    return {"t": run["t"], "tension": run["tension"], "wall": run["wall_time_s"]}


def cablefem_friction(motion, order, elements, dt, tolerance=1e-8, cache=None):
    """``cablefem_friction_series``, kept in ``cache`` (a folder, or None) under its settings."""
    settings = dict(code="cf", motion=motion, order=order, elements=elements, dt=dt, friction=True, slack=True,
                    tol=tolerance, newton="full", duration=DURATION[motion], variant=None)
    return _cached(cache, settings, lambda: cablefem_friction_series(motion, order, elements, dt, tolerance))


#: the finest run of each code with friction: MoorDyn (segments, dtM, coupling), cablefem (order,
#: elements, dt, Newton tolerance); the frictionless study's settings
REFERENCES_FRICTION = {"snap": {"moordyn": (1280, 2e-5, COUPLING_DT), "cablefem": (1, 640, 0.000625, 1e-8)},
                       "slow": {"moordyn": (640, 1e-4, FINE_COUPLING), "cablefem": (1, 320, 0.0025, 1e-8)}}
#: cablefem's rows (``common.Row``'s fields: order, elements, dt, Newton tolerance[, integrator,
#: rho_inf]): the work-precision study's Pareto rows (which have friction), the frictionless common
#: study's and finer ones
CABLEFEM_ROWS_FRICTION = {
    "snap": [(1, 14, 0.16, 1e-4), (2, 7, 0.16, 1e-4), (2, 10, 0.16, 1e-4), (3, 7, 0.16, 1e-4), (3, 14, 0.16, 1e-4),
             (1, 40, 0.16, 1e-4), (1, 80, 0.08, 1e-4), (2, 40, 0.08, 1e-4), (1, 160, 0.08, 1e-4),
             (1, 160, 0.04, 1e-4), (1, 160, 0.02, 1e-4), (1, 226, 0.04, 1e-4), (1, 226, 0.02, 1e-4),
             (1, 320, 0.04, 1e-4), (2, 113, 0.02, 1e-4), (2, 160, 0.02, 1e-4), (3, 57, 0.04, 1e-4),
             (3, 80, 0.02, 1e-4), (1, 320, 0.02, 1e-4), (1, 320, 0.01, 1e-4), (2, 160, 0.01, 1e-4),
             (1, 640, 0.005, 1e-4)],
    "slow": [(1, 14, 0.17, 1e-4), (2, 14, 0.17, 1e-4), (1, 28, 0.17, 1e-4), (1, 57, 0.085, 1e-4),
             (2, 28, 0.085, 1e-4), (2, 57, 0.04, 1e-4), (1, 80, 0.04, 1e-4), (1, 113, 0.04, 1e-4),
             (2, 40, 0.04, 1e-4), (2, 80, 0.04, 1e-4), (1, 160, 0.04, 1e-4), (1, 160, 0.02, 1e-4),
             (2, 57, 0.02, 1e-4), (2, 80, 0.02, 1e-4), (1, 320, 0.01, 1e-4), (2, 80, 0.01, 1e-4),
             (2, 160, 0.01, 1e-4), (2, 80, 0.005, 1e-4),
             # with friction the mesh decides: P1 x 90-100 at dt 0.06 for MoorDyn's 160 segments
             (1, 90, 0.06, 1e-4), (1, 100, 0.06, 1e-4), (1, 113, 0.085, 1e-4, "generalized-alpha", 0.9)]}
