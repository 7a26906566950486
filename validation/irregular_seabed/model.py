"""The setting of validation/irregular_seabed: the diamond-square seabed and its three models, the
Table 5 line and its circular motion, a scene run quietly and what is read from its frames
(positions at a time, touchdown, grounded length)."""

import json
from pathlib import Path

import numpy as np

from cablefem.geometry import TriangulatedSurface
from cablefem.geometry.generators import diamond_square
from cablefem.model.line import Line, Segment
from cablefem.model.scene import Contact, Environment, Friction, Motion, Output, Scene, Solver
from cablefem.model.builtin import table5_chain

METHODS = ("general", "inclined", "horizontal")
LENGTH = 635.0  # m, Table 5

# ---- the seabed (Fig. 18). The paper gives smoothness 0.3 and z-bar = -93.5 m only.
SMOOTHNESS = 0.3
LEVELS = 6  # 2^6 + 1 = 65 nodes a side: 12.5 m cells, 8192 triangles
EXTENT = ((-700.0, 100.0), (-400.0, 400.0))  # m: 100 m beyond the anchor (x = -597 m), 88 m beyond the fairlead
MEAN_DEPTH = 93.5  # m, Fig. 18's z-bar
#: corner half-range of the fractal before detrending [m]: about its plane the surface then has
#: an RMS of 2.5-4.7 m and a range of 20-30 m, local slopes of 4 deg (median) to 13-21 deg (README)
AMPLITUDE = 20.0
#: amplitudes and seeds of the static sweep (the spread of the realisations)
SWEEP_AMPLITUDES = (10.0, 20.0, 30.0)
#: gradient (dz/dx, dz/dy) of the least-squares plane: rises 1.1 deg towards the fairlead
#: (shallower than z-bar under the touchdown, as Sec. 5 explains the horizontal > inclined
#: tensions) and 0.6 deg towards +y (inclined in both directions, as Fig. 18)
TILT = (0.02, 0.01)

# ---- the line and the motion (Sec. 5: circle in XY of 2.5 m, 12 s, origin at x = 10 m)
ANCHOR_XY = (-597.0, 0.0)  # m; z on each seabed model. Chosen for the horizontal total peak ~2.4 MN
CENTRE = (10.0, 0.0, 0.0)  # m: the scene's fairlead; the motion circles around it
PERIOD = 12.0
MOTION = Motion(kind="circular", radius=2.5, period=PERIOD, plane="xy", ramp=PERIOD / 2)
SNAPSHOT_T = 6.0  # s, Fig. 19
CONTACT = Contact(stiffness=3.0e5, damping_ratio=1.0)  # Table 5 G_K
FRICTION = Friction(model="isotropic", mu=0.3, v_threshold=0.01)  # Table 5 C_K, U_c
ENVIRONMENT = Environment(water_density=1025.0, gravity=9.81)

#: desire2023 Sec. 5, read from the text (Fig. 20) and Table 6
PAPER = {
    "dynamic_peak_N": {"general": 5.0e5, "inclined": 4.0e5, "horizontal": 4.0e5},  # approximations "< 4e5"
    "total_peak_N": {"general": 2.8e6, "inclined": 2.2e6, "horizontal": 2.4e6},
    "table6_wall_time_s": {"horizontal": 11236.0, "general": 13488.0},
}

SETTINGS = {
    "full": {"elements": 80, "dt": 0.01, "duration": 60.0, "seeds": (0, 1, 2, 3, 4), "every": 0.5,
             "cost_duration": 120.0, "repeats": 3, "sweep_seeds": 20, "sweep_amplitudes": SWEEP_AMPLITUDES},
    "fast": {"elements": 40, "dt": 0.02, "duration": 24.0, "seeds": (0, 1, 2), "every": 1.0,
             "cost_duration": 6.0, "repeats": 3, "sweep_seeds": 10, "sweep_amplitudes": (AMPLITUDE,)},
}
#: the seed drawn in the figures (the first one: not chosen for its numbers)
PRIMARY_SEED = 0
#: statistics "after the ramp": from the end of the ramp plus one period
STEADY_FROM = MOTION.ramp + PERIOD


def seabed_grid(seed, amplitude=AMPLITUDE, tilt=TILT):
    """The Fig. 18-like diamond-square DepthGrid of ``seed`` [m]."""
    return diamond_square(LEVELS, SMOOTHNESS, amplitude, seed, EXTENT, MEAN_DEPTH, tilt)


def seabed_models(grid):
    """The three seabed models of Sec. 5 for ``grid``: dict method -> Seabed."""
    return {"general": TriangulatedSurface(*grid.surface()),
            "inclined": grid.least_squares_plane(),
            "horizontal": grid.mean_depth_horizontal()}


