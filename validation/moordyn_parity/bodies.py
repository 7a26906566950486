"""The body cases of validation/moordyn_parity: MoorDyn-C's side of a coupled body (its points'
forces and the body's force and moment), and each code's run of a free body driven through its anchor.

MoorDyn-C moves a coupled body along x + xd (t' - t) between coupling calls (``Body::updateFairlead``,
the six components x, y, z, roll, pitch, yaw in radians, ``XYZQuat::fromVec6``); here xd is the secant
of the scene's body motion over the coupling step, as ``peer`` moves coupled points. The force on each
of the body's points is ``GetPointForce`` (the lines' end nodes: tension, half-segment weight, drag,
seabed; ``Point::doRHS``) less the end nodes' mass (``GetPointM``) times the point's acceleration
(``cablefem.model.network.BodyPointPath``): the force cablefem's fairlead reaction gives. The body's
force and moment (about its reference point) are these forces summed, in both codes alike.
"""

import tempfile
import time
from pathlib import Path

import numpy as np

from cablefem.model.motion import body_motion
from cablefem.model.network import BodyPointPath
from validation.moordyn import peer
from validation.moordyn.runners import COUPLING_DT


def body_points(scene, body):
    """The names of the points of ``body`` (scene order) and the MoorDyn point IDs they come from."""
    names = [name for name, point in scene.points.items() if point.body == body]
    return names, [int(name.removeprefix("point")) for name in names]


def body_pose(body, times):
    """Poses (n, 6) and their rates (n, 6) of a coupled ``body`` at ``times`` (n,): rest plus motion."""
    d, v, _ = body_motion(body.motion, np.asarray(times, dtype=float))
    return np.concatenate([body.position, body.rotation]) + d, v


def point_kinematics(scene, names, times):
    """Positions and accelerations (n, k, 3) of the body points ``names`` at ``times`` (n,)."""
    states = [BodyPointPath(scene.bodies[scene.points[name].body], scene.points[name].position).states(times)
              for name in names]
    return np.stack([x for x, _, _ in states], axis=1), np.stack([a for _, _, a in states], axis=1)


def body_loads(scene, body, names, times, forces):
    """The force (n, 3) [N] and moment (n, 3) [N m] about the reference point of ``body`` from the
    forces (n, k, 3) on its points ``names`` at ``times`` (n,)."""
    positions, _ = point_kinematics(scene, names, times)
    pose, _ = body_pose(scene.bodies[body], times)
    arms = positions - pose[:, None, :3]
    return forces.sum(axis=1), np.cross(arms, forces).sum(axis=1)


def run_moordyn_body(path, scene, body, duration, settings, coupling_dt=COUPLING_DT):
    """MoorDyn-C on ``path``, its one coupled body ``body`` following the scene's body motion: dict of
    t (n,), forces_on_point (n, k, 3) [N] on the body's points (``body_points`` order, end-node inertia
    subtracted), body_force and body_moment (n, 3), the body's six-component force MoorDyn-C returns
    (n, 6: its inertia term from the coupling's velocity differences), wall_time_s and init_time_s.
    ``settings``: segments (factor over the file's NumSegs), dtM, ic_dtM [s] as
    ``validation.moordyn.runners.run_moordyn_case`` takes them."""
    import moordyn

    path = Path(path).resolve()
    text = path.read_text()
    segments = {line: n * settings["segments"] for line, n in peer.line_segments(text).items()}
    text = peer.rewrite_input(text, settings["ic_dtM"], segments, base_dir=path.parent)
    names, ids = body_points(scene, body)
    steps = round(duration / coupling_dt)
    t = np.arange(steps + 1) * coupling_dt
    poses, _ = body_pose(scene.bodies[body], t)
    forces = np.empty((steps + 1, len(ids), 3))
    masses = np.empty((steps + 1, len(ids), 3, 3))
    returned = np.zeros((steps + 1, 6))
    with tempfile.TemporaryDirectory(prefix="parity-body-") as folder:
        work = Path(folder) / path.name
        work.write_text(text)
        with peer.silenced_stdout():
            start = time.perf_counter()
            system = moordyn.Create(str(work))
            try:
                moordyn.Init(system, poses[0], np.zeros(6))
                moordyn.SetDt(system, settings["dtM"])
                initialised = time.perf_counter()
                points = [moordyn.GetPoint(system, i) for i in ids]
                for n in range(steps + 1):
                    if n:
                        rate = (poses[n] - poses[n - 1]) / coupling_dt
                        returned[n] = moordyn.Step(system, poses[n - 1], rate, t[n - 1], coupling_dt)
                    forces[n] = [moordyn.GetPointForce(p) for p in points]
                    masses[n] = [moordyn.GetPointM(p) for p in points]
                finished = time.perf_counter()
            finally:
                moordyn.Close(system)
    _, accelerations = point_kinematics(scene, names, t)
    on_points = forces - np.einsum("nkab,nkb->nka", masses, accelerations)
    force, moment = body_loads(scene, body, names, t, on_points)
    return {"t": t, "forces_on_point": on_points, "body_force": force, "body_moment": moment,
            "returned": returned, "wall_time_s": finished - start, "init_time_s": initialised - start}


def cablefem_body_loads(scene, body, run):
    """cablefem's run (``run_cablefem_case``) of a scene whose lines end on ``body``'s points: the
    forces (n, k, 3) on those points in ``body_points`` order, and the body's force and moment (n, 3)."""
    names, _ = body_points(scene, body)
    column = {line.ends[1]: k for k, line in enumerate(scene.lines)}
    forces = run["forces"][:, [column[name] for name in names]]
    force, moment = body_loads(scene, body, names, run["t"], forces)
    return forces, force, moment


def run_cablefem_free(scene, duration, dt, body, point):
    """``cablefem run`` (``cablefem.runs.run.run_scene``) of a scene with a free ``body``: dict of
    t (n,), forces (n, 1, 3) [N] the lines exert on the coupled ``point`` (tensions.csv), the body's
    height z (n,) [m] and wall_time_s."""
    from dataclasses import replace

    from cablefem.runs.run import run_scene

    scene = replace(scene, output=replace(scene.output, every=duration))  # one frame: the run's rows are what count
    with tempfile.TemporaryDirectory(prefix="parity-free-") as folder:
        start = time.perf_counter()
        run_scene(scene, folder, duration=duration, dt=dt)
        wall = time.perf_counter() - start
        table = np.genfromtxt(Path(folder) / "tensions.csv", delimiter=",", names=True, deletechars="")
    force = np.column_stack([table[f"point:{point}:f{axis}"] for axis in "xyz"])
    return {"t": table["t"], "forces": force[:, None, :], "z": table[f"body:{body}:z"], "wall_time_s": wall}
