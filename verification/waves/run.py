"""Linear waves: kinematics, irregular seas and Morison loads, verified against closed forms.

Run ``python -m verification.waves.run [--fast] [--out DIR]``; ``run(fast=True)`` returns the numbers
the tests assert on.

(a) eta, u and a of ``cablefem.waves`` against the textbook formulas (``closed_forms.py``) at points
    below and above the mean level, for Wheeler, vertical and no stretching (``kinematics.py``);
(b) the compiled face against the numpy face, the exact gradients against central differences;
(c) irregular JONSWAP seas: m0 of many seeds' records against Hs^2 / 16, the spectral peak at Tp
    (``spectrum.py``); (d) cos-2s spreading of the components' headings;
(e) a fixed, very stiff horizontal line in regular waves: its end reactions against the integral of
    the Morison force along it (``morison.py``).
"""

import argparse
import time
from pathlib import Path

import numpy as np

from cablefem.study import provenance, stamp, write_json
from verification.waves.kinematics import against_closed_forms, faces_and_gradients
from verification.waves.morison import check as morison_check
from verification.waves.spectrum import spectrum_check, spreading_check

HERE = Path(__file__).resolve().parent


def run(fast=False):
    """The study's numbers (dict)."""
    started, clock = provenance(), time.perf_counter()
    rng = np.random.default_rng(2024)
    seeds = range(1, 21) if fast else range(1, 101)
    results = {"closed_forms": against_closed_forms(rng), "faces": faces_and_gradients(rng),
               "spectrum": spectrum_check(seeds, 3600.0 if fast else 10800.0), "spreading": spreading_check()}
    cases = [("bdf2", 1)] if fast else [("bdf2", 1), ("bdf2", 2), ("generalized-alpha", 1), ("generalized-alpha", 2)]
    results["morison"] = [morison_check(10, order, integrator) for integrator, order in cases]
    results["wall_time_s"] = time.perf_counter() - clock
    results["provenance"] = stamp(started)
    return results


def report(results):
    """The tables, printed."""
    print("(a) kinematics against closed forms: largest error / (A, A w, A w^2) at wet points")
    print(f"{'case':28s} {'stretching':10s} {'points':>6s} {'above 0':>7s} {'eta':>9s} {'u':>9s} {'a':>9s}")
    for row in results["closed_forms"]:
        print(f"{row['case']:28s} {row['stretching']:10s} {row['points']:6d} {row['above_mean_level']:7d} "
              f"{row['eta']:9.1e} {row['velocity']:9.1e} {row['acceleration']:9.1e}")
    faces = results["faces"]
    print(f"(b) compiled - numpy: {faces['compiled_vs_numpy']:.1e}; gradients - central differences: "
          f"{faces['gradient_vs_central_difference']:.1e} (relative)")
    s = results["spectrum"]
    print(f"(c) {s['seeds']} seeds x {s['duration_s']:g} s: mean m0 {s['m0_mean']:.4f} m^2 against Hs^2/16 = "
          f"{s['m0_target']:.4f} ({100 * s['m0_error']:+.2f} %; seeds spread {100 * s['m0_seed_spread']:.1f} %); "
          f"peak at {s['peak_omega']:.4f} rad/s against {s['omega_p']:.4f} ({100 * s['peak_error']:+.2f} %, "
          f"smoothing window {100 * s['resolution']:.1f} % of omega_p); spectrum near the peak within "
          f"{100 * s['spectrum_error_near_peak']:.1f} % of S(omega_p)")
    print("(d) cos-2s spreading: mean cos(beta - beta_0) of 2000 components")
    for row in results["spreading"]:
        print(f"    s = {row['s']:4g}: {row['mean_cos']:.4f} against s/(s+1) = {row['expected']:.4f}")
    print("(e) stiff line in regular waves: end reactions against the lever rule of the Morison force")
    for row in results["morison"]:
        print(f"    {row['integrator']:18s} P{row['order']} x {row['elements']}: largest difference "
              f"{row['error']:.1e} of the largest reaction ({row['largest_reaction_N']:.0f} N), {row['times']} times")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="fewer seeds and shorter records (the tests)")
    parser.add_argument("--out", type=Path, default=HERE, help="folder for results.json")
    args = parser.parse_args(argv)
    results = run(fast=args.fast)
    report(results)
    write_json(args.out / "results.json", results)


if __name__ == "__main__":
    main()