def surface_statistics(grid):
    """Numbers that describe a seabed grid [m, deg]: mean, the plane, the roughness about it."""
    plane = grid.least_squares_plane()
    vertices = grid.vertices
    residual = vertices[:, 2] - plane.elevation(vertices[:, :2])
    slope_y, slope_x = np.gradient(grid.z, grid.y, grid.x)
    local = np.degrees(np.arctan(np.hypot(slope_x, slope_y)))
    cut = np.column_stack([grid.x, np.zeros_like(grid.x)])
    cut_residual = grid.elevation(cut) - plane.elevation(cut)
    return {"mean_elevation_m": float(vertices[:, 2].mean()),
            "plane_gradient": [float(-plane.normal[0] / plane.normal[2]),
                               float(-plane.normal[1] / plane.normal[2])],
            "plane_slope_deg": float(np.degrees(plane.slope_angle())),
            "roughness_rms_m": float(residual.std()), "roughness_range_m": float(np.ptp(residual)),
            "cut_y0_roughness_rms_m": float(cut_residual.std()),
            "cut_y0_roughness_range_m": float(np.ptp(cut_residual)),
            "local_slope_deg_median": float(np.median(local)), "local_slope_deg_max": float(local.max()),
            "elevation_range_m": [float(grid.z.min()), float(grid.z.max())]}


def line_on(seabed, elements, anchor_xy=ANCHOR_XY):
    """The Table 5 line from its anchor resting on ``seabed`` at anchor_xy to the circle's centre."""
    anchor = (anchor_xy[0], anchor_xy[1], float(seabed.elevation(np.array([anchor_xy]))[0]))
    return Line("line1", anchor, CENTRE, (Segment(table5_chain(), LENGTH, elements),), 1)


def scene_on(seabed, name, elements, dt, duration, every):
    """The Sec. 5 scene on ``seabed``: Table 5 line and friction, circular fairlead motion."""
    return Scene(name=name, lines=[line_on(seabed, elements)], seabed=seabed, contact=CONTACT,
                 environment=ENVIRONMENT, friction=FRICTION, motion=MOTION,
                 solver=Solver(integrator="bdf2", dt=dt, duration=duration),
                 output=Output(dir="out", every=every), notes=[f"desire2023 Sec. 5: {name}"])


def run_scene_quiet(scene, out_dir):
    """``run_scene`` without a progress bar; (summary, error message or None)."""
    from cablefem.runs.run import run_scene

    try:
        return run_scene(scene, str(out_dir), progress=False), None
    except Exception as failure:  # a solver failure is a result here, recorded in the table
        summary = json.loads((Path(out_dir) / "summary.json").read_text())
        return summary, f"{type(failure).__name__}: {failure}"


def frame_at(out_dir, t):
    """(time [s], line points (m, 3) [m], seabed gap (m,) [m]) of the output frame nearest t."""
    import meshio

    from cablefem.io.vtk import read_collection

    times, files = read_collection(str(next(Path(out_dir).glob("*.pvd"))))
    k = int(np.argmin(np.abs(times - t)))
    mesh = meshio.read(files[k])
    return float(times[k]), mesh.points, mesh.point_data["seabed_gap"]


def touchdown(points, gap):
    """(x [m], arc position along the polyline [m]) of the touchdown: the last point from the
    anchor with d_G <= 0, refined linearly to d_G = 0 towards the next point; NaNs without contact."""
    touching = np.flatnonzero(gap <= 0.0)
    if touching.size == 0:
        return float("nan"), float("nan")
    k = touching[-1]
    chord = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])
    if k == len(gap) - 1:
        return float(points[k, 0]), float(chord[k])
    w = gap[k] / (gap[k] - gap[k + 1])
    return (float(points[k, 0] + w * (points[k + 1, 0] - points[k, 0])),
            float(chord[k] + w * (chord[k + 1] - chord[k])))


def grounded_length(points, gap):
    """Length [m] of the polyline in contact (d_G <= 0), linear in d_G along each segment."""
    lengths = np.linalg.norm(np.diff(points, axis=0), axis=1)
    g0, g1 = gap[:-1], gap[1:]
    both = (g0 <= 0) & (g1 <= 0)
    one = (g0 <= 0) != (g1 <= 0)
    fraction = np.where(one, np.where(g0 <= 0, g0, g1) / np.where(one, g0 - g1, 1.0), 0.0)
    return float(lengths[both].sum() + (np.abs(fraction) * lengths)[one].sum())


def setup_description():
    """The choices of this study, for results.json."""
    return {"smoothness": SMOOTHNESS, "levels": LEVELS, "nodes_per_side": 2 ** LEVELS + 1, "extent_m": EXTENT,
            "amplitude_m": AMPLITUDE, "tilt": TILT, "mean_depth_m": MEAN_DEPTH, "anchor_xy_m": ANCHOR_XY,
            "circle_centre_m": CENTRE, "radius_m": MOTION.radius, "period_s": MOTION.period,
            "ramp_s": MOTION.ramp, "snapshot_t_s": SNAPSHOT_T, "steady_from_s": STEADY_FROM,
            "ground_stiffness_N_m3": CONTACT.stiffness, "friction_mu": FRICTION.mu,
            "friction_v_threshold_m_s": FRICTION.v_threshold}
