"""Both codes' runs of validation/moordyn: the settings per case, MoorDyn through ``peer`` under the
scene's motion, cablefem's statics and steps (refined, with its switches), and the points' order."""

import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from cablefem.dynamics.registry import INTEGRATORS
from cablefem.errors import ConvergenceError
from cablefem.model.line import Line
from cablefem.loads.added_mass import AddedMass
from cablefem.loads.drag import Drag
from cablefem.model.motion import fairlead_motion
from cablefem.model.network import boundary_path
from cablefem.fem.system import build_system
from cablefem.statics.scene import start_states
from cablefem.statics.solve import solve_static

from validation.moordyn import peer
from validation.moordyn.switches import PerUnstretchedLength, VerticalSeabed

#: per case family: MoorDyn NumSegs factor over the file (flume: 40 segments of 15.9 m in the
#: file; housner: 20 + 40 segments of 25 m) and dtM [s], the time step of MoorDyn's
#: initial-condition solve [s] (its stable value falls as 1 / segments^2 where BA dominates:
#: housner, beta = 0.01 s), cablefem elements factor and dt [s], the periods simulated after the
#: one-period ramp, and the convergence check: both codes rerun at half the resolution in space
#: and time ("coarse"). Its change bounds the reference's error for any order >= 1 (README,
#: "Convergence"); a finer check would cost ~6 min per flume case in MoorDyn alone.
SETTINGS = {
    "full": {
        "flume-quasi-static": {"segments": 4, "dtM": 1e-4, "ic_dtM": 4e-4, "elements": 4, "dt": 0.01, "periods": 3,
                               "check": "coarse"},
        "flume-dynamic": {"segments": 4, "dtM": 1e-4, "ic_dtM": 4e-4, "elements": 4, "dt": 0.005, "periods": 5,
                          "check": "coarse"},
        "housner": {"segments": 2, "dtM": 2.5e-4, "ic_dtM": 1e-3, "elements": 2, "dt": 0.005, "periods": 3,
                    "check": "coarse"},
    },
    "fast": {
        "flume-quasi-static": {"segments": 1, "dtM": 4e-4, "ic_dtM": 4e-4, "elements": 1, "dt": 0.05, "periods": 1},
        "housner": {"segments": 1, "dtM": 1e-3, "ic_dtM": 4e-3, "elements": 1, "dt": 0.05, "periods": 1},
    },
}
#: cases whose convergence is checked in the full study (every case)
CONVERGENCE_CASES = ("flume-quasi-static", "flume-dynamic", "housner-flat", "housner-upslope", "housner-downslope",
                     "housner-sideslope")
COUPLING_DT = 0.01  # s between MoorDyn coupling calls (and cablefem samples)
WINDOW_PERIODS = 2  # differences are taken over the last two periods (the last one in --fast)


def settings_for(case, fast):
    """The settings dict of ``case`` (see SETTINGS)."""
    table = SETTINGS["fast" if fast else "full"]
    return dict(table[case] if case in table else table["housner"])


def moordyn_motion(scene, points):
    """``motion(t)`` for the peer: every coupled point (k, 3) [m] moved rigidly by the scene's motion."""
    def motion(t):
        d, v, _ = fairlead_motion(scene.motion, t)
        return points + d, np.broadcast_to(v, points.shape)
    return motion


def run_moordyn_case(path, scene, duration, settings, options=None, initial_state=None, coupling_dt=COUPLING_DT,
                     probe=None):
    """MoorDyn on ``path`` with the scene's motion, coupled every ``coupling_dt`` [s]: dict of t (n,),
    forces (n, k, 3) [N] (the peer's, end-node inertia not subtracted), forces_on_point (n, k, 3)
    (end-node inertia subtracted), wall times [s], the coupled points' positions (k, 3), and the
    ``probe``'s values (``peer.run_moordyn``)."""
    text = Path(path).read_text()
    counts = peer.line_segments(text)
    segments = {line_id: n * settings["segments"] for line_id, n in counts.items()}
    options = dict(options or {})
    fric_damp = peer.option_value(text, "FricDamp")
    if fric_damp is not None and "FricDamp" not in options:
        # a node stands for UnstrLen / NumSegs: keep the friction ramp's saturation velocity
        options["FricDamp"] = float(fric_damp) / settings["segments"]
    _, points = peer.coupled_points(path)
    result = peer.run_moordyn(path, moordyn_motion(scene, points), duration, coupling_dt,
                              dtM=settings["dtM"], segments=segments, options=options,
                              ic_dtM=settings["ic_dtM"], initial_state=initial_state, probe=probe)
    acceleration = np.array([fairlead_motion(scene.motion, t)[2] for t in result["t"]])
    result["forces_on_point"] = result["forces"] - np.einsum("nkab,nb->nka", result["end_mass"], acceleration)
    result["points"] = points
    return result


