"""cablefem against MoorDyn-C on the same MoorDyn input files: the flat flume cases of desire2023
and the three-line semi-taut system of housner2022 over flat and 12.5 % sloped seabeds.

Run ``python -m validation.moordyn.run [--fast] [--out DIR]``; ``run(fast=True)`` returns the
numbers tests/test_validation_moordyn.py asserts on. The README has the case definitions, the
choices and the latest numbers.

1. Same scenes, one input file: each case is ONE MoorDyn v2 file (``inputs/``, written by
   ``write_inputs``) that MoorDyn runs (``peer.run_moordyn``) and cablefem reads through a TOML
   that adds the motion (``[moordyn] file = ...``). Both codes' settings are checked by doubling
   the time step and halving the segments/elements (``convergence_check``).
2. Fairlead tension series of both codes per case, differences over the last two periods
   (RMS, largest, mean and peak, relative to the mean tension) and wall times.
3. Physics differences switched off one at a time (``switches``; OPTIONS rewritten for both).
"""

import argparse
import json
import pickle
import sys
import tempfile
import textwrap
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # python validation/moordyn/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.dynamics import INTEGRATORS  # noqa: E402
from cablefem.errors import ConvergenceError  # noqa: E402
from cablefem.geometry.generators import slope  # noqa: E402
from cablefem.geometry.readers import moordyn_c  # noqa: E402
from cablefem.line import Line, Segment  # noqa: E402
from cablefem.loads.added_mass import AddedMass  # noqa: E402
from cablefem.loads.contact import SeabedContact  # noqa: E402
from cablefem.loads.drag import Drag  # noqa: E402
from cablefem.motion import fairlead_motion  # noqa: E402
from cablefem.run import boundary_path, build_system, start_states  # noqa: E402
from cablefem.io import load_scene  # noqa: E402
from cablefem.statics import solve_static  # noqa: E402
from cablefem.scenes import FLUME_ANCHOR, FLUME_DEPTH, FLUME_MOTIONS, table5_chain  # noqa: E402

from validation.moordyn import peer  # noqa: E402
from validation.moordyn.switches import PerUnstretchedLength, TwoSidedDamping, VerticalSeabed  # noqa: E402

HERE = Path(__file__).resolve().parent
MN = 1e6
WATER_DENSITY, GRAVITY = 1025.0, 9.81

# ----------------------------------------------------------------------------- input files
#: flume (desire2023 Table 5, Sec. 4): 635 m chain, anchor 595 m from the fairlead at the origin
FLUME_LENGTH = 635.0
FLUME_FILE_SEGMENTS = 40  # NumSegs written in the file; FricDamp is for this node length
FLUME_KBOT = 3.0e5  # N/m^3, the built-in flume scenes' ground stiffness
FLUME_MU, FLUME_V_THRESHOLD = 0.3, 0.01  # isotropic friction of the built-in flume scenes

#: housner2022 Sec. 3.1: VolturnUS-S semi-taut moorings, 850 m mean depth
HOUSNER_DEPTH = 850.0
HOUSNER_FAIRLEAD_RADIUS, HOUSNER_FAIRLEAD_DEPTH = 58.0, 14.0  # m; 14 m draft of VolturnUS-S fairleads
HOUSNER_ANCHOR_RADIUS = 1130.0
HOUSNER_HEADINGS = (180.0, 60.0, 300.0)  # deg from +x: line 1 runs towards -x
HOUSNER_CHAIN_LENGTH, HOUSNER_ROPE_LENGTH = 500.0, 1000.0
HOUSNER_GRADE = 0.125
HOUSNER_GRID_HALF_WIDTH, HOUSNER_GRID_NODES = 1200.0, 25  # +-1200 m, 100 m spacing
HOUSNER_SEABEDS = ("flat", "upslope", "downslope", "sideslope")
#: rise direction (azimuth [deg]) of each slope: up-/down-slope along line 1, side-slope across it
HOUSNER_RISE_AZIMUTH = {"upslope": 180.0, "downslope": 0.0, "sideslope": 90.0}
#: beta [s] of both line types: about critical for a 25 m segment (MoorDyn's usual BA = -1 at the
#: reference segmentation), written as BA = beta EA [N s] so that it does not change with NumSegs
HOUSNER_BETA = 0.01
#: platform motion (our choice; housner2022 prescribed OpenFAST motions in regular waves of
#: 14.9 s, 9.3 m at 90 deg): a rigid surge + sway harmonic of the three fairleads
HOUSNER_PERIOD = 14.9
HOUSNER_AMPLITUDE = (4.0, 4.0, 0.0)


def line_type_120mm_chain():
    """MoorPy's default-library properties of 120 mm R4 studless chain (dict of MoorDyn columns)."""
    d = 0.120
    return {"Diam": 1.80 * d, "MassDen": 20.0e3 * d**2, "EA": 85.6e9 * d**2 - 3.93e7 * d**3,
            "Cd": 1.333, "Ca": 1.0, "CdAx": 0.639, "CaAx": 0.5}


def line_type_186mm_polyester():
    """MoorPy's default-library properties of 186 mm polyester rope (quasi-static EA = 14 MBL)."""
    d = 0.186
    mass = 679.0 * d**2
    return {"Diam": float(np.sqrt(4.0 * mass / (np.pi * 1380.0))), "MassDen": mass,
            "EA": 14.0 * 308e6 * d**2, "Cd": 2.021, "Ca": 1.1, "CdAx": 0.2, "CaAx": 0.15}


def _type_row(name, props, beta):
    p = dict(props)
    return (f"{name:<10} {p['Diam']!r:<20} {p['MassDen']!r:<20} {p['EA']!r:<22} {beta * p['EA']!r:<22} 0.0  "
            f"{p['Cd']!r:<6} {p['Ca']!r:<5} {p['CdAx']!r:<20} {p['CaAx']!r}")


TYPE_HEADER = ("----------------------- LINE TYPES ------------------------------------------\n"
               "TypeName   Diam                 Mass/m               EA                     BA                     "
               "EI   Cd     Ca    CdAx                 CaAx\n"
               "(name)     (m)                  (kg/m)               (N)                    (N-s)                  "
               "(-)  (-)    (-)   (-)                  (-)\n")
POINT_HEADER = ("---------------------- POINTS ------------------------------------------------\n"
                "ID  Attachment  X                     Y                     Z                     M  V  CdA  CA\n"
                "(-) (-)         (m)                   (m)                   (m)                   (kg) (m^3) (m^2) (-)\n")
LINE_HEADER = ("---------------------- LINES -------------------------------------------------\n"
               "ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  Outputs\n"
               "(-) (-)       (-)      (-)      (m)       (-)      (-)\n")
OPTIONS_HEADER = "---------------------- OPTIONS -----------------------------------------------\n"
OUTPUTS = ("---------------------- OUTPUTS -----------------------------------------------\n"
           "{channels}\n"
           "------------------------- need this line (MoorDyn 2.7 crashes on a file ending in OPTIONS) ---\n")
