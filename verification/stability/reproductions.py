"""Case 7 of verification/stability: minimal reproductions of what the suite found, kept as
regressions (a toy chain laid onto a stiff seabed, generalised-alpha on a chain pulled taut, output
frames that left slivers of steps)."""

import os
import tempfile

import numpy as np

from cablefem.geometry import Horizontal
from cablefem.model.line import Line, LineType, Segment
from cablefem.runs.run import run_scene
from cablefem.model.scene import Contact, Environment, Friction, Motion, Output, Scene, Solver

from verification.stability.driver import simulate, summary


def toy_scene(stiffness, dt, integrator="bdf2", rho_inf=0.5, depth=10.0, motion=None, EA=5.055e11):
    """A 22 m chain (Table 2 mass and diameter, EA [N], no drag, added mass or damping) of
    4 P1 elements between (0, 0, -5) and (21, 0, -5) over a flat seabed ``depth`` [m] deep
    (G_K ``stiffness`` [N/m^3]). By default the fairlead moves 4 m towards the anchor at
    0.1 m/s, which lays the middle of the chain onto a seabed 10 m deep at ~0.06 m/s."""
    chain = LineType("toy-chain", diameter=0.3539, mass=835.4, EA=EA, damping=0.0, Cd_normal=0.0,
                     Cd_tangential=0.0, Ca_normal=0.0, Ca_tangential=0.0)
    line = Line("toy", (0.0, 0.0, -5.0), (21.0, 0.0, -5.0), (Segment(chain, 22.0, 4),), 1)
    if motion is None:
        motion = Motion(kind="table", times=np.array([0.0, 40.0, 1e3]),
                        positions=np.array([[0, 0, 0], [-4.0, 0, 0], [-4.0, 0, 0]]))
    return Scene(name="toy", lines=[line], seabed=Horizontal(depth), contact=Contact(stiffness=stiffness),
                 environment=Environment(), friction=Friction(), motion=motion,
                 solver=Solver(integrator=integrator, dt=dt, rho_inf=rho_inf, duration=60.0))


def run_reproductions(fast):
    """Case 7, the problems this suite found, kept as regressions: (a) a chain laid onto a stiff
    seabed gained energy when halved BDF2 steps jumped back to dt (fixed: steps grow by at most
    2x); (b) generalised-alpha with rho_inf >= 0.6 pumps energy into a stiff chain pulled taut
    (a property of the scheme on nonlinear problems: default rho_inf is now 0.5 and
    ``run.setting_warnings`` says so before a run); (c) output frames no longer leave slivers.
    Peak kinetic energy against what the motion gives it (~1e2 J for (a), ~5e3 J for (b))."""
    landing = []
    settings = [(3e14, 0.01)] if fast else \
        [(3e5, 0.01), (3e8, 0.01), (3e11, 0.01), (3e11, 0.001), (3e14, 0.01), (3e14, 0.001)]
    for stiffness, dt in settings:
        row = summary(simulate(toy_scene(stiffness, dt), dt, 30.0, energy=False))
        row.update(stiffness=stiffness)
        landing.append(row)
    alpha = []
    smooth = Motion(kind="harmonic", amplitude=(-1.0, 0.0, 0.0), period=20.0, ramp=10.0)
    variants = (("bdf2", None), ("generalized-alpha", 0.5)) if fast else (
        ("bdf2", None), ("generalized-alpha", 0.0), ("generalized-alpha", 0.5), ("generalized-alpha", 0.6),
        ("generalized-alpha", 0.8), ("generalized-alpha", 1.0))
    for integrator, rho in variants:
        for EA in ((5.055e11,) if fast else (3.15e9, 5.055e11)):
            scene = toy_scene(3e5, 0.01, integrator, 0.5 if rho is None else rho, depth=1000.0, motion=smooth, EA=EA)
            run = simulate(scene, 0.01, 20.0, integrator, energy=False)
            row = summary(run)
            row.update(rho_inf=rho, EA=EA)
            alpha.append(row)
    return {"landing": landing, "alpha": alpha, "frames": frame_landing()}


def frame_landing(dt=1e-4, duration=1.15, every=0.1):
    """(c) ``run_scene`` lands on its output frames by shortening the step to the frame time;
    t accumulates round-off, and when it sits more than 1e-9 dt short of a frame the step
    taken is that sliver (1.5e-13 s at t = 1.5 s here), after which BDF2's next step has a
    step ratio of ~1e9. The toy chain (EA 3.15e9 N, hanging freely, 1 m surge) at dt = 1e-4 s,
    frames every 0.1 s: the largest tension and the shortest step in tensions.csv."""
    motion = Motion(kind="harmonic", amplitude=(-1.0, 0.0, 0.0), period=4.0, ramp=2.0)
    scene = toy_scene(3e5, dt, depth=1000.0, motion=motion, EA=3.15e9)
    with tempfile.TemporaryDirectory() as out:
        scene.output = Output(dir=out, every=every)
        written = run_scene(scene, out_dir=out, duration=duration, dt=dt, progress=False)
        table = np.loadtxt(os.path.join(out, "tensions.csv"), delimiter=",", skiprows=1)
    t, T = table[:, 0], table[:, 1]
    return {"dt": dt, "every": every, "status": written["status"], "first_tension": float(T[0]),
            "largest_tension": float(T.max()), "time_of_largest": float(t[np.argmax(T)]),
            "shortest_step_written": float(np.min(np.diff(t)))}