def refined(scene, factor):
    """The scene with every segment's element count times ``factor`` (all else of each line and
    segment kept: a SYROPE segment's initial condition, ends, joints)."""
    lines = [replace(line, segments=[replace(seg, elements=int(seg.elements * factor)) for seg in line.segments])
             for line in scene.lines]
    return replace(scene, lines=lines)


def run_cablefem_case(scene, duration, dt, hydro_per_unstretched=False, lumped=False, retries=2):
    """cablefem's BDF2 on ``scene`` (statics at t = 0, then steps of dt [s]): dict of t (n,),
    forces (n, lines, 3) [N] on the fairleads, wall_time_s, init_time_s, newton_iterations, dt
    as run, ``failures`` (messages) and ``start`` (how the statics converged). A run whose Newton
    fails even after the integrator's own step halving is rerun from the start with dt / 2, up to
    ``retries`` times, and says so (README, "Problems found")."""
    start = time.perf_counter()
    states, how = static_start(scene)
    initialised = time.perf_counter()
    failures = []
    while True:
        try:
            result = _cablefem_steps(scene, states, duration, dt, hydro_per_unstretched, lumped)
        except ConvergenceError as error:
            if len(failures) >= retries:
                raise
            failures.append(f"dt = {dt:g} s: {error}")
            dt /= 2
            continue
        result.update(failures=failures, start=how, init_time_s=initialised - start,
                      wall_time_s=time.perf_counter() - start)
        return result


def static_start(scene):
    """Static equilibrium of every line at t = 0 (``cablefem.statics.scene.start_states``) and how it was
    reached. With MoorDyn's vertical contact, a line whose Newton fails from the catenary guess
    (the slack line 2 on the side slope, at 12.5 m elements) is solved again from its equilibrium
    with cablefem's own contact: a continuation, same equations (README, "Problems found")."""
    try:
        return start_states(scene)[0], "catenary guess"
    except ConvergenceError:
        if not isinstance(scene.seabed, VerticalSeabed):
            raise
    states, how = [], []
    offset = fairlead_motion(scene.motion, 0.0)[0]
    tolerance, cap = scene.solver.tolerance, scene.solver.max_iterations
    for line in scene.lines:
        moved = Line(line.name, line.anchor, line.fairlead + offset, line.segments, line.order)
        try:
            states.append(solve_static(build_system(scene, moved, dynamic=False), tolerance=tolerance,
                                       max_iterations=cap).X)
            how.append(f"{line.name}: catenary guess")
        except ConvergenceError:
            own = solve_static(build_system(replace(scene, seabed=scene.seabed.inner), moved, dynamic=False),
                               tolerance=tolerance, max_iterations=cap).X
            states.append(solve_static(build_system(scene, moved, dynamic=False), X0=own, tolerance=tolerance,
                                       max_iterations=cap).X)
            how.append(f"{line.name}: from its equilibrium with cablefem's contact")
    return states, "; ".join(how)


def _cablefem_steps(scene, states, duration, dt, hydro_per_unstretched, lumped):
    """Step every line from ``states`` by dt [s] up to ``duration`` [s]; the run's dict."""
    integrators = []
    for line, X0 in zip(scene.lines, states):
        system = build_system(scene, line)
        system.reset_history(X0)  # a load's history from its start (a SYROPE rope's initial condition)
        if hydro_per_unstretched:
            system.loads = [PerUnstretchedLength(load) if isinstance(load, (Drag, AddedMass)) else load
                            for load in system.loads]
        integrators.append(INTEGRATORS[scene.solver.integrator](
            system, X0, boundary_path(scene, line), dt=dt, tolerance=scene.solver.tolerance,
            newton="full", lumped=lumped,  # one Newton for the compiled and the numpy path
            # wrapped loads have no compiled face: the numpy path
            compiled=not hydro_per_unstretched))
    steps = int(round(duration / dt))
    t = np.arange(steps + 1) * dt
    forces = np.empty((steps + 1, len(integrators), 3))
    forces[0] = [integ.reactions()[0] for integ in integrators]
    for n in range(steps):
        for integ in integrators:
            integ.step(dt)
        forces[n + 1] = [integ.reactions()[0] for integ in integrators]
    return {"t": t, "forces": forces, "tensions": np.linalg.norm(forces, axis=2),
            "newton_iterations": sum(i.newton_iterations for i in integrators),
            "rejected_steps": sum(i.rejected for i in integrators), "dt": dt,
            "steps": steps, "line_names": [line.name for line in scene.lines]}


def point_order(scene, points):
    """Index of the cablefem line (scene order) whose fairlead is each coupled point (k, 3)."""
    fairleads = np.array([line.fairlead for line in scene.lines])
    return [int(np.argmin(np.linalg.norm(fairleads - p, axis=1))) for p in points]
