"""Where cablefem's time error lives in the frictionless slow surge (issue 16, part 4's profile).

In the common study (``common.py``) every cablefem mesh from P1 x 40 to P2 x 80 stays at 0.2-0.3 %
RMS at dt 0.04 s, far from the 17 s period of the motion. This runs generalised-alpha (rho_inf 0.9,
"auto" Newton) on the aligned slow-surge scene at dt 0.04, 0.02 and 0.01 s against the same mesh at
dt 0.0025 s, and splits each difference of the fairlead tension by frequency
(``validation.moordyn_aligned.run.spectrum_bands``, over the study's window: the last two periods). Beside it, the natural frequency of
a point of the chain on the seabed, the contact spring k d over the mass with the normal added mass,
f = sqrt(k d / (m + C_a rho pi d^2 / 4)) / 2 pi (critically damped, ``scenes.flume_scene``'s
contact): the band that holds the time error.

    python -m verification.work_precision.time_error [--order 1] [--elements 80] [--out DIR]

writes ``time_error.json``.
"""

import argparse
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.scenes import flume_scene, table5_chain  # noqa: E402
from cablefem.study import write_json  # noqa: E402
from validation.moordyn_aligned.run import WINDOW, aligned_scene, spectrum_bands  # noqa: E402
from verification.work_precision.runs import run_cablefem_scene  # noqa: E402

HERE = Path(__file__).resolve().parent
STEPS = (0.04, 0.02, 0.01)
FINE = 0.0025
EDGES = (0.0, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0)


def contact_frequency(water_density=1025.0):
    """Natural frequency [Hz] of a point of the flume chain on its seabed: sqrt(k d / (m + m_a)) / 2 pi."""
    chain, contact = table5_chain(), flume_scene("flat").contact
    added = chain.Ca_normal * water_density * np.pi * chain.diameter ** 2 / 4.0
    return float(np.sqrt(contact.stiffness * chain.diameter / (chain.mass + added)) / (2 * np.pi))


def run(order, elements, dt):
    """The aligned slow surge, generalised-alpha 0.9, auto Newton: (t, tension) of the fairlead."""
    scene = aligned_scene("slow", order, elements, dt, tolerance=1e-4)
    scene.solver = replace(scene.solver, integrator="generalized-alpha", rho_inf=0.9, newton="auto")
    found = run_cablefem_scene(scene)
    return {"t": found["t"], "tension": found["tension"]}


def split(run_, fine, t_from):
    """RMS of run - fine over t >= t_from relative to fine's mean, and its shares per band."""
    on = np.interp(run_["t"], fine["t"], fine["tension"])
    keep = run_["t"] >= t_from
    mean = float(on[keep].mean())
    diff = {"t": run_["t"], "tension": (run_["tension"] - on) / mean}
    return {"rms": float(np.sqrt(np.mean(diff["tension"][keep] ** 2))),
            "bands": spectrum_bands(diff, t_from, EDGES)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--order", type=int, default=1)
    parser.add_argument("--elements", type=int, default=80)
    parser.add_argument("--out", type=Path, default=HERE)
    args = parser.parse_args(argv)
    fine = run(args.order, args.elements, FINE)
    t_from = WINDOW["slow"]
    results = {"mesh": f"P{args.order} x {args.elements}", "fine_dt": FINE, "window_from_s": t_from,
               "contact_frequency_Hz": contact_frequency(), "steps": {}}
    print(f"contact frequency {results['contact_frequency_Hz']:.2f} Hz; P{args.order} x {args.elements} "
          f"against dt {FINE:g}")
    for dt in STEPS:
        found = results["steps"][f"{dt:g}"] = split(run(args.order, args.elements, dt), fine, t_from)
        print(f"  dt {dt:<5g} RMS {100 * found['rms']:.3f} %  "
              + "  ".join(f"{b['band_Hz'][0]:g}-{b['band_Hz'][1]:g} Hz {b['share']:.2f}" for b in found["bands"]))
    write_json(args.out / "time_error.json", results)


if __name__ == "__main__":
    main()