#: MoorDyn's initial-condition solve, tightened from its 1e-3 default (see README)
IC_OPTIONS = "1e-5                  threshIC      - relative tension change for a converged initial condition\n" \
             "600.0                 TmaxIC        - s\n"
#: housner: dynamic relaxation (MoorDyn 2.7's default stationary solver stops at 40 kN instead
#: of the 200 kN equilibrium for chain + polyester joined through a free point), with checks 10 s
#: apart and unscaled drag (2 s checks with CdScaleIC = 5 stop while the chain still creeps down
#: the slope: 49.7 kN for the upslope line 1 against its 64.2 kN equilibrium; README)
IC_DYNAMIC = "1                     ICgenDynamic  - dynamic relaxation\n" \
             "10.0                  dtIC          - s between convergence checks\n" \
             "1.0                   CdScaleIC     - drag scale during the relaxation\n"


def _number(value):
    """A coordinate as file text: rounded to 1e-9 m (no 1e-13 residues of cos 90 deg), full precision."""
    return repr(float(np.round(value, 9)) + 0.0)


def _point_row(pid, kind, xyz):
    x, y, z = (_number(c) for c in xyz)
    return f"{pid:<3} {kind:<11} {x:<21} {y:<21} {z:<21} 0  0  0    0\n"


def flume_text(segments=FLUME_FILE_SEGMENTS):
    """The flat flume case (desire2023 Table 5 chain, 100 m, anchor at x = -595 m) as MoorDyn v2 text."""
    chain = table5_chain()
    props = {"Diam": chain.diameter, "MassDen": chain.mass, "EA": chain.EA, "Cd": chain.Cd_normal,
             "Ca": chain.Ca_normal, "CdAx": chain.Cd_tangential / np.pi, "CaAx": chain.Ca_tangential}
    weight = chain.submerged_weight(WATER_DENSITY, GRAVITY)
    critical = 2.0 * np.sqrt(FLUME_KBOT * chain.mass / chain.diameter)  # damping ratio 1 of Eq. 11, per area
    fric_damp = weight * FLUME_LENGTH / segments / FLUME_V_THRESHOLD  # a resting node saturates at v_threshold
    return ("--------------------- MoorDyn Input File ------------------------------------\n"
            "desire2023 flume, flat seabed, prototype scale (Table 5 chain); validation/moordyn\n"
            + TYPE_HEADER + _type_row("chain", props, chain.damping) + "\n"
            + POINT_HEADER + _point_row(1, "Fixed", FLUME_ANCHOR) + _point_row(2, "Coupled", (0.0, 0.0, 0.0))
            + LINE_HEADER + f"1   chain     1        2        {FLUME_LENGTH!r}     {segments}       -\n"
            + OPTIONS_HEADER
            + "0.0001                dtM           - s, MoorDyn's explicit step\n"
            + f"{FLUME_DEPTH!r:<21} WtrDpth       - m\n"
            + f"{WATER_DENSITY!r:<21} WtrDnsty      - kg/m^3\n"
            + f"{GRAVITY!r:<21} g             - m/s^2\n"
            + f"{FLUME_KBOT!r:<21} kBot          - N/m^3\n"
            + f"{float(critical)!r:<21} cBot          - N s/m^3: 2 sqrt(kBot m / d), critical\n"
            + f"{FLUME_MU!r:<21} FrictionCoefficient\n"
            + f"{float(fric_damp)!r:<21} FricDamp      - N s/m: a resting node reaches mu F_n at {FLUME_V_THRESHOLD} m/s\n"
            + "1.0                   StatDynFricScale\n"
            + IC_OPTIONS
            + OUTPUTS.format(channels="FairTen1\nAnchTen1"))


def housner_grid(kind):
    """The 12.5 % slope ``kind`` of housner2022 as a DepthGrid over +-1200 m (700-1000 m deep)."""
    extent = ((-HOUSNER_GRID_HALF_WIDTH, HOUSNER_GRID_HALF_WIDTH),) * 2
    return slope(np.arctan(HOUSNER_GRADE), np.radians(HOUSNER_RISE_AZIMUTH[kind]), depth=HOUSNER_DEPTH,
                 extent=extent, nodes=HOUSNER_GRID_NODES)


def housner_points(kind):
    """Anchors (3, 3) and fairleads (3, 3) [m] of the three lines over seabed ``kind``."""
    angles = np.radians(HOUSNER_HEADINGS)
    unit = np.column_stack([np.cos(angles), np.sin(angles), np.zeros(3)])
    fairleads = HOUSNER_FAIRLEAD_RADIUS * unit + [0.0, 0.0, -HOUSNER_FAIRLEAD_DEPTH]
    anchors = np.round(HOUSNER_ANCHOR_RADIUS * unit, 9)  # as written in the file
    fairleads = np.round(fairleads, 9)
    if kind == "flat":
        anchors[:, 2] = -HOUSNER_DEPTH
    else:
        anchors[:, 2] = housner_grid(kind).elevation(anchors[:, :2])
    return anchors, fairleads


def housner_text(kind, chain_segments=20, rope_segments=40):
    """The three-line semi-taut system over seabed ``kind`` as MoorDyn v2 text (SeafloorFile
    ``housner_<kind>_bathymetry.txt`` beside it for the slopes)."""
    anchors, fairleads = housner_points(kind)
    points = "".join(_point_row(i + 1, "Fixed", a) for i, a in enumerate(anchors))
    points += "".join(_point_row(i + 4, "Coupled", f) for i, f in enumerate(fairleads))
    points += "".join(_point_row(i + 7, "Free", a + HOUSNER_CHAIN_LENGTH / np.linalg.norm(f - a) * (f - a))
                      for i, (a, f) in enumerate(zip(anchors, fairleads)))
    lines = "".join(f"{i + 1}   chain     {i + 1}        {i + 7}        {HOUSNER_CHAIN_LENGTH!r}     "
                    f"{chain_segments}       -\n" for i in range(3))
    lines += "".join(f"{i + 4}   polyester {i + 7}        {i + 4}        {HOUSNER_ROPE_LENGTH!r}    "
                     f"{rope_segments}       -\n" for i in range(3))
    seabed = (f"{HOUSNER_DEPTH!r:<21} WtrDpth       - m\n" if kind == "flat" else
              f"{HOUSNER_DEPTH!r:<21} WtrDpth       - m, mean depth (the grid gives the seabed)\n"
              f"housner_{kind}_bathymetry.txt SeafloorFile\n")
    return ("--------------------- MoorDyn Input File ------------------------------------\n"
            f"housner2022 Sec. 3.1 semi-taut three-line system (VolturnUS-S), {kind} seabed; "
            "validation/moordyn\nno kBot/cBot: MoorDyn's defaults 3e6 N/m^3 and 3e5 N s/m^3; no friction\n"
            + TYPE_HEADER + _type_row("chain", line_type_120mm_chain(), HOUSNER_BETA) + "\n"
            + _type_row("polyester", line_type_186mm_polyester(), HOUSNER_BETA) + "\n"
            + POINT_HEADER + points + LINE_HEADER + lines + OPTIONS_HEADER
            + "0.0005                dtM           - s\n" + seabed
            + f"{WATER_DENSITY!r:<21} WtrDnsty      - kg/m^3\n"
            + f"{GRAVITY!r:<21} g             - m/s^2\n"
            + IC_OPTIONS + IC_DYNAMIC
            + OUTPUTS.format(channels="FairTen4\nFairTen5\nFairTen6"))


