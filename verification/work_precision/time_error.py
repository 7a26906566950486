"""Where cablefem's time error lives in the frictionless slow surge (issue 16, part 4's profile).

In the common study (``common.py``) every cablefem mesh from P1 x 40 to P2 x 80 stays at 0.2-0.3 %
RMS at dt 0.04 s, far from the 17 s period of the motion. This runs generalised-alpha (rho_inf 0.9,
"auto" Newton) on the aligned slow-surge scene at dt 0.04, 0.02 and 0.01 s against the same mesh at
dt 0.0025 s, and splits each difference of the fairlead tension by frequency
(``validation.moordyn_aligned.run.spectrum_bands``, over the study's window: the last two periods).
Beside it, two candidate frequencies: the first axial mode of the whole line held at both ends,
c / 2 L with c = sqrt(EA / m) (without friction the part on the seabed slides freely, so the whole
635 m rings), and a point of the chain ringing on the seabed's contact spring,
sqrt(k d / (m + C_a rho pi d^2 / 4)) / 2 pi. They are 1.53 and 1.49 Hz on the flume chain; the
switches tell them apart: ``--ea-factor 4`` doubles the first, ``--stiffness-factor 4`` the second,
and the error's band moves only with EA (time_error_ea4.json, time_error_k4.json).

    python -m verification.work_precision.time_error [--order 1] [--elements 80]
        [--stiffness-factor F] [--ea-factor F] [--out DIR]

writes ``time_error.json`` (``time_error_k{F}.json``, ``time_error_ea{F}.json`` with a switch).
"""

import argparse
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.model.builtin import flume_scene, table5_chain  # noqa: E402
from cablefem.study import write_json  # noqa: E402
from validation.moordyn_aligned.run import WINDOW, aligned_scene, compare, spectrum_bands  # noqa: E402
from verification.work_precision.runs import run_cablefem_scene  # noqa: E402

HERE = Path(__file__).resolve().parent
STEPS = (0.04, 0.02, 0.01)
FINE = 0.0025
EDGES = (0.0, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0)


def contact_frequency(water_density=1025.0, stiffness_factor=1.0):
    """Natural frequency [Hz] of a point of the flume chain on its seabed: sqrt(k d / (m + m_a)) / 2 pi
    (k the flume's contact stiffness times ``stiffness_factor``)."""
    chain, contact = table5_chain(), flume_scene("flat").contact
    added = chain.Ca_normal * water_density * np.pi * chain.diameter ** 2 / 4.0
    k = contact.stiffness * stiffness_factor
    return float(np.sqrt(k * chain.diameter / (chain.mass + added)) / (2 * np.pi))


def axial_frequency(ea_factor=1.0):
    """First axial frequency [Hz] of the whole flume line held at both ends, c / 2 L with
    c = sqrt(EA / m) (no tangential added mass), EA times ``ea_factor``."""
    chain, line = table5_chain(), flume_scene("flat").lines[0]
    return float(np.sqrt(chain.EA * ea_factor / chain.mass) / (2.0 * line.unstretched_length))


def run(order, elements, dt, stiffness_factor=1.0, ea_factor=1.0):
    """The aligned slow surge, generalised-alpha 0.9, auto Newton, the contact stiffness times
    ``stiffness_factor`` (its damping ratio kept) and EA times ``ea_factor``: (t, tension) of the
    fairlead."""
    scene = aligned_scene("slow", order, elements, dt, tolerance=1e-4)
    scene = replace(scene, contact=replace(scene.contact, stiffness=scene.contact.stiffness * stiffness_factor))
    scene = replace(scene, lines=[scene.lines[0].with_types(lambda t: replace(t, EA=t.EA * ea_factor))])
    scene.solver = replace(scene.solver, integrator="generalized-alpha", rho_inf=0.9, newton="auto")
    found = run_cablefem_scene(scene)
    return {"t": found["t"], "tension": found["tension"]}


def split(run_, fine, t_from):
    """RMS of run - fine over t >= t_from relative to fine's mean (the studies' ``compare``), and
    the difference's shares per frequency band."""
    on = np.interp(run_["t"], fine["t"], fine["tension"])
    diff = {"t": run_["t"], "tension": run_["tension"] - on}
    return {"rms": compare(run_, fine, t_from)["rms"], "bands": spectrum_bands(diff, t_from, EDGES)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--order", type=int, default=1)
    parser.add_argument("--elements", type=int, default=80)
    parser.add_argument("--stiffness-factor", type=float, default=1.0,
                        help="the contact stiffness times this (a switch: the error's band should move with it)")
    parser.add_argument("--ea-factor", type=float, default=1.0, help="EA times this (a switch, likewise)")
    parser.add_argument("--out", type=Path, default=HERE)
    args = parser.parse_args(argv)
    factor, ea = args.stiffness_factor, args.ea_factor
    fine = run(args.order, args.elements, FINE, factor, ea)
    t_from = WINDOW["slow"]
    results = {"mesh": f"P{args.order} x {args.elements}", "fine_dt": FINE, "window_from_s": t_from,
               "stiffness_factor": factor, "ea_factor": ea,
               "contact_frequency_Hz": contact_frequency(stiffness_factor=factor),
               "axial_frequency_Hz": axial_frequency(ea), "steps": {}}
    print(f"contact frequency {results['contact_frequency_Hz']:.2f} Hz, axial {results['axial_frequency_Hz']:.2f} Hz; "
          f"P{args.order} x {args.elements} against dt {FINE:g}")
    for dt in STEPS:
        found = results["steps"][f"{dt:g}"] = split(run(args.order, args.elements, dt, factor, ea), fine, t_from)
        print(f"  dt {dt:<5g} RMS {100 * found['rms']:.3f} %  "
              + "  ".join(f"{b['band_Hz'][0]:g}-{b['band_Hz'][1]:g} Hz {b['share']:.2f}" for b in found["bands"]))
    name = "time_error" + ("" if factor == 1.0 else f"_k{factor:g}") + ("" if ea == 1.0 else f"_ea{ea:g}")
    write_json(args.out / f"{name}.json", results)


if __name__ == "__main__":
    main()
