"""The cases of validation/moordyn as MoorDyn v2 input files: the flat flume line (desire2023 Table
5) and housner2022's semi-taut three-line system over flat and sloped seabeds, the line types and
file sections other studies reuse, and the TOML that adds each case's motion for cablefem."""

from pathlib import Path

import numpy as np

from cablefem.geometry.generators import slope
from cablefem.geometry.readers import moordyn_c
from cablefem.model.builtin import FLUME_ANCHOR, FLUME_DEPTH, FLUME_MOTIONS, table5_chain

MN = 1e6
WATER_DENSITY, GRAVITY = 1025.0, 9.81

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
                        f"place for\nname = \"{case}\"\n\n[moordyn]\nfile = \"{case_file(case)}\"\n"
                        "order = 1  # the file's mesh, P1 x NumSegs: the study compares MoorDyn-C at NumSegs\n\n"
                        + _motion_toml(motion))
        tomls[case] = path
    return tomls


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