def _motion_toml(motion):
    vector = lambda v: "[" + ", ".join(repr(float(x)) for x in v) + "]"  # noqa: E731
    return ("[motion]\nkind = \"harmonic\"\n"
            f"amplitude = {vector(motion['amplitude'])}\nperiod = {motion['period']!r}\n"
            f"offset = {vector(motion['offset'])}\nramp = {motion['ramp']!r}\n")


def case_motions():
    """Per case name: the motion as a dict of [motion] keys (harmonic, ramped in over one period)."""
    motions = {f"flume-{name}": {"amplitude": m.amplitude, "period": m.period, "offset": m.offset,
                                 "ramp": m.ramp} for name, m in FLUME_MOTIONS.items()}
    for kind in HOUSNER_SEABEDS:
        motions[f"housner-{kind}"] = {"amplitude": HOUSNER_AMPLITUDE, "period": HOUSNER_PERIOD,
                                      "offset": (0.0, 0.0, 0.0), "ramp": HOUSNER_PERIOD}
    return motions


def case_title(case):
    """One line saying what a case is (figure titles, README)."""
    if case.startswith("flume"):
        m = FLUME_MOTIONS[case.split("-", 1)[1]]
        return (f"{case}: desire2023 Table 5 chain (635 m) over a flat seabed 100 m deep; fairlead surge "
                f"{m.amplitude[0]:g} m, period {m.period:g} s"
                + (f", about a {m.offset[0]:g} m drift" if m.offset[0] else ", no drift"))
    kind = case.split("-", 1)[1]
    depths = ", ".join(f"{-z:.0f}" for z in housner_points(kind)[0][:, 2])
    where = {"flat": "flat seabed", "upslope": "12.5 % slope rising towards line 1's anchor",
             "downslope": "12.5 % slope falling towards line 1's anchor",
             "sideslope": "12.5 % slope across line 1, rising towards line 2's anchor"}[kind]
    return (f"{case}: housner2022 semi-taut system (500 m chain + 1000 m polyester), {where}; anchor depths "
            f"{depths} m (lines 1-3); platform surge = sway = {HOUSNER_AMPLITUDE[0]:g} m, period {HOUSNER_PERIOD:g} s")


def case_file(case):
    """The MoorDyn file name of a case (flume cases share one file)."""
    return "flume_flat.dat" if case.startswith("flume") else f"housner_{case.split('-')[1]}.dat"


def write_inputs(folder):
    """Write every input file (MoorDyn .dat, MoorDyn-C SeafloorFile grids, TOML wrappers) into
    ``folder``; returns {case: toml path}."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "flume_flat.dat").write_text(flume_text())
    for kind in HOUSNER_SEABEDS:
        (folder / f"housner_{kind}.dat").write_text(housner_text(kind))
        if kind != "flat":
            moordyn_c.write(folder / f"housner_{kind}_bathymetry.txt", housner_grid(kind))
    tomls = {}
    for case, motion in case_motions().items():
        path = folder / f"{case}.toml"
        path.write_text(f"# {case}: the MoorDyn file as is, with the fairlead motion MoorDyn's file has no "
                        f"place for\nname = \"{case}\"\n\n[moordyn]\nfile = \"{case_file(case)}\"\n\n"
                        + _motion_toml(motion))
        tomls[case] = path
    return tomls


# ----------------------------------------------------------------------------- settings
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


# ----------------------------------------------------------------------------- runners
def moordyn_motion(scene, points):
    """``motion(t)`` for the peer: every coupled point (k, 3) [m] moved rigidly by the scene's motion."""
    def motion(t):
        d, v, _ = fairlead_motion(scene.motion, t)
        return points + d, np.broadcast_to(v, points.shape)
    return motion


def run_moordyn_case(path, scene, duration, settings, options=None, initial_state=None, coupling_dt=COUPLING_DT):
    """MoorDyn on ``path`` with the scene's motion, coupled every ``coupling_dt`` [s]: dict of t (n,),
    forces (n, k, 3) [N] (the peer's, end-node inertia not subtracted), forces_on_point (n, k, 3)
    (end-node inertia subtracted), wall times [s], and the coupled points' positions (k, 3)."""
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
                              ic_dtM=settings["ic_dtM"], initial_state=initial_state)
    acceleration = np.array([fairlead_motion(scene.motion, t)[2] for t in result["t"]])
    result["forces_on_point"] = result["forces"] - np.einsum("nkab,nb->nka", result["end_mass"], acceleration)
    result["points"] = points
    return result


def refined(scene, factor):
    """The scene with every segment's element count times ``factor``."""
    lines = [Line(line.name, line.anchor, line.fairlead,
                  [Segment(seg.type, seg.length, int(seg.elements * factor)) for seg in line.segments], line.order)
             for line in scene.lines]
    return replace(scene, lines=lines)


def run_cablefem_case(scene, duration, dt, hydro_per_unstretched=False, lumped=False, retries=2,
                      two_sided_damping=False):
    """cablefem's BDF2 on ``scene`` (statics at t = 0, then steps of dt [s]): dict of t (n,),
    forces (n, lines, 3) [N] on the fairleads, wall_time_s, init_time_s, newton_iterations, dt
    as run, ``failures`` (messages) and ``start`` (how the statics converged). A run whose Newton
    fails even after the integrator's own step halving is rerun from the start with dt / 2, up to
    ``retries`` times, and says so (README, "Problems found"). ``two_sided_damping``: MoorDyn-C's
    seabed damping, acting also on a penetrating point that moves out (``switches``)."""
    start = time.perf_counter()
    states, how = static_start(scene)
    initialised = time.perf_counter()
    failures = []
    while True:
        try:
            result = _cablefem_steps(scene, states, duration, dt, hydro_per_unstretched, lumped, two_sided_damping)
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
    """Static equilibrium of every line at t = 0 (``cablefem.run.start_states``) and how it was
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


def _cablefem_steps(scene, states, duration, dt, hydro_per_unstretched, lumped, two_sided_damping=False):
    """Step every line from ``states`` by dt [s] up to ``duration`` [s]; the run's dict."""
    integrators = []
    for line, X0 in zip(scene.lines, states):
        system = build_system(scene, line)
        if hydro_per_unstretched:
            system.loads = [PerUnstretchedLength(load) if isinstance(load, (Drag, AddedMass)) else load
                            for load in system.loads]
        if two_sided_damping:
            system.loads = [TwoSidedDamping(load) if isinstance(load, SeabedContact) else load
                            for load in system.loads]
        integrators.append(INTEGRATORS[scene.solver.integrator](
            system, X0, boundary_path(scene, line), dt=dt, tolerance=scene.solver.tolerance,
            newton="full", lumped=lumped,  # one Newton for the compiled and the numpy path
            # wrapped loads have no compiled face: the numpy path
            compiled=not (hydro_per_unstretched or two_sided_damping)))
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


