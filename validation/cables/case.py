"""The lazy-wave dynamic power cable of validation/cables, written once for both codes.

A 260 m cable, EI = 2e4 N m², from an anchor on a flat seabed 100 m deep to a hang-off 20 m below the
surface where it is clamped vertical (a bend stiffener's root on a floater), with a 40 m buoyancy
section (0.40 m over its modules) that lifts it into a lazy wave: touchdown, sag bend, hog bend over
the modules, sag bend again, and the hang-off. The hang-off follows a platform motion (``MOTION``).

For MoorDyn-C the cable is three lines, each of one line type, joined through zero-length free Rods
(MoorDyn's connector that passes the bending moment: it turns to balance the attached ends' moments,
so that the tangent is continuous as in one line), the hang-off a Coupled Rod, vertical, whose end A
the cable's top is clamped to. For cablefem the same file with those Rods made Free and Coupled
POINTS (cablefem reads a zero-length Rod as a point, which passes no moment) is read by cablefem's MoorDyn reader (the same
conversions as any MoorDyn file: Hermite elements, damping, drag, seabed); its free points are hinges
where bending lines meet, so the three lines are welded into one line, C1 through the joints as the
Rods make them, its top clamped along the Rod (``fairlead_tangent``).
"""

from dataclasses import replace
from pathlib import Path

import numpy as np

DEPTH = 100.0  # m
ANCHOR = (-200.0, 0.0, -DEPTH)
HANG_OFF = (0.0, 0.0, -20.0)
ROD_LENGTH = 0.01  # m: the coupled Rod is a direction, its own weight and drag nothing
#: line types (MoorDyn's columns): the cable, and the cable inside its buoyancy modules (the modules
#: add volume and mass, no bending stiffness); BA as a damping coefficient [N s] (beta = BA / EA =
#: 4e-5 s), the same at any NumSegs
TYPES = {"cable": {"Diam": 0.15, "MassDen": 40.0, "EA": 5.0e8, "BA": 2.0e4, "EI": 2.0e4,
                   "Cd": 1.2, "Ca": 1.0, "CdAx": 0.008, "CaAx": 0.0},
         "buoyancy": {"Diam": 0.40, "MassDen": 80.0, "EA": 5.0e8, "BA": 2.0e4, "EI": 2.0e4,
                      "Cd": 1.2, "Ca": 1.0, "CdAx": 0.008, "CaAx": 0.0}}
#: the cable from the anchor: (line type, length [m]); the joints' starting guesses (MoorDyn's
#: relaxation starts from them; cablefem does not read them)
SECTIONS = (("cable", 120.0), ("buoyancy", 40.0), ("cable", 100.0))
JOINTS = ((-130.0, 0.0, -80.0), (-100.0, 0.0, -50.0))
KBOT, CBOT = 3.0e6, 3.0e5  # MoorDyn's defaults
#: the platform's motion of the hang-off: surge and heave, one period, ramped in over its first 10 s
MOTION = {"amplitude": (6.0, 0.0, 2.0), "period": 12.0, "ramp": 10.0}
LENGTH = sum(length for _, length in SECTIONS)


def segments_for(length):
    """NumSegs of each section for segments of about ``length`` [m] (at least 2)."""
    return tuple(max(2, int(round(section / length))) for _, section in SECTIONS)


