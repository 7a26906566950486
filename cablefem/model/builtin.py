"""Built-in scenes: the desire2023 flume cases at prototype scale (Sec. 4, Table 5, Figs. 10-17).

The flume (56 m x 2 m at 1:75) held one chain over three seabeds, flat,
gentle step (4 deg) and steep step (19 deg), each driven by two fairlead
motions: quasi-static (17 s period, 2.5 m amplitude, 15 m mean drift) and
dynamic with snap loads (6 s, 5 m, no drift). The step geometry is
reconstructed in ``cablefem.geometry.generators.flume_step`` (docs/seabeds.md);
the anchor rests on the 100 m deep floor at x = -595 m, the fairlead is at the
origin (the paper's frame). Steps are triangulated and use the general
vertex-normal projection, as in the paper.
"""

from cablefem.geometry import Horizontal
from cablefem.model.line import Line, LineType, Segment
from cablefem.model.scene import Contact, Environment, Friction, Motion, Output, Scene, Solver

FLUME_SEABEDS = ("flat", "gentle", "steep")
FLUME_DEPTH = 100.0  # m, floor on the anchor side
FLUME_ANCHOR = (-595.0, 0.0, -FLUME_DEPTH)

#: desire2023 Sec. 4.1: the two fairlead motions, each ramped in over one period
FLUME_MOTIONS = {
    "quasi-static": Motion(kind="harmonic", amplitude=(2.5, 0.0, 0.0), period=17.0,
                           offset=(15.0, 0.0, 0.0), ramp=17.0),
    "dynamic": Motion(kind="harmonic", amplitude=(5.0, 0.0, 0.0), period=6.0, ramp=6.0),
}


def table5_chain():
    """The desire2023 Table 5 chain (prototype scale; Cd_t in the paper's d-area convention)."""
    return LineType("chain", diameter=0.3539, mass=835.4, EA=3.15e9, damping=0.001,
                    Cd_normal=2.5, Cd_tangential=0.5, Ca_normal=3.8, Ca_tangential=0.0)


def flume_seabed(kind):
    """The flume seabed ``kind`` ("flat", "gentle", "steep") as the model a run uses."""
    if kind == "flat":
        return Horizontal(FLUME_DEPTH)
    from cablefem.geometry.generators import flume_step, triangulated_step  # grids and meshes: not for a plane

    return triangulated_step(flume_step(kind, depth=FLUME_DEPTH))


def flume_scene(seabed="steep", motion="dynamic", elements=40, order=1, duration=60.0, dt=0.01):
    """One of the six flume cases: seabed "flat" | "gentle" | "steep", motion "quasi-static" |
    "dynamic"; ``elements`` elements of ``order``; duration and dt [s]."""
    line = Line("line1", FLUME_ANCHOR, (0.0, 0.0, 0.0), (Segment(table5_chain(), 635.0, elements),), order)
    bed = flume_seabed(seabed)
    return Scene(
        name=f"flume-{seabed}-{motion}",
        lines=[line],
        seabed=bed,
        contact=Contact(stiffness=3.0e5, damping_ratio=1.0),
        environment=Environment(water_density=1025.0, gravity=9.81),
        friction=Friction(model="isotropic", mu=0.3, v_threshold=0.01),
        motion=FLUME_MOTIONS[motion],
        solver=Solver(integrator="bdf2", dt=dt, duration=duration),
        output=Output(dir="out", every=0.1),
        notes=[f"built-in scene: desire2023 flume, {seabed} seabed, {motion} motion"],
    )


def default_scene():
    """The built-in scene of ``cablefem static`` / ``run`` with no SCENE: the desire2023
    steep-slope (19 deg) flume case with the dynamic 6 s / 5 m motion, 60 s at dt = 0.01 s,
    40 P1 elements (``cablefem.model.builtin.flume_scene``; examples/flume_steep.toml)."""
    return flume_scene("steep", "dynamic")