# ----------------------------------------------------------------------------- comparison
def differences(t, reference, other, t_from):
    """Statistics of two tension series (n,) [N] over t >= t_from [s], relative to the
    reference's mean: RMS and largest difference, difference of the means and of the peaks."""
    window = t >= t_from - 1e-9
    a, b = reference[window], other[window]
    mean = float(a.mean())
    return {"reference_mean_N": mean, "other_mean_N": float(b.mean()),
            "reference_max_N": float(a.max()), "other_max_N": float(b.max()),
            "reference_min_N": float(a.min()), "other_min_N": float(b.min()),
            "rms": float(np.sqrt(np.mean((b - a) ** 2)) / mean),
            "max": float(np.max(np.abs(b - a)) / mean),
            "mean": float((b.mean() - a.mean()) / mean),
            "peak": float((b.max() - a.max()) / mean),
            "trough": float((b.min() - a.min()) / mean)}


def on_grid(t, series, grid):
    """Series (n, ...) sampled at times t (n,) interpolated to times grid (m,)."""
    flat = series.reshape(len(t), -1)
    return np.column_stack([np.interp(grid, t, column) for column in flat.T]).reshape((len(grid),) + series.shape[1:])


def compare_runs(moordyn, cablefem, order, t_from, use_point_force=False):
    """Per line (MoorDyn point order): ``differences`` of cablefem against MoorDyn on cablefem's times
    (or MoorDyn's, whichever is coarser)."""
    grid = cablefem["t"] if len(cablefem["t"]) <= len(moordyn["t"]) else moordyn["t"]
    md_forces = moordyn["forces_on_point"] if use_point_force else moordyn["forces"]
    md = np.linalg.norm(on_grid(moordyn["t"], md_forces, grid), axis=2)
    cf = on_grid(cablefem["t"], cablefem["tensions"], grid)
    return [differences(grid, md[:, k], cf[:, line], t_from) for k, line in enumerate(order)]


def self_differences(first, second, t_from, key="tensions"):
    """Per column: ``differences`` of two runs of one code (second against first) on the coarser grid."""
    grid = first["t"] if len(first["t"]) <= len(second["t"]) else second["t"]
    a = on_grid(first["t"], first[key], grid)
    b = on_grid(second["t"], second[key], grid)
    return [differences(grid, a[:, k], b[:, k], t_from) for k in range(a.shape[1])]


def periodicity(run, columns, t_end, period, scales):
    """Per column of run["tensions"]: change of the mean, max and min from the second-to-last period
    before t_end [s] to the last one, over scales (k,) [N]: how far the window is from periodic."""
    t = run["t"]
    last = (t >= t_end - period - 1e-9) & (t <= t_end + 1e-9)
    before = (t >= t_end - 2 * period - 1e-9) & (t <= t_end - period + 1e-9)
    rows = []
    for column, scale in zip(columns, scales):
        a, b = run["tensions"][before, column], run["tensions"][last, column]
        rows.append({"mean": float((b.mean() - a.mean()) / scale), "max": float((b.max() - a.max()) / scale),
                     "min": float((b.min() - a.min()) / scale)})
    return rows


def worst(rows, key):
    """Largest |value| of ``key`` over rows (lines)."""
    return float(max(abs(r[key]) for r in rows))


# ----------------------------------------------------------------------------- the study
def flume_variant_file(folder, name, **changes):
    """A variant of the flume file in ``folder`` (``kbot=None`` drops kBot: MoorDyn's and cablefem's
    default 3e6 N/m^3; ``fairlead_z`` [m] moves the coupled point); returns its path."""
    text = flume_text()
    if changes.get("kbot", 0.0) is None:
        text = "\n".join(row for row in text.splitlines() if " kBot " not in row) + "\n"
    if "fairlead_z" in changes:
        text = text.replace(_point_row(2, "Coupled", (0.0, 0.0, 0.0)),
                            _point_row(2, "Coupled", (0.0, 0.0, changes["fairlead_z"])))
    path = Path(folder) / name
    path.write_text(text)
    return path


def _timing(md, cf):
    return {"moordyn_wall_time_s": md["wall_time_s"], "moordyn_init_time_s": md["init_time_s"],
            "cablefem_wall_time_s": cf["wall_time_s"], "cablefem_init_time_s": cf["init_time_s"],
            "cablefem_steps": cf["steps"], "cablefem_newton_iterations": cf["newton_iterations"],
            "cablefem_rejected_steps": cf["rejected_steps"], "cablefem_dt": cf["dt"],
            "cablefem_failures": cf["failures"], "cablefem_start": cf["start"]}