def moordyn_text(segments, dtM, ic=None, rods=True):
    """The MoorDyn v2 input file (text) with ``segments`` (NumSegs per section), time step dtM [s] and
    ``ic`` (dict OPTIONS name -> value for the initial-condition solve); ``rods`` False: the joints
    and the hang-off as Free and Coupled POINTS (for cablefem, whose zero-length Rods are points)."""
    rows = ["--------------------- MoorDyn Input File ------------------------------------",
            "Lazy-wave dynamic power cable (cablefem validation/cables)",
            "----------------------- LINE TYPES ------------------------------------------",
            "TypeName   Diam    Mass/m     EA         BA/-zeta    EI         Cd     Ca     CdAx    CaAx",
            "(name)     (m)     (kg/m)     (N)        (N-s/-)     (N-m^2)    (-)    (-)    (-)     (-)"]
    for name, p in TYPES.items():
        rows.append(f"{name:<10} {p['Diam']!r} {p['MassDen']!r} {p['EA']!r} {p['BA']!r} {p['EI']!r} "
                    f"{p['Cd']!r} {p['Ca']!r} {p['CdAx']!r} {p['CaAx']!r}")
    x, y, z = HANG_OFF
    if rods:
        cable = TYPES["cable"]
        rows += ["---------------------- ROD TYPES ------------------------------------",
                 "TypeName      Diam     Mass/m    Cd     Ca      CdEnd    CaEnd",
                 "(name)        (m)      (kg/m)    (-)    (-)     (-)      (-)",
                 f"connector     {cable['Diam']!r}     0.0       0.0    0.0     0.0      0.0",
                 "---------------------- RODS ----------------------------------------",
                 "ID   RodType  Attachment  Xa    Ya    Za     Xb    Yb    Zb      NumSegs  RodOutputs",
                 "(#)  (name)    (#/key)    (m)   (m)   (m)    (m)   (m)   (m)     (-)       (-)",
                 f"1    connector  Coupled  {x!r} {y!r} {z!r} {x!r} {y!r} {z + ROD_LENGTH!r}  1  -"]
        rows += [f"{k + 2}    connector  Free  {a!r} {b!r} {c!r} {a!r} {b!r} {c!r}  0  -"
                 for k, (a, b, c) in enumerate(JOINTS)]
    rows += ["---------------------- POINTS ----------------------------------------",
             "ID    Type      X       Y       Z       Mass   Volume  CdA    Ca",
             "(#)   (-)       (m)     (m)     (m)     (kg)   (m^3)   (m^2)  (-)",
             f"1     Fixed     {ANCHOR[0]!r} {ANCHOR[1]!r} {ANCHOR[2]!r}  0  0  0  0"]
    if rods:
        ends = ["1", "R2A", "R2B", "R3A", "R3B", "R1A"]
    else:
        rows += [f"{k + 2}     Free      {a!r} {b!r} {c!r}  0  0  0  0" for k, (a, b, c) in enumerate(JOINTS)]
        rows.append(f"4     Coupled   {x!r} {y!r} {z!r}  0  0  0  0")
        ends = ["1", "2", "2", "3", "3", "4"]
    rows += ["---------------------- LINES ----------------------------------------",
             "ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs",
             "(#)   (name)     (#)      (#)       (m)       (-)     (-)"]
    for k, ((kind, length), n) in enumerate(zip(SECTIONS, segments)):
        rows.append(f"{k + 1}     {kind:<10} {ends[2 * k]:<8} {ends[2 * k + 1]:<8} {length!r}  {n}  -")
    options = {"dtM": dtM, "WtrDpth": DEPTH, "kBot": KBOT, "cBot": CBOT, **(ic or {})}
    rows.append("---------------------- OPTIONS -----------------------------------------")
    rows += [f"{value!r:<14} {name}" if not isinstance(value, str) else f"{value:<14} {name}"
             for name, value in options.items()]
    rows.append("------------------------- need this line --------------------------------------")
    return "\n".join(rows) + "\n"


def cablefem_scene(elements, folder, options=None, moving=True):
    """cablefem's Scene of the case at ``elements`` (Hermite elements per section), read from the POINTS
    variant of the file (written to ``folder``, with more OPTIONS ``options``: a ``WaveKin``) by
    cablefem's MoorDyn reader, its top clamped along the hang-off Rod, moving with ``MOTION`` (held
    still unless ``moving``)."""
    from cablefem.io import load_scene
    from cablefem.model.scene import Motion

    path = Path(folder) / f"lazy_wave_points_{'_'.join(map(str, elements))}.dat"
    path.write_text(moordyn_text(elements, 1e-4, options, rods=False))
    scene = load_scene(path)
    # the file's free points are hinges for cablefem (each line a string); MoorDyn's zero-length free Rods
    # pass the moment, so the cable is welded here: one line of the three sections, C1 through them
    first, *_, last = scene.lines
    line = replace(first, name="+".join(line.name for line in scene.lines), fairlead=last.fairlead,
                   segments=tuple(s for each in scene.lines for s in each.segments), ends=(first.ends[0], last.ends[1]),
                   prescribed=(first.prescribed[0], last.prescribed[1]), tangents=(None, np.array([0.0, 0.0, 1.0])))
    points = {name: point for name, point in scene.points.items() if name in line.ends}
    scene = replace(scene, points=points)
    if not moving:
        return replace(scene, lines=[line])
    motion = Motion(kind="harmonic", amplitude=MOTION["amplitude"], period=MOTION["period"], ramp=MOTION["ramp"])
    return replace(scene, lines=[line], motion=motion)
