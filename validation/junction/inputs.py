"""The crowfoot of validation/junction, described once: its constants, written as MoorDyn v2 text
(``moordyn_text``) and as a cablefem TOML scene (``toml_text``), and the two written as files."""

import tempfile
from pathlib import Path

import numpy as np

from cablefem.io import load_scene

from validation.moordyn.inputs import (IC_OPTIONS, LINE_HEADER, OPTIONS_HEADER, OUTPUTS, POINT_HEADER,
                                       TYPE_HEADER, _type_row)

WATER_DENSITY, GRAVITY = 1025.0, 9.81
DEPTH = 300.0  # m: the anchors at 180 m, every line clear of the seabed (no contact, no friction)
#: chain (benchmarks/crowfoot.toml): d, kg/m, EA [N], beta [s] (BA = beta EA), Cd, Ca, Cd_tangential
#: (desire2023's, on d: MoorDyn's CdAx = Cd_tangential / pi, on pi d), CaAx
CHAIN = {"diameter": 0.1, "mass": 60.0, "EA": 5.0e8, "damping": 0.001, "Cd_normal": 1.2, "Ca_normal": 1.0,
         "Cd_tangential": 0.4, "Ca_tangential": 0.0}
FAIRLEAD = (-10.0, 0.0, -10.0)
JUNCTION = (-131.09, 0.0, -149.68)  # the start of both codes' searches: MoorPy's equilibrium to 1 cm
CLUMP = {"mass": 2000.0, "volume": 1.0, "CdA": 2.0, "Ca": 1.0}  # kg, m^3, m^2, -
ANCHORS = ((-400.0, 150.0, -180.0), (-400.0, -150.0, -180.0))
LENGTHS = {"upper": 185.0, "leg1": 330.0, "leg2": 330.0}  # m
#: per line: MoorDyn's NumSegs in the file (5 m segments) and cablefem's elements in the TOML
FILE_SEGMENTS = {"upper": 37, "leg1": 66, "leg2": 66}
FILE_ELEMENTS = {"upper": 8, "leg1": 14, "leg2": 14}
ORDER = 2
#: MoorDyn's stationary initial-condition solve steps with IC_DTM at the file's segments (held at
#: rest 10 s after it, its tensions move by < 1e-4; with the file's 4e-4 s it takes 10 x longer
#: for the same state to 1e-4)
IC_DTM = 5e-3
#: the cases: the fairlead's surge and heave, in phase, ramped in over one period (smoothstep); each
#: simulated for the ramp and ``periods`` more, statistics over the last two (fast: the last one)
CASES = {
    "slow": {"motion": {"amplitude": (4.0, 0.0, 1.0), "period": 10.0, "offset": (0.0, 0.0, 0.0), "ramp": 10.0},
             "periods": 3},
    "dynamic": {"motion": {"amplitude": (3.0, 0.0, 1.5), "period": 5.0, "offset": (0.0, 0.0, 0.0), "ramp": 5.0},
                "periods": 4},
}


def _vector(values):
    return "[" + ", ".join(repr(float(v)) for v in values) + "]"


def _row(pid, kind, xyz, mass=0.0, volume=0.0, cda=0.0, ca=0.0):
    x, y, z = (repr(float(c)) for c in xyz)
    return f"{pid:<3} {kind:<11} {x:<10} {y:<10} {z:<10} {mass!r:<8} {volume!r:<6} {cda!r:<6} {ca!r}\n"


def moordyn_text(factor=1):
    """The crowfoot as MoorDyn v2 text, NumSegs the file's times ``factor``: points 1 fairlead
    (Coupled), 2 junction (Free, the clump), 3-4 anchors (Fixed); lines 1 upper (A junction, B
    fairlead), 2-3 legs (A anchor, B junction)."""
    props = {"Diam": CHAIN["diameter"], "MassDen": CHAIN["mass"], "EA": CHAIN["EA"], "Cd": CHAIN["Cd_normal"],
             "Ca": CHAIN["Ca_normal"], "CdAx": CHAIN["Cd_tangential"] / np.pi, "CaAx": CHAIN["Ca_tangential"]}
    points = (_row(1, "Coupled", FAIRLEAD)
              + _row(2, "Free", JUNCTION, CLUMP["mass"], CLUMP["volume"], CLUMP["CdA"], CLUMP["Ca"])
              + _row(3, "Fixed", ANCHORS[0]) + _row(4, "Fixed", ANCHORS[1]))
    segments = {name: int(round(n * factor)) for name, n in FILE_SEGMENTS.items()}
    lines = (f"1   chain     2        1        {LENGTHS['upper']!r}     {segments['upper']}       -\n"
             f"2   chain     3        2        {LENGTHS['leg1']!r}     {segments['leg1']}       -\n"
             f"3   chain     4        2        {LENGTHS['leg2']!r}     {segments['leg2']}       -\n")
    return ("--------------------- MoorDyn Input File ------------------------------------\n"
            "crowfoot: a coupled fairlead, a free junction with a clump, two legs to anchors; validation/junction\n"
            + TYPE_HEADER + _type_row("chain", props, CHAIN["damping"]) + "\n"
            + POINT_HEADER + points + LINE_HEADER + lines + OPTIONS_HEADER
            + "0.0004                dtM           - s, MoorDyn's explicit step\n"
            + f"{DEPTH!r:<21} WtrDpth       - m: every line clear of the seabed\n"
            + f"{WATER_DENSITY!r:<21} WtrDnsty      - kg/m^3\n"
            + f"{GRAVITY!r:<21} g             - m/s^2\n"
            + IC_OPTIONS
            + OUTPUTS.format(channels="FairTen1\nAnchTen2\nAnchTen3"))