def run_case(case, toml, fast, log=print):
    """Reference comparison of one case, its convergence checks (full) and its physics switches."""
    scene = load_scene(toml)
    path = Path(toml).parent / case_file(case)
    s = settings_for(case, fast)
    period = scene.motion.period
    duration = scene.motion.ramp + s["periods"] * period
    t_from = duration - min(WINDOW_PERIODS, s["periods"]) * period
    cf_scene = refined(scene, s["elements"])
    log(f"{case}: {duration:g} s, MoorDyn x{s['segments']} segments dtM {s['dtM']:g} s, "
        f"cablefem x{s['elements']} elements dt {s['dt']:g} s")
    md = run_moordyn_case(path, scene, duration, s)
    cf = run_cablefem_case(cf_scene, duration, s["dt"])
    order = point_order(scene, md["points"])
    names = [scene.lines[i].name for i in order]
    entry = {"case": case, "title": case_title(case), "file": path.name, "settings": s, "duration_s": duration, "window_s": [t_from, duration],
             "period_s": period, "lines": names, "moordyn_segments": md["segments"],
             "cablefem_elements": {line.name: [seg.elements for seg in line.segments] for line in cf_scene.lines},
             "seabed": scene.seabed.describe(), **_timing(md, cf),
             "differences": compare_runs(md, cf, order, t_from),
             "differences_point_force": compare_runs(md, cf, order, t_from, use_point_force=True)}
    if s["periods"] >= 2:
        scales = [d["reference_mean_N"] for d in entry["differences"]]
        entry["periodicity"] = {"moordyn": periodicity(md, range(len(order)), duration, period, scales),
                                "cablefem": periodicity(cf, order, duration, period, scales)}
    series = {"moordyn": md, "cablefem": cf, "order": order}
    log(f"  MoorDyn {md['wall_time_s']:.1f} s, cablefem {cf['wall_time_s']:.1f} s; "
        + "; ".join(f"{n} mean {r['mean']:+.2e} peak {r['peak']:+.2e} rms {r['rms']:.2e}"
                    for n, r in zip(names, entry["differences"])))
    if cf["failures"]:
        log(f"  cablefem reran at dt = {cf['dt']:g} s: {cf['failures']}")

    switches = {}
    flume = case.startswith("flume")

    def both(name, md_options=None, cf_scene_variant=None, md_path=None, md_scene=None, md_result=None,
             md_settings=None, md_initial_state=None, cf_result=None, **cf_flags):
        try:
            md_v = md_result if md_result is not None else md if md_options is None and md_path is None else \
                run_moordyn_case(md_path or path, md_scene or scene, duration, md_settings or s, md_options,
                                 initial_state=md_initial_state)
            cf_v = cf_result if cf_result is not None else cf if cf_scene_variant is None and not cf_flags else \
                run_cablefem_case(cf_scene_variant if cf_scene_variant is not None else cf_scene, duration, s["dt"],
                                  **cf_flags)
        except (ConvergenceError, RuntimeError) as error:  # recorded, and the study goes on
            switches[name] = {"error": f"{type(error).__name__}: {error}"}
            log(f"  switch {name} failed: {error}")
            return None
        rows = compare_runs(md_v, cf_v, order, t_from)
        switches[name] = {"differences": rows,
                          "moordyn_change": self_differences(md, md_v, t_from) if md_v is not md else None,
                          "cablefem_change": [self_differences(cf, cf_v, t_from)[i] for i in order]
                          if cf_v is not cf else None,
                          "moordyn_wall_time_s": md_v["wall_time_s"], "cablefem_wall_time_s": cf_v["wall_time_s"],
                          "cablefem_dt": cf_v["dt"], "cablefem_failures": cf_v["failures"],
                          "cablefem_start": cf_v["start"]}
        series[name] = {"moordyn": md_v, "cablefem": cf_v}
        log(f"  switch {name}: " + "; ".join(f"{n} mean {r['mean']:+.2e} peak {r['peak']:+.2e} rms {r['rms']:.2e}"
                                             for n, r in zip(names, rows)))
        if cf_v.get("failures"):
            log(f"  cablefem reran {name} at dt = {cf_v['dt']:g} s: {cf_v['failures']}")
        return md_v

    if not case.endswith("flat") and not flume:
        both("vertical_contact", cf_scene_variant=replace(cf_scene, seabed=VerticalSeabed(cf_scene.seabed)))
    if not fast and flume:
        both("no_seabed_damping", md_options={"cBot": 0.0},
             cf_scene_variant=replace(cf_scene, contact=replace(cf_scene.contact, damping=0.0)))
        both("no_friction", md_options={"FrictionCoefficient": 0.0},
             cf_scene_variant=replace(cf_scene, friction=replace(cf_scene.friction, model="none")))
        both("hydrodynamics_per_unstretched_length", hydro_per_unstretched=True)
        both("cdax_not_converted", cf_scene_variant=_unconverted_cdax(cf_scene))
        if case == "flume-dynamic":
            both("lumped_mass", lumped=True)  # MoorDyn's nodes carry lumped masses
        if case == "flume-quasi-static":
            with tempfile.TemporaryDirectory(prefix="moordyn-variant-") as folder:
                variant = flume_variant_file(folder, "flume_flat_kbot_default.dat", kbot=None)
                default_scene = replace(load_scene(variant), motion=scene.motion)
                md_default = both("kbot_default", md_path=variant, md_scene=default_scene,
                                  cf_scene_variant=refined(default_scene, s["elements"]))
                both("cablefem_kbot_3e5_moordyn_default", md_result=md_default)
    if not fast and case == "housner-flat":
        both("hydrodynamics_per_unstretched_length", hydro_per_unstretched=True)
        both("cdax_not_converted", cf_scene_variant=_unconverted_cdax(cf_scene))
    if not fast and case == "housner-upslope":
        mu = 0.5
        chain = line_type_120mm_chain()
        weight = (chain["MassDen"] - WATER_DENSITY * np.pi / 4 * chain["Diam"] ** 2) * GRAVITY
        fric_damp = weight * HOUSNER_CHAIN_LENGTH / 20 / 0.01  # a resting chain node saturates at 0.01 m/s
        from cablefem.scene import Friction
        friction = Friction(model="isotropic", mu=mu, v_threshold=0.01, saturation_damping=fric_damp)
        md_friction = {"FrictionCoefficient": mu, "FricDamp": fric_damp / s["segments"]}
        # both codes start from the frictionless equilibrium (cablefem's statics have no friction;
        # MoorDyn loads the reference run's initial state): a relaxation under friction stops
        # wherever friction arrests the chain, which the last variant shows
        md_with_friction = both("friction", md_options=md_friction, md_initial_state=md["initial_state"],
                                cf_scene_variant=replace(cf_scene, friction=friction))
        cf_vertical_friction = replace(cf_scene, friction=friction, seabed=VerticalSeabed(cf_scene.seabed))
        if md_with_friction is not None:
            both("friction_vertical_contact", md_result=md_with_friction, cf_scene_variant=cf_vertical_friction)
        if "friction_vertical_contact" in series:
            # a resting node's friction damping, mu FricDamp / node mass ~ 430 1/s, makes MoorDyn's explicit
            # relaxation unstable at a 4e-3 s initial-condition step (NaN at t = 206 s): 1e-3 s
            both("friction_vertical_contact_moordyn_relaxed", md_options=md_friction,
                 md_settings=dict(s, ic_dtM=min(s["ic_dtM"], 1e-3)),
                 cf_result=series["friction_vertical_contact"]["cablefem"])
    entry["switches"] = switches

    if not fast and case in CONVERGENCE_CASES:
        try:
            entry["convergence"], series["check"] = convergence_check(case, path, scene, s, duration, t_from,
                                                                      order, md, cf, log)
        except (ConvergenceError, RuntimeError) as error:  # recorded, and the study goes on
            entry["convergence"] = {"error": f"{type(error).__name__}: {error}"}
            log(f"  convergence check failed: {error}")
    return entry, series


def convergence_check(case, path, scene, s, duration, t_from, order, md, cf, log=print):
    """Both codes rerun at the ``s["check"]`` resolution ("coarse": half the segments/elements,
    twice the steps; "fine": the reverse): the change of each line's tension statistics from the
    reference, and the two codes compared at that resolution. Returns (entry, series)."""
    factor = 0.5 if s["check"] == "coarse" else 2.0
    other = dict(s, segments=s["segments"] * factor, dtM=s["dtM"] / factor)
    # MoorDyn's initial-condition step: stable for the reference, so for a coarser run; a finer
    # one needs 1 / factor^2 of it where BA dominates
    other["ic_dtM"] = s["ic_dtM"] if factor < 1 else s["ic_dtM"] / factor**2
    elements, dt = s["elements"] * factor, s["dt"] / factor
    log(f"  convergence ({s['check']}): MoorDyn x{other['segments']:g} segments dtM {other['dtM']:g} s; "
        f"cablefem x{elements:g} elements dt {dt:g} s")
    md_other = run_moordyn_case(path, scene, duration, other)
    cf_other = run_cablefem_case(refined(scene, elements), duration, dt)
    entry = {
        "check": s["check"],
        "moordyn": {"settings": other, "segments": md_other["segments"], "wall_time_s": md_other["wall_time_s"],
                    "change": self_differences(md, md_other, t_from)},
        "cablefem": {"elements_factor": elements, "dt": cf_other["dt"], "wall_time_s": cf_other["wall_time_s"],
                     "failures": cf_other["failures"],
                     "change": [self_differences(cf, cf_other, t_from)[i] for i in order]},
        "differences": compare_runs(md_other, cf_other, order, t_from)}
    for code in ("moordyn", "cablefem"):
        rows = entry[code]["change"]
        log(f"  {code} change: " + "; ".join(f"mean {r['mean']:+.2e} peak {r['peak']:+.2e} rms {r['rms']:.2e}"
                                             for r in rows))
    log("  both at that resolution: " + "; ".join(f"mean {r['mean']:+.2e} peak {r['peak']:+.2e} rms {r['rms']:.2e}"
                                                  for r in entry["differences"]))
    return entry, {"moordyn": md_other, "cablefem": cf_other}


