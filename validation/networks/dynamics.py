"""Both codes on one network in the time domain: MoorDyn-C with its coupled bodies driven through
its coupling API, cablefem on the TOML scene of the same network; the series each returns.

MoorDyn-C's coupled body (``Body::initiateStep``, ``updateFairlead``): each coupling call
``moordyn.Step(x, xd, t, dt)`` gives per body x = (x, y, z [m], roll, pitch, yaw [rad]) and xd;
until the next call the body moves along x + xd (t' - t), angles included, and its points sit at
r + R(angles) p with R = Rx Ry Rz. As in ``validation.moordyn.peer`` (coupling "secant") xd is
the secant of the prescribed motion over the coupling interval, so positions follow its
piecewise-linear interpolant. MoorDyn gives a body's points the velocity v + xd[3:] x (R p): the
Euler angle rates taken as the angular velocity, which differs from d(R p)/dt by O(angle x rate)
(``Body::setDependentStates``); the end segments' damping sees that velocity (see the README:
switch ``moordyn_points_not_body``, the fairleads driven as coupled points instead).

The force MoorDyn returns per body is the net force of its points (each the force of its line end
nodes, without their inertia) and its moment about the body's reference point, in the global frame.
cablefem's is the sum of the string end forces at the body's points (FEM reactions) and their
moment about the same point.
"""

import tempfile
import time
from pathlib import Path

import numpy as np

from cablefem.dynamics.registry import INTEGRATORS
from cablefem.io import load_scene
from cablefem.model.motion import body_motion
from cablefem.model.network import BodyPointPath
from cablefem.model.network import anchor_path, boundary_path
from cablefem.fem.system import build_system
from cablefem.statics.scene import start_states
from cablefem.dynamics.registry import integrator_options
from validation.moordyn import peer


def body_poses(scene, names, t):
    """Poses (k, 6) [m, rad] and their rates (k, 6) of the coupled bodies ``names`` at time t [s]."""
    x, v = [], []
    for name in names:
        body = scene.bodies[name]
        d, dv, _ = body_motion(body.motion, t)
        x.append(np.concatenate([body.position + d[:3], body.rotation + d[3:]]))
        v.append(dv)
    return np.array(x), np.array(v)


