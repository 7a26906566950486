"""The lines of validation/waves, as MoorDyn v2 files that both codes read, and the regular wave.

- ``chain``: a 550 m chain catenary in 100 m of water from an anchor at x = -480 m to a fairlead
  held at 15 m below the surface at the origin, frictionless (MoorDyn's FrictionCoefficient 0).
- ``buoy``: the same anchor and fairlead, the chain in two parts (300 m from the anchor, 250 m to
  the fairlead) joined at a buoy (a free point of 2 t, 8 m^3, CdA 4 m^2, Ca 0.5).
The wave travels along +x (the line's plane): amplitude 4 m, period 10 s, MoorDyn-C's WaveKin 7 with
wave_frequencies.txt (rows omega re im), so that both codes sum the same component; MoorDyn's
surface is |c| sin(omega t - k x + arg c), here 4 sin(omega t - k x).

MoorDyn-C's initial condition is its dynamic relaxation in still water, checked every 10 s to a
relative tension change of 1e-5 (ICgenDynamic; its default stationary solver, starting from a
straight line when its catenary fails, as it does here, stops 90 % short of the equilibrium);
cablefem's is its static solve. The waves start at full height at t = 0 in both.
"""

from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
INPUTS = HERE / "inputs"
AMPLITUDE, PERIOD = 4.0, 10.0
#: MoorDyn-C's rows of wave_frequencies.txt: the zero frequency first, then the wave
FREQUENCIES = f"0.0 0.0 0.0\n{2 * np.pi / PERIOD!r} {AMPLITUDE!r} 0.0\n"

HEAD = """--------------------- MoorDyn Input File ------------------------------------
{title} (cablefem validation/waves)
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam    Mass/m     EA         BA/-zeta    EI    Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)        (N-s/-)     (N-m^2) (-)  (-)    (-)     (-)
chain      0.15    130.0      1.2e9      1.2e7       0     1.2    1.0    0.2     0.5
---------------------- POINTS --------------------------------
ID    Attachment  X       Y     Z      Mass   Volume  CdA   CA
(#)   (-)         (m)     (m)   (m)    (kg)   (m^3)   (m^2) (-)
1     Fixed      -480.0   0.0  -100.0  0      0       0     0
2     Coupled     0.0     0.0  -15.0   0      0       0     0
"""
OPTIONS = """---------------------- OPTIONS -----------------------------------------
9.81          g
1025.0        WtrDnsty
100.0         WtrDpth
3.0e6         kBot
3.0e5         cBot
2.5e-4        dtM
0.0           FrictionCoefficient
1e-5          threshIC
600.0         TmaxIC
1             ICgenDynamic
10.0          dtIC
1.0           CdScaleIC
7             WaveKin
------------------------- need this line --------------------------------------
"""
LINES = """---------------------- LINES ----------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  Outputs
(#)   (name)     (#)      (#)       (m)       (-)     (-)
"""
TEXT = {
    "chain": HEAD.format(title="A chain catenary in a regular wave") + LINES
    + "1     chain      1        2         550.0     40       -\n" + OPTIONS,
    "buoy": HEAD.format(title="A chain with a buoy in a regular wave")
    + "3     Free       -200.0   0.0  -60.0   2000   8.0     4.0   0.5\n" + LINES
    + "1     chain      1        3         300.0     22       -\n"
    + "2     chain      3        2         250.0     18       -\n" + OPTIONS,
}


def write_inputs(folder=INPUTS):
    """Write each case's MoorDyn file and wave_frequencies.txt into ``folder``: {case: path}."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "wave_frequencies.txt").write_text(FREQUENCIES)
    paths = {}
    for name, text in TEXT.items():
        paths[name] = folder / f"{name}.dat"
        paths[name].write_text(text)
    return paths