def _unconverted_cdax(scene):
    """The scene with Cd_tangential = MoorDyn's CdAx copied, not multiplied by pi (the mistake the
    reader avoids), to show what the conversion is worth."""
    types = {}
    lines = []
    for line in scene.lines:
        segments = []
        for seg in line.segments:
            kind = types.setdefault(seg.type.name, replace(seg.type, Cd_tangential=seg.type.Cd_tangential / np.pi))
            segments.append(Segment(kind, seg.length, seg.elements))
        lines.append(Line(line.name, line.anchor, line.fairlead, segments, line.order))
    return replace(scene, lines=lines)


def static_checks(inputs_folder, fast, log=print):
    """Static pretension of the flat flume line: MoorDyn (peer), held 5 s to show it is MoorDyn's own
    equilibrium, MoorPy's catenary (rigid seabed), cablefem; and, in full, the surface-piercing
    fairlead (z = 0 against z = -1 m) and a stiff seabed."""
    from moorpy.Catenary import catenary

    from cablefem.scene import Contact

    chain = table5_chain()
    weight = chain.submerged_weight(WATER_DENSITY, GRAVITY)
    path = Path(inputs_folder) / "flume_flat.dat"
    factor = 1 if fast else 4
    settings = {"segments": factor, "dtM": 4e-4, "ic_dtM": 4e-4}
    scene = load_scene(path)
    held = run_moordyn_case(path, scene, 5.0, settings)
    moordyn_static = float(held["tensions"][0, 0])
    hold_change = float(np.max(np.abs(held["tensions"][:, 0] - moordyn_static)) / moordyn_static)

    def moorpy(height):
        fAH, fAV, fBH, fBV, _ = catenary(-FLUME_ANCHOR[0], height, FLUME_LENGTH, chain.EA, weight, CB=0.0,
                                         Tol=1e-12, MaxIter=500)
        return float(np.hypot(fBH, fBV))

    def cablefem_static(scene, elements_factor):
        cf = run_cablefem_case(refined(scene, elements_factor), 0.0, 1.0)
        return float(cf["tensions"][0, 0])

    result = {"moordyn_segments": FLUME_FILE_SEGMENTS * factor, "moordyn_N": moordyn_static,
              "moordyn_hold_5s_change": hold_change, "moorpy_N": moorpy(FLUME_DEPTH),
              "cablefem_N": cablefem_static(scene, factor), "cablefem_elements": FLUME_FILE_SEGMENTS * factor}
    result["moordyn_vs_moorpy"] = result["moordyn_N"] / result["moorpy_N"] - 1
    result["cablefem_vs_moorpy"] = result["cablefem_N"] / result["moorpy_N"] - 1
    result["moordyn_vs_cablefem"] = result["moordyn_N"] / result["cablefem_N"] - 1
    if not fast:
        converged = cablefem_static(scene, 16)
        stiff = cablefem_static(replace(scene, contact=Contact(stiffness=3e9, damping=0.0)), 16)
        with tempfile.TemporaryDirectory(prefix="moordyn-variant-") as folder:
            below = flume_variant_file(folder, "flume_flat_fairlead_1m_below.dat", fairlead_z=-1.0)
            below_scene = load_scene(below)
            md_below = run_moordyn_case(below, below_scene, 0.0, settings)
        result.update({
            "cablefem_640_elements_N": converged, "cablefem_stiff_seabed_N": stiff,
            "seabed_elasticity": converged / stiff - 1,
            "moorpy_vs_cablefem_stiff_seabed": result["moorpy_N"] / stiff - 1,
            "fairlead_1m_below": {"moordyn_N": float(md_below["tensions"][0, 0]),
                                  "cablefem_N": cablefem_static(below_scene, factor)}})
        below_row = result["fairlead_1m_below"]
        below_row["moordyn_vs_cablefem"] = below_row["moordyn_N"] / below_row["cablefem_N"] - 1
    log(f"statics: MoorDyn {moordyn_static:.1f} N (held 5 s: {hold_change:.1e}), MoorPy {result['moorpy_N']:.1f} N "
        f"({result['moordyn_vs_moorpy']:+.2e}), cablefem {result['cablefem_N']:.1f} N")
    return result


def run(fast=False, out_dir=None, log=print):
    """The whole study; returns (results dict, series for the figures)."""
    out_dir = Path(out_dir or HERE)
    inputs = write_inputs(out_dir / "inputs")
    cases = ["flume-quasi-static", "housner-flat", "housner-upslope"] if fast else \
        ["flume-quasi-static", "flume-dynamic"] + [f"housner-{kind}" for kind in HOUSNER_SEABEDS]
    results = {"fast": fast, "coupling_dt_s": COUPLING_DT, "window_periods": WINDOW_PERIODS,
               "moordyn_version": _version("moordyn"), "cases": {}}
    series = {}
    start = time.perf_counter()
    _warm_up(inputs["flume-quasi-static"])
    for case in cases:
        results["cases"][case], series[case] = run_case(case, inputs[case], fast, log)
    results["statics"] = static_checks(out_dir / "inputs", fast, log)
    results["wall_time_s"] = time.perf_counter() - start
    return results, series


def _warm_up(toml):
    """Two steps of a small run, so that numba's compilation of cablefem's step kernel (cached on
    disk after the first run ever) is not counted in the first case's wall time."""
    run_cablefem_case(load_scene(toml), 0.1, 0.05)


def _version(name):
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version(name)
    except PackageNotFoundError:
        return None


# ----------------------------------------------------------------------------- output
#: how the figures draw each series: (label, colour, line style, width)
STYLES = {"moordyn": ("MoorDyn", "tab:blue", "-", 1.6), "cablefem": ("cablefem", "tab:red", "--", 1.2),
          "vertical": ("cablefem, MoorDyn's vertical contact", "black", ":", 1.4),
          "moordyn_relaxed": ("MoorDyn from its relaxation under friction", "tab:cyan", "-.", 1.2),
          "lumped": ("cablefem, lumped mass", "tab:green", "-.", 1.1)}