def run_moordyn(path, scene, duration, dt_out, dtM, ic_dtM, watch, segments=None, as_points=False):
    """MoorDyn on ``path``: its bodies (file order = ``scene.bodies`` order) driven by the scene's
    motions, coupling every ``dt_out`` [s]. ``watch``: dict with the MoorDyn IDs of ``fairleads``
    (points on bodies), ``joints`` (free points) and ``ends`` ((line ID, node) of line ends whose
    tension to record). With ``as_points`` the file's BODIES are coupled POINTS instead (the file
    written that way by the caller), moved along the secants of r + R p. Returns a dict of
    t (n,), body (n, k, 6) [N, N m], fairleads (n, f, 3) [N], joints (n, j, 3) [m], ends (n, e) [N],
    end_mass (n, f, 3, 3) [kg] (the mass matrix, added mass included, of the line end node at each
    fairlead: MoorDyn's point force leaves out its inertia), wall_time_s and init_time_s."""
    import moordyn

    names = list(scene.bodies)
    steps = int(round(duration / dt_out))
    t = np.arange(steps + 1) * dt_out
    text = peer.rewrite_input(Path(path).read_text(), dtM=ic_dtM, segments=segments)
    out = {key: [] for key in ("body", "fairleads", "joints", "ends", "end_mass")}
    local = [scene.points[name] for name in watch["fairlead_names"]]

    def coupled(time_s):
        poses, rates = body_poses(scene, names, time_s)
        if not as_points:
            return poses.ravel(), rates.ravel()
        xs, vs = [], []
        for point in local:
            x, v, _ = BodyPointPath(scene.bodies[point.body], point.position)(time_s)
            xs.append(x)
            vs.append(v)
        return np.ravel(xs), np.ravel(vs)

    with tempfile.TemporaryDirectory(prefix="moordyn-net-") as folder:
        work = Path(folder) / Path(path).name
        work.write_text(text)
        with peer.silenced_stdout():
            start = time.perf_counter()
            system = moordyn.Create(str(work))
            try:
                x, _ = coupled(0.0)
                moordyn.Init(system, x, np.zeros_like(x))
                moordyn.SetDt(system, dtM)
                initialised = time.perf_counter()
                fairleads = [moordyn.GetPoint(system, i) for i in watch["fairleads"]]
                joints = [moordyn.GetPoint(system, i) for i in watch["joints"]]
                ends = [(moordyn.GetLine(system, line), node) for line, node in watch["ends"]]
                fairlead_ends = [(moordyn.GetLine(system, line), node) for line, node in watch["fairlead_ends"]]

                def record(forces):
                    fair = np.array([moordyn.GetPointForce(p) for p in fairleads])
                    if forces is None:  # the body's force and moment from its points, as cablefem's
                        forces = body_loads(scene, names, watch["fairlead_names"],
                                            np.array([moordyn.GetPointPos(p) for p in fairleads]), fair, t_now[0])
                    out["body"].append(np.reshape(forces, (len(names), 6)))
                    out["fairleads"].append(fair)
                    out["joints"].append([moordyn.GetPointPos(p) for p in joints])
                    out["ends"].append([np.linalg.norm(moordyn.GetLineNodeTen(line, node)) for line, node in ends])
                    out["end_mass"].append([moordyn.GetLineNodeM(line, node) for line, node in fairlead_ends])

                t_now = [0.0]
                record(None)  # before the first step MoorDyn has returned no body force
                for n in range(steps):
                    x_next, _ = coupled(t[n + 1])
                    forces = moordyn.Step(system, x, (x_next - x) / dt_out, t[n], dt_out)
                    t_now[0] = t[n + 1]
                    record(None if as_points else forces)
                    x = x_next
                finished = time.perf_counter()
            finally:
                moordyn.Close(system)
    result = {key: np.array(value) for key, value in out.items()}
    result.update(t=t, wall_time_s=finished - start, init_time_s=initialised - start)
    return result


def body_loads(scene, names, point_names, positions, forces, t):
    """Force and moment (k, 6) [N, N m] on the bodies ``names`` at time t [s] from forces (m, 3) [N]
    at their points ``point_names`` at ``positions`` (m, 3) [m]; moments about the bodies'
    reference points r + d(t)."""
    loads = np.zeros((len(names), 6))
    poses, _ = body_poses(scene, names, t)
    for name, x, f in zip(point_names, positions, forces):
        k = names.index(scene.points[name].body)
        loads[k, :3] += f
        loads[k, 3:] += np.cross(x - poses[k, :3], f)
    return loads


def started(scene, dt):
    """The scene's integrator for every string, at its static equilibrium at t = 0, step dt [s]."""
    systems = [build_system(scene, line) for line in scene.lines]
    states, _ = start_states(scene, systems=systems)
    return [INTEGRATORS[scene.solver.integrator](system, X0, boundary_path(scene, line), dt=dt,
                                                anchor=anchor_path(scene, line), **integrator_options(scene.solver))
            for system, line, X0 in zip(systems, scene.lines, states)]