def toml_text(case="dynamic", factor=1, order=ORDER, dt=0.01, duration=None, clump=None, slack_damping=True):
    """The same crowfoot as a cablefem TOML scene under ``case``'s motion, elements the file's times
    ``factor``; ``clump`` replaces keys of CLUMP, ``slack_damping`` False takes cablefem's own
    damping law (the switches)."""
    motion = CASES[case]["motion"]
    duration = case_duration(case) if duration is None else duration
    chain = "".join(f"{key} = {value!r}\n" for key, value in CHAIN.items())
    clump = "".join(f"{key} = {value!r}\n" for key, value in {**CLUMP, **(clump or {})}.items())
    lines = ""
    for name, (anchor, fairlead) in {"upper": ("j", "f"), "leg1": ("a1", "j"), "leg2": ("a2", "j")}.items():
        lines += (f"[[lines]]\nname = \"{name}\"\nanchor = \"{anchor}\"\nfairlead = \"{fairlead}\"\norder = {order}\n"
                  f"segments = [{{ type = \"chain\", length = {LENGTHS[name]!r}, "
                  f"elements = {int(round(FILE_ELEMENTS[name] * factor))} }}]\n")
    return ("# crowfoot: a coupled fairlead, a free junction with a clump, two legs to anchors; validation/junction\n"
            "# the same physics as crowfoot.dat (MoorDyn v2); damping_when_slack: MoorDyn-C's law\n"
            f"name = \"crowfoot\"\n[environment]\nwater_density = {WATER_DENSITY!r}\ngravity = {GRAVITY!r}\n"
            f"[line_types.chain]\n{chain}damping_when_slack = {str(slack_damping).lower()}\n"
            f"[points.f]\nkind = \"coupled\"\nposition = {_vector(FAIRLEAD)}\n"
            f"[points.j]\nkind = \"free\"\nposition = {_vector(JUNCTION)}\n{clump}"
            f"[points.a1]\nkind = \"fixed\"\nposition = {_vector(ANCHORS[0])}\n"
            f"[points.a2]\nkind = \"fixed\"\nposition = {_vector(ANCHORS[1])}\n"
            + lines
            + f"[seabed]\nkind = \"horizontal\"\ndepth = {DEPTH!r}\n"
            f"[motion]\nkind = \"harmonic\"\namplitude = {_vector(motion['amplitude'])}\n"
            f"period = {motion['period']!r}\n"
            f"offset = {_vector(motion['offset'])}\nramp = {motion['ramp']!r}\n"
            f"[solver]\nintegrator = \"bdf2\"\ndt = {dt!r}\nduration = {duration!r}\n")


def case_duration(case):
    """Simulated time [s] of ``case``: its ramp and its periods."""
    motion = CASES[case]["motion"]
    return motion["ramp"] + CASES[case]["periods"] * motion["period"]


def write_inputs(folder):
    """Write crowfoot.dat and crowfoot-<case>.toml (the files' settings) into ``folder``; the .dat's
    path and {case: the TOML's path}."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    dat = folder / "crowfoot.dat"
    dat.write_text(moordyn_text())
    tomls = {case: folder / f"crowfoot-{case}.toml" for case in CASES}
    for case, path in tomls.items():
        path.write_text(toml_text(case))
    return dat, tomls


def scene_of(text):
    """A cablefem Scene from TOML text."""
    with tempfile.TemporaryDirectory(prefix="crowfoot-") as folder:
        path = Path(folder) / "crowfoot.toml"
        path.write_text(text)
        return load_scene(path)