SWITCH_LABELS = {
    "vertical_contact": "contact vertical, friction horizontal, as MoorDyn-C",
    "friction": "friction mu = 0.5 on, both codes",
    "friction_vertical_contact": "friction mu = 0.5 on + contact vertical",
    "friction_vertical_contact_moordyn_relaxed": "as above, MoorDyn from its relaxation under friction",
    "no_seabed_damping": "seabed damping cBot = 0, both codes",
    "no_friction": "friction off, both codes",
    "hydrodynamics_per_unstretched_length": "drag, added mass per unstretched length, as MoorDyn",
    "cdax_not_converted": "CdAx read without the pi (cablefem; shows the conversion)",
    "lumped_mass": "lumped structural mass in cablefem, as MoorDyn's nodes",
    "kbot_default": "kBot = 3e6 N/m^3 (MoorDyn's default), both codes",
    "cablefem_kbot_3e5_moordyn_default": "kBot 3e5 in cablefem, 3e6 in MoorDyn",
}


def _difference_series(md, cf, k, line, scale):
    """Times and cablefem - MoorDyn tension of point k / cablefem line ``line`` on the coarser grid, over scale."""
    grid = cf["t"] if len(cf["t"]) <= len(md["t"]) else md["t"]
    return grid, (on_grid(cf["t"], cf["tensions"][:, line], grid) - on_grid(md["t"], md["tensions"][:, k], grid)) / scale


