"""The two sides of the free-body decay study: a body released from a pose off its equilibrium, at
rest, in cablefem (``cablefem.dynamics.body_group``) and in MoorDyn-C (PyPI ``moordyn``), and the
period and logarithmic decrement of its heave or pitch.

Both codes start from ``inputs/buoy.dat`` with the body's row at the released pose: MoorDyn-C with no
initial-condition solve (``TmaxIC`` 0: the body where the file puts it, its lines as MoorDyn-C
initialises them between their ends); cablefem with its lines in static equilibrium under the body
held at that pose (network statics of the file with the body fixed), then the body let go.
"""

import os
import re
import sys
import tempfile
from dataclasses import replace

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
INPUT = os.path.join(HERE, "inputs", "buoy.dat")
#: the body's row of the file: ID, attachment, then its pose X0 Y0 Z0 r0 p0 y0
BODY_ROW = re.compile(r"^(1\s+free\s+)(\S+\s+){6}", re.M)


#: a line's row of the file: ID, type, ends, length, then NumSegs
LINE_ROW = re.compile(r"^(\d+\s+chain\s+\d+\s+\d+\s+\S+\s+)(\d+)", re.M)
#: the solver options' dtM row
DTM_ROW = re.compile(r"^\S+(\s+dtM\b)", re.M)


def with_pose(text, pose, numsegs=None, dtM=None):
    """The file's text with the body's pose (x, y, z [m], roll, pitch, yaw [rad]), and each line's
    NumSegs and the time step dtM [s] where given."""
    values = list(pose[:3]) + list(np.degrees(pose[3:]))
    text = BODY_ROW.sub(lambda match: match.group(1) + "".join(f"{v:.10g}   " for v in values), text, count=1)
    if numsegs is not None:
        text = LINE_ROW.sub(lambda match: match.group(1) + str(numsegs), text)
    if dtM is not None:
        text = DTM_ROW.sub(lambda match: f"{dtM:g}" + match.group(1), text, count=1)
    return text


def equilibrium():
    """The body's static pose (6,) in cablefem (network statics of the file)."""
    from cablefem.io import load_scene
    from cablefem.statics.scene import static_lines

    network = static_lines(load_scene(INPUT))[3]
    return network.poses["body1"].copy()


def with_mesh(scene, order, elements):
    """``scene`` with every line on ``elements`` elements of ``order`` (None: as the file reads)."""
    if order is None:
        return scene
    return replace(scene, lines=[replace(line, order=order, segments=tuple(replace(s, elements=elements)
                                                                            for s in line.segments))
                                 for line in scene.lines])


def cablefem_decay(pose, duration, dt, integrator, rho_inf=0.9, order=None, elements=None):
    """cablefem: times (n,) [s] and poses (n, 6) of the body released at rest from ``pose``, its lines
    on ``elements`` elements of ``order`` each (None: the file's mesh by cablefem's defaults)."""
    from cablefem.dynamics.body_group import body_groups
    from cablefem.dynamics.registry import INTEGRATORS, integrator_options
    from cablefem.fem.system import build_system
    from cablefem.io import load_scene
    from cablefem.model.network import anchor_path, boundary_path, dynamic_lines
    from cablefem.statics.scene import network_start

    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "released.dat")
        with open(path, "w", encoding="utf-8") as handle:
            handle.write(with_pose(open(INPUT, encoding="utf-8").read(), pose))
        scene = with_mesh(load_scene(path), order, elements)
    scene = replace(scene, solver=replace(scene.solver, integrator=integrator, rho_inf=rho_inf))
    held = replace(scene, bodies={name: replace(body, kind="fixed") for name, body in scene.bodies.items()},
                   lines=[replace(line, prescribed=(True, True)) for line in scene.lines])  # anchor to body
    _, states, _, _ = network_start(held)  # the lines in equilibrium under the body held at ``pose``
    systems = [build_system(scene, line) for line in dynamic_lines(scene)]
    integrators = [INTEGRATORS[integrator](system, X, boundary_path(scene, line), dt=dt,
                                           anchor=anchor_path(scene, line), **integrator_options(scene.solver))
                   for system, line, X in zip(systems, scene.lines, states)]
    group, = body_groups(scene, integrators, {"body1": np.asarray(pose, dtype=float)})
    for _ in range(int(round(duration / dt))):
        group.step(dt)
    body = group.bodies[0]
    times = np.array([t for t, _ in body.history])
    return times, np.array([pose for _, pose in body.history]), integrators[0].newton_iterations


def moordyn_decay(pose, duration, dt_out, numsegs=None, dtM=None):
    """MoorDyn-C: times (n,) [s] and poses (n, 6) of the body released at rest from ``pose`` (its
    angles from ``moordyn.GetBodyState``, radians), each line on ``numsegs`` segments and stepping
    ``dtM`` [s] where given (the file's otherwise)."""
    import moordyn

    from validation.moordyn.peer import silenced_stdout

    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "released.dat")
        with open(path, "w", encoding="utf-8") as handle:
            handle.write(with_pose(open(INPUT, encoding="utf-8").read(), pose, numsegs, dtM))
        with silenced_stdout():
            system = moordyn.Create(path)
            moordyn.Init(system, [], [])
            body = moordyn.GetBody(system, 1)
            times, poses, t = [0.0], [moordyn.GetBodyState(body)[0]], 0.0
            for k in range(int(round(duration / dt_out))):
                moordyn.Step(system, [], [], t, dt_out)
                t = (k + 1) * dt_out
                times.append(t)
                poses.append(moordyn.GetBodyState(body)[0])
            moordyn.Close(system)
    sys.stdout.flush()
    return np.array(times), np.array(poses, dtype=float)


def crossings(times, signal):
    """Times (k,) where ``signal`` crosses zero (linear interpolation) and the largest |signal| (k - 1,)
    between successive ones: the half-cycles of an oscillation about zero, robust to the ripple the
    lines' own modes put on it."""
    sign = np.signbit(signal)
    at = np.flatnonzero(sign[1:] != sign[:-1])
    t = times[at] - signal[at] * (times[at + 1] - times[at]) / (signal[at + 1] - signal[at])
    swings = np.array([np.max(np.abs(signal[a + 1:b + 1])) for a, b in zip(at[:-1], at[1:])])
    return t, swings


def period_and_decrement(times, signal, equilibrium, cycles=3):
    """The period [s] and the logarithmic decrement per period of ``signal`` about ``equilibrium`` over
    its first ``cycles`` periods: the mean time and the mean ln(a_k / a_{k+2}) from each half-cycle to
    the next of the same sign (a heave whose lines stiffen going down swings further down than up)."""
    t, swings = crossings(times, signal - equilibrium)
    if len(swings) < 2 * cycles + 1:
        raise ValueError(f"{len(swings)} half-cycles, fewer than {2 * cycles + 1}: run longer")
    t, swings = t[:2 * cycles + 1], swings[:2 * cycles + 1]
    return float(np.mean(t[2:] - t[:-2])), float(np.mean(np.log(swings[:-2] / swings[2:])))