def run_cablefem(toml, duration, dt_out, dt, joints, scene=None):
    """cablefem's BDF2 on the TOML scene (statics at t = 0, then steps of dt [s], sampled every
    dt_out [s]). ``joints``: names of the free points whose positions to record. Returns a dict of
    t, body (n, k, 6), fairleads (n, f, 3) (the scene's body points in ``fairlead_names`` order),
    joints (n, j, 3), ends (n, e) (element tensions beside each joint: the line entering and the
    line leaving it), wall_time_s, init_time_s, newton_iterations and the names."""
    scene = scene or load_scene(toml)
    names = list(scene.bodies)
    start = time.perf_counter()
    integrators = started(scene, dt)
    initialised = time.perf_counter()
    # where things are: (string, end 0/1) per body point, (string, vertex) per joint
    on_body = [(k, e, name) for k, line in enumerate(scene.lines) for e, name in enumerate(line.ends)
               if name is not None and scene.points[name].body is not None]
    vertex = {}
    for k, line in enumerate(scene.lines):
        boundaries = np.cumsum([0] + [seg.elements for seg in line.segments])  # vertex rows come first
        for b, joint in line.joints:
            vertex[joint.name] = (k, int(boundaries[b]))
    dt_out = max(dt_out, dt)
    per_sample = int(round(dt_out / dt))
    steps = int(round(duration / dt_out))
    t = np.arange(steps + 1) * dt_out
    out = {key: [] for key in ("body", "fairleads", "joints", "ends")}

    def record(time_s):
        reactions = [integ.reactions() for integ in integrators]  # (fairlead, anchor) per string
        points = [name for _, _, name in on_body]
        forces = np.array([reactions[k][1 - e] for k, e, _ in on_body])
        positions = np.array([integrators[k].X[-1 if e else 0] for k, e, _ in on_body])
        out["body"].append(body_loads(scene, names, points, positions, forces, time_s))
        out["fairleads"].append(forces)
        out["joints"].append([integrators[vertex[j][0]].X[vertex[j][1]] for j in joints])
        out["ends"].append([tension for j in joints
                            for tension in element_tensions(integrators[vertex[j][0]], vertex[j][1])])

    record(0.0)
    for n in range(steps):
        for integ in integrators:
            integ.march(np.linspace(t[n], t[n + 1], per_sample + 1)[1:])
        record(t[n + 1])
    result = {key: np.array(value) for key, value in out.items()}
    result.update(t=t, wall_time_s=time.perf_counter() - start, init_time_s=initialised - start,
                  newton_iterations=sum(i.newton_iterations for i in integrators),
                  fairlead_names=[name for _, _, name in on_body])
    return result


def time_cablefem(toml, duration, dt, scene=None):
    """Wall time [s] of cablefem's steps alone on the scene, every string marched over the whole
    run in one call as ``cablefem run`` does (no sampling of the state between steps), and of its
    statics: (stepping, statics)."""
    scene = scene or load_scene(toml)
    start = time.perf_counter()
    integrators = started(scene, dt)
    statics = time.perf_counter() - start
    times = np.arange(1, int(round(duration / dt)) + 1) * dt
    start = time.perf_counter()
    for integ in integrators:
        integ.march(times)
    return time.perf_counter() - start, statics


def element_tensions(integ, vertex):
    """Axial tensions [N] of the P1 elements before and after ``vertex`` of an integrator's line:
    EA max(e, 0) + EA beta de/dt, MoorDyn-C's law (damping_when_slack)."""
    system, X, V = integ.system, integ.X, integ.V
    lengths = np.concatenate([[seg.length / seg.elements] * seg.elements for seg in system.line.segments])
    tensions = []
    for element in (vertex - 1, vertex):
        d = (X[element + 1] - X[element]) / lengths[element]
        stretch = np.linalg.norm(d)
        rate = d @ (V[element + 1] - V[element]) / lengths[element] / stretch
        EA = system.props["EA"][element]
        beta = system.props["damping"][element] if "damping" in system.props else 0.0
        tensions.append(float(EA * max(stretch - 1.0, 0.0) + EA * beta * rate))
    return tensions



def without_end_inertia(md, scene, point_names):
    """MoorDyn's run ``md`` with each fairlead force less the inertia of its line end node, M a
    with a the point's acceleration on its body (the force the line exerts on the point, as
    cablefem's FEM reaction), and the bodies' loads summed from those (validation/moordyn's RMS*)."""
    names = list(scene.bodies)
    paths = [BodyPointPath(scene.bodies[scene.points[n].body], scene.points[n].position) for n in point_names]
    x = np.stack([path.states(md["t"])[0] for path in paths], axis=1)
    a = np.stack([path.states(md["t"])[2] for path in paths], axis=1)
    forces = md["fairleads"] - np.einsum("nfab,nfb->nfa", md["end_mass"], a)
    body = np.array([body_loads(scene, names, point_names, x[n], forces[n], t) for n, t in enumerate(md["t"])])
    return dict(md, fairleads=forces, body=body)