def _overlay(plt, entry, order, runs, title, path):
    """Rows per line: tensions of ``runs`` (list of (style key, MoorDyn-or-cablefem run, is_moordyn)) over
    the run, and each cablefem run minus the first MoorDyn run in % of MoorDyn's window mean; a case
    with one line gets a second row, the last period enlarged."""
    rows = [(k, line, False) for k, line in enumerate(order)]
    if len(order) == 1:
        rows.append((0, order[0], True))
    fig, axes = plt.subplots(len(rows), 2, figsize=(12, 2.7 * len(rows) + 0.9), squeeze=False,
                             gridspec_kw={"width_ratios": [1.35, 1]})
    t0, t1 = entry["window_s"]
    reference = next(run for _, run, is_md in runs if is_md)
    for (k, line, zoom), (left, right) in zip(rows, axes):
        mean = float(on_grid(reference["t"], reference["tensions"][:, k],
                             reference["t"][reference["t"] >= t0 - 1e-9]).mean())
        for key, run, is_md in runs:
            label, colour, style, width = STYLES[key]
            column = k if is_md else line
            left.plot(run["t"], run["tensions"][:, column] / MN, color=colour, ls=style, lw=width, label=label)
            if not is_md:
                grid, diff = _difference_series(reference, run, k, line, mean)
                right.plot(grid, 100 * diff, color=colour, ls=style, lw=width, label=f"{label} - MoorDyn")
        for ax in (left, right):
            ax.axvspan(t0, t1, color="0.92", zorder=0)
            ax.grid(alpha=0.3)
            ax.set_xlim((t1 - entry["period_s"], t1) if zoom else (0.0, t1))
        right.axhline(0.0, color="0.5", lw=0.6)
        left.set_ylabel(f"{entry['lines'][k]}\nfairlead tension [MN]")
        right.set_ylabel("difference [% of MoorDyn mean]")
        right.set_title(f"{entry['lines'][k]}: MoorDyn mean {mean / MN:.3f} MN over the shaded window"
                        + (", last period" if zoom else ""), fontsize=9)
    axes[0, 0].legend(loc="best", fontsize=8)
    axes[0, 1].legend(loc="best", fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("t [s]")
    fig.suptitle("\n".join(textwrap.wrap(title, 140, break_long_words=False)) if "\n" not in title else title,
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return Path(path).name


def _switch_summary(plt, results, path):
    """Bars: the largest |mean| and RMS difference over a case's lines, as run and with each switch."""
    rows = []
    for case, entry in results["cases"].items():
        for name, switch in entry["switches"].items():
            if "error" in switch:
                continue
            before, after = entry["differences"], switch["differences"]
            rows.append((f"{case}:\n{SWITCH_LABELS.get(name, name)}",
                         [max(abs(r[key]) for r in before) for key in ("mean", "rms")],
                         [max(abs(r[key]) for r in after) for key in ("mean", "rms")]))
    if not rows:
        return None
    height = 0.5 * len(rows) + 1.4
    fig, axes = plt.subplots(1, 2, figsize=(14, height), sharey=True)
    y = np.arange(len(rows))[::-1]
    for j, (ax, what) in enumerate(zip(axes, ("|mean|", "RMS"))):
        ax.barh(y + 0.2, [100 * max(r[1][j], 1e-5) for r in rows], height=0.38, color="0.65",
                label="as in the MoorDyn file")
        ax.barh(y - 0.2, [100 * max(r[2][j], 1e-5) for r in rows], height=0.38, color="tab:green",
                label="with the switch")
        ax.set_xscale("log")
        ax.set_xlim(5e-3, 300)
        ax.set_xlabel(f"{what} of cablefem - MoorDyn [% of MoorDyn mean],\nlargest over the lines")
        ax.axvline(1.0, color="0.3", lw=0.8, ls="--")
        ax.grid(alpha=0.3, axis="x", which="both")
    axes[0].set_yticks(y)
    axes[0].set_yticklabels([r[0] for r in rows], fontsize=8)
    axes[1].legend(loc="lower right", fontsize=8)
    fig.suptitle("Physics switches: fairlead tension difference over the last two periods, "
                 "before and after each switch (dashed: 1 %)", fontsize=10)
    fig.subplots_adjust(left=0.3, right=0.98, wspace=0.06, top=1 - 0.45 / height, bottom=0.85 / height)
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return Path(path).name


def figures(results, series, out_dir):
    """PNGs: per case the fairlead tension of both codes and their difference (slopes add cablefem
    with MoorDyn's vertical contact); the friction switch on the up-slope; the switch summary."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out_dir = Path(out_dir)
    written = []
    for case, entry in results["cases"].items():
        data = series[case]
        runs = [("moordyn", data["moordyn"], True), ("cablefem", data["cablefem"], False)]
        if "vertical_contact" in data:
            runs.append(("vertical", data["vertical_contact"]["cablefem"], False))
        if "lumped_mass" in data:
            runs.append(("lumped", data["lumped_mass"]["cablefem"], False))
        written.append(_overlay(plt, entry, data["order"], runs, entry["title"], out_dir / f"{case}.png"))
        if "friction" in data and "friction_vertical_contact" in data:
            runs = [("moordyn", data["friction"]["moordyn"], True), ("cablefem", data["friction"]["cablefem"], False),
                    ("vertical", data["friction_vertical_contact"]["cablefem"], False)]
            if "friction_vertical_contact_moordyn_relaxed" in data:
                runs.append(("moordyn_relaxed", data["friction_vertical_contact_moordyn_relaxed"]["moordyn"], True))
            written.append(_overlay(plt, entry, data["order"], runs,
                                    f"{case} with seabed friction mu = 0.5 in both codes (MoorDyn-C: isotropic "
                                    "saturated damping on the horizontal velocity), both from the frictionless "
                                    "equilibrium unless said",
                                    out_dir / f"{case}-friction.png"))
    summary = _switch_summary(plt, results, out_dir / "switches.png")
    if summary:
        written.append(summary)
    return written


def _pct(x):
    return f"{100 * x:+7.2f}%"


def report(results):
    """The tables as text: case differences and wall times, convergence, switches, statics."""
    out = ["Fairlead tension, cablefem - MoorDyn over the last periods, relative to MoorDyn's mean there",
           f"{'case':<19} {'line':<8} {'MoorDyn mean':>12} {'mean':>8} {'peak':>8} {'trough':>8} {'RMS':>8} "
           f"{'max':>8} {'RMS*':>8} {'MoorDyn [s]':>11} {'cablefem [s]':>12}"]
    for case, e in results["cases"].items():
        for k, (d, p) in enumerate(zip(e["differences"], e["differences_point_force"])):
            times = (f"{e['moordyn_wall_time_s']:11.1f} {e['cablefem_wall_time_s']:12.1f}" if k == 0 else "")
            out.append(f"{case if k == 0 else '':<19} {e['lines'][k]:<8} {d['reference_mean_N'] / MN:9.4f} MN "
                       f"{_pct(d['mean'])} {_pct(d['peak'])} {_pct(d['trough'])} {_pct(d['rms'])} {_pct(d['max'])} "
                       f"{_pct(p['rms'])} {times}")
    out.append("RMS*: against MoorDyn's force minus its end-node inertia (the force on the point, as cablefem's)")
    if any("periodicity" in e for e in results["cases"].values()):
        out.append("")
        out.append("Periodicity: change from the second-to-last period to the last (mean, max, min; % of MoorDyn mean)")
    for case, e in results["cases"].items():
        if "periodicity" not in e:
            continue
        for k, line in enumerate(e["lines"]):
            cells = [" ".join(_pct(e["periodicity"][code][k][key]) for key in ("mean", "max", "min"))
                     for code in ("moordyn", "cablefem")]
            out.append(f"{case if k == 0 else '':<19} {line:<8} MoorDyn {cells[0]} | cablefem {cells[1]}")
    if any("convergence" in e for e in results["cases"].values()):
        out.append("")
        out.append("Convergence: change of each code's statistics from the reference to the check resolution "
                   "(coarse: 1/2 segments, 2 dt), and the two codes compared there")
    for case, e in results["cases"].items():
        c = e.get("convergence")
        if not c:
            continue
        if "error" in c:
            out.append(f"{case:<19} convergence check failed: {c['error']}")
            continue
        for k, line in enumerate(e["lines"]):
            cells = []
            for part in (c["moordyn"]["change"][k], c["cablefem"]["change"][k], c["differences"][k]):
                cells.append(f"{_pct(part['mean'])} {_pct(part['peak'])} {_pct(part['rms'])}")
            out.append(f"{case if k == 0 else '':<19} {c['check'] if k == 0 else '':<6} {line:<8} "
                       f"MoorDyn {cells[0]} | cablefem {cells[1]} | cablefem - MoorDyn {cells[2]}")
        out.append(f"{'':<19} (mean peak RMS each; wall time MoorDyn {c['moordyn']['wall_time_s']:.1f} s, "
                   f"cablefem {c['cablefem']['wall_time_s']:.1f} s)")
    out.append("")
    out.append("Physics switches: cablefem - MoorDyn, as in the file -> with the switch")
    for case, e in results["cases"].items():
        for name, sw in e["switches"].items():
            if "error" in sw:
                out.append(f"{case:<19} {name:<36} failed: {sw['error']}")
                continue
            for k, d in enumerate(sw["differences"]):
                ref = e["differences"][k]
                out.append(f"{case:<19} {name:<36} {e['lines'][k]:<8} mean {_pct(ref['mean'])} -> {_pct(d['mean'])}, "
                           f"peak {_pct(ref['peak'])} -> {_pct(d['peak'])}, RMS {_pct(ref['rms'])} -> {_pct(d['rms'])}")
    failures = [(case, name, run["cablefem_failures"]) for case, e in results["cases"].items()
                for name, run in [("reference", e)] + list(e["switches"].items()) if run.get("cablefem_failures")]
    for case, name, messages in failures:
        out.append(f"cablefem reran {case} {name} with a smaller dt: {'; '.join(messages)}")
    for case, e in results["cases"].items():
        for name, run in [("reference", e)] + list(e["switches"].items()):
            if run.get("cablefem_start", "catenary guess") != "catenary guess":
                out.append(f"cablefem statics of {case} {name}: {run['cablefem_start']}")
    s = results["statics"]
    out.append("")
    out.append(f"Static pretension, flat flume line: MoorDyn ({s['moordyn_segments']} segments) {s['moordyn_N']:.1f} N "
               f"(held 5 s: {s['moordyn_hold_5s_change']:.1e}), MoorPy catenary {s['moorpy_N']:.1f} N "
               f"({_pct(s['moordyn_vs_moorpy'])}), cablefem ({s['cablefem_elements']} elements) {s['cablefem_N']:.1f} N "
               f"(MoorDyn/cablefem {_pct(s['moordyn_vs_cablefem'])})")
    if "fairlead_1m_below" in s:
        b = s["fairlead_1m_below"]
        out.append(f"  seabed elasticity (cablefem 640 el, kBot 3e5 vs 3e9): {_pct(s['seabed_elasticity'])}; "
                   f"MoorPy vs cablefem stiff seabed {_pct(s['moorpy_vs_cablefem_stiff_seabed'])}; "
                   f"fairlead 1 m below the surface: MoorDyn/cablefem {_pct(b['moordyn_vs_cablefem'])}")
    if "wall_time_s" in results:
        out.append(f"study wall time {results['wall_time_s']:.0f} s")
    return "\n".join(out)


def _json_ready(value):
    if isinstance(value, dict):
        return {k: _json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_ready(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    return value


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="coarse settings, short runs (~1 min): what the tests assert")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for inputs/, results.json and PNGs")
    parser.add_argument("--series", type=Path, help="also keep the time series in this pickle (for --replot)")
    parser.add_argument("--replot", type=Path, help="no runs: redraw the PNGs from --out/results.json and this pickle")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    if args.replot:
        results = json.loads((args.out / "results.json").read_text())
        with open(args.replot, "rb") as handle:
            series = pickle.load(handle)
        print(report(results))
        print(f"wrote {', '.join(figures(results, series, args.out))}")
        return
    results, series = run(fast=args.fast, out_dir=args.out)
    print(report(results))
    (args.out / "results.json").write_text(json.dumps(_json_ready(results), indent=1))
    if args.series:
        with open(args.series, "wb") as handle:
            pickle.dump(series, handle)
    written = figures(results, series, args.out)
    print(f"wrote {args.out / 'results.json'}, {', '.join(written)}")


if __name__ == "__main__":
    main()
