"""MoorDyn's RodHanging.txt (a free rod on two 450 m ropes) in a run of both codes: where the rod rests
and the period of its sway along the ropes.

    python -m benchmarks.rod_hanging_parity FOLDER

FOLDER is MoorDyn's ``tests/Mooring``. The file's TmaxIC is 0 (MoorDyn-C's start is no equilibrium),
so MoorDyn-C relaxes it here (TmaxIC 300, CdScaleIC 4), which leaves the rod tilted and swinging,
and steps it 300 s (0.1 s coupling steps); its rest is its pose over the last 20 s and its sway
period the spacing of the upward zero crossings of the rod middle's x (smoothed over 0.9 s against
the ropes' axial mode at 0.87 s) after 20 s. cablefem starts from its statics, the rod and the ropes
swinging along x (0.1 m/s at the rod, falling linearly to 0 at the anchors), and steps 40 s of
generalised-alpha at 0.1 s; its sway period is measured the same way after 5 s.

Measured (moordyn 2.7 wheel): rest depth of end A -86.1876 m (MoorDyn-C, its last 20 s still moving
by 5 mm) and -86.1827 m (cablefem), 4.9 mm apart; sway period 9.608 s and 9.593 s (0.16 %).
"""

import argparse
import os
import tempfile
from dataclasses import replace

import numpy as np


def period(t, x, after):
    """The mean spacing [s] of the upward zero crossings of x (n,) after ``after`` [s], smoothed over
    nine samples."""
    keep = t >= after
    t, x = t[keep], x[keep] - x[keep].mean()
    smooth = np.convolve(x, np.ones(9) / 9, mode="same")
    up = [t[k] - smooth[k] * (t[k + 1] - t[k]) / (smooth[k + 1] - smooth[k])
          for k in range(9, len(t) - 10) if smooth[k] < 0 <= smooth[k + 1]]
    return float(np.mean(np.diff(up)))


def moordyn_c(path):
    """(rest end A (3,), sway period [s]) of MoorDyn-C relaxed and stepped for 300 s."""
    import moordyn

    from validation.moordyn.peer import silenced_stdout

    text = open(path).read().replace("0             TmaxIC               max time for ic gen (s)",
                                     "300           TmaxIC\n4             CdScaleIC")
    with tempfile.TemporaryDirectory() as folder:
        relaxed = os.path.join(folder, "RodHanging.txt")
        with open(relaxed, "w") as handle:
            handle.write(text)
        with silenced_stdout():
            system = moordyn.Create(relaxed)
            moordyn.Init(system, [], [])
            rod = moordyn.GetRod(system, 1)
            last = moordyn.GetRodN(rod)
            rows = []
            for k in range(3001):
                ends = [np.array(moordyn.GetRodNodePos(rod, n)) for n in (0, last)]
                rows.append([0.1 * k, *ends[0], *(0.5 * (ends[0] + ends[1]))])
                if k < 3000:
                    moordyn.Step(system, [], [], 0.1 * k, 0.1)
            moordyn.Close(system)
    rows = np.array(rows)
    return rows[-200:, 1:4].mean(axis=0), period(rows[:, 0], rows[:, 4], 20.0)


def cablefem(path, dt=0.1, duration=40.0):
    """(rest end A (3,), sway period [s]) of cablefem from its statics, the rod and ropes swinging."""
    from cablefem.dynamics.body_group import body_groups
    from cablefem.dynamics.registry import INTEGRATORS, integrator_options
    from cablefem.io import load_scene
    from cablefem.model.network import anchor_path, boundary_path
    from cablefem.statics.scene import network_start

    scene = load_scene(path)
    scene = replace(scene, solver=replace(scene.solver, integrator="generalized-alpha"))
    systems, states, _, network = network_start(scene)
    stepper = INTEGRATORS["generalized-alpha"]
    integrators = [stepper(system, X, boundary_path(scene, line), dt=dt, anchor=anchor_path(scene, line),
                           **integrator_options(scene.solver)) for system, line, X in zip(systems, scene.lines, states)]
    group, = body_groups(scene, integrators, network.poses)
    body = group.bodies[0]
    group.set_velocity(body, [[0.1, 0.0, 0.0], [0.0, 0.0, 0.0]])
    for m in integrators:
        anchor = m.X[0] if abs(m.X[0, 0]) > abs(m.X[-1, 0]) else m.X[-1]
        reach = np.linalg.norm(m.X - anchor, axis=1)
        m.V[:, 0] = 0.1 * reach / reach.max()
    group.start_bodies()
    rows = []
    for _ in range(int(round(duration / dt))):
        group.step(dt)
        middle = body.X[0] + body.rotation(body.X[1]) @ [0.0, 0.0, 0.5 * scene.bodies["rod1"].rod.length]
        rows.append([body.t, middle[0]])
    rows = np.array(rows)
    return network.poses["rod1"][:3], period(rows[:, 0], rows[:, 1], 5.0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folder", help="MoorDyn's tests/Mooring")
    path = os.path.join(parser.parse_args().folder, "RodHanging.txt")
    peer, ours = moordyn_c(path), cablefem(path)
    print(f"{'code':<10} {'end A z at rest [m]':>20} {'sway period [s]':>16}")
    for name, (rest, swing) in (("MoorDyn-C", peer), ("cablefem", ours)):
        print(f"{name:<10} {rest[2]:>20.4f} {swing:>16.3f}")
    print(f"difference: {abs(peer[0][2] - ours[0][2]) * 1e3:.1f} mm at rest, "
          f"{abs(peer[1] / ours[1] - 1) * 100:.2f} % in the sway period")


if __name__ == "__main__":
    main()
