"""MoorDyn's own test inputs in both codes under a smooth fairlead motion (issue 36, deliverable 6):
fairlead forces compared over the last periods, each code at the file's mesh and refined.

Cases (``CASES``), each a file of MoorDyn v2.7's ``tests/Mooring`` copied to ``inputs/`` (its README
names the source), its coupled points moved by a harmonic surge (ramped in over the first period):

- ``polyester``: ``polyester/simple.txt``, a 1400 m polyester line (EA 3.339e8 N, BA -1: a
  critical damping ratio of 1 per segment) from an anchor on the seabed 372 m deep to a fairlead
  18 m below the surface, taut; surge 5 m at 30 s.

MoorDyn's SYROPE and viscoelastic inputs are run in both codes by verification/axial_laws (d).

Rows per case: MoorDyn-C on the file (its NumSegs and dtM, its IC solve) and refined (2x the
segments, the case's smaller dtM, BA given as the file's N s so that -zeta does not change with the
segment length); cablefem on the scene as ``cablefem run`` reads it (its default mesh, BDF2 at
the case's dt) and refined (P2 elements, twice as many as it reads, dt / 4). Each row's fairlead force magnitude
is compared with MoorDyn-C's refined run over the last ``WINDOW_PERIODS`` periods:
``validation.moordyn.comparison.differences`` (RMS, relative to the reference's mean). MoorDyn-C's
force is the force on the coupled point with its end node's inertia subtracted
(``forces_on_point``), the force cablefem's reaction gives.

    python -m validation.moordyn_parity.run [--fast] [--out DIR]

``--fast`` runs the file-mesh rows only (what tests/test_moordyn_parity.py asserts: within the
issue's 2 % RMS).
"""

import argparse
import json
import re
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # python validation/moordyn_parity/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.io import load_scene  # noqa: E402
from validation.moordyn import peer  # noqa: E402
from validation.moordyn.comparison import differences, on_grid  # noqa: E402
from validation.moordyn.runners import point_order, refined, run_cablefem_case, run_moordyn_case  # noqa: E402

HERE = Path(__file__).resolve().parent
INPUTS = HERE / "inputs"
WINDOW_PERIODS = 2
#: per case: the input, the surge amplitude [m] and period [s], periods simulated (the first one a
#: ramp), MoorDyn's IC step [s] and its step refined [s] (polyester: half the segment length
#: doubles the damping ratio the file's BA gives a segment, and 1.25e-3 s went unstable), cablefem's
#: step [s]
CASES = {
    "polyester": {"file": "polyester_simple.txt", "amplitude": 5.0, "period": 30.0, "periods": 4,
                  "ic_dtM": 0.005, "refined_dtM": 2.5e-4, "dt": 0.1},
}


def scene_of(case):
    """The scene cablefem reads: the MoorDyn file wrapped in a TOML with the case's surge."""
    spec = CASES[case]
    source = INPUTS / spec["file"]
    text = (f'name = "{case}"\n[moordyn]\nfile = "{source.name}"\n[motion]\nkind = "harmonic"\n'
            f'amplitude = [{spec["amplitude"]!r}, 0.0, 0.0]\nperiod = {spec["period"]!r}\n'
            f'ramp = {spec["period"]!r}\n')
    wrapper = source.parent / f".{case}-parity.toml"
    wrapper.write_text(text)
    try:
        return load_scene(wrapper)
    finally:
        wrapper.unlink()


def absolute_damping(text, scene):
    """MoorDyn file text with every line type's BA/-zeta < 0 written as the BA [N s] it means at the
    file's segments (MoorDyn scales -zeta with UnstrLen / NumSegs; a refined run keeps the line's BA)."""
    betas = {}
    for line in scene.lines:
        for segment in line.segments:
            kind = segment.type
            betas.setdefault(kind.name, kind.damping * kind.EA if kind.damping else None)
    rows = text.splitlines()
    for i, row in enumerate(rows):
        fields = row.split()
        if len(fields) > 4 and fields[0] in betas and betas[fields[0]] is not None:
            try:
                ba = float(fields[4])
            except ValueError:
                continue
            if ba < 0:
                rows[i] = re.sub(re.escape(fields[4]), f"{betas[fields[0]]:.9g}", row, count=1)
    return "\n".join(rows) + "\n"


def moordyn_run(case, scene, factor):
    """MoorDyn-C on the case's file (factor 1) or at 2x its segments and the case's refined dtM."""
    spec = CASES[case]
    source = INPUTS / spec["file"]
    duration = spec["period"] * spec["periods"]
    text = source.read_text()
    dtM = float(peer.option_value(text, "dtM"))
    fine = spec["refined_dtM"]
    settings = {"segments": factor, "dtM": dtM if factor == 1 else fine,
                "ic_dtM": spec["ic_dtM"] if factor == 1 else min(fine, spec["ic_dtM"])}
    with tempfile.TemporaryDirectory(prefix="parity-") as folder:
        work = Path(folder) / source.name
        work.write_text(absolute_damping(text, scene) if factor != 1 else text)
        return run_moordyn_case(work, scene, duration, settings)


def cablefem_run(case, scene, factor):
    """cablefem's BDF2 on the scene as read (factor 1), or on P2 elements ``factor`` x as many as it
    reads, at dt / factor^2."""
    spec = CASES[case]
    duration = spec["period"] * spec["periods"]
    if factor == 1:
        return run_cablefem_case(scene, duration, spec["dt"])
    fine = refined(scene, factor)
    fine = replace(fine, lines=[replace(line, order=2) for line in fine.lines])
    return run_cablefem_case(fine, duration, spec["dt"] / factor ** 2)


def compare(reference, run, t_from, column=None):
    """``differences`` of a run's fairlead force magnitude against MoorDyn-C's ``reference`` (its
    forces on the point) over t >= t_from, on the coarser of the two time grids."""
    grid = run["t"] if len(run["t"]) <= len(reference["t"]) else reference["t"]
    ref = np.linalg.norm(on_grid(reference["t"], reference["forces_on_point"], grid), axis=2)[:, 0]
    key = "forces_on_point" if "forces_on_point" in run else "forces"
    other = np.linalg.norm(on_grid(run["t"], run[key], grid), axis=2)[:, 0 if column is None else column]
    return differences(grid, ref, other, t_from)


def run(fast=False):
    """Every case's rows: {case: {row: differences against the reference, with wall_time_s}}."""
    results = {}
    for case, spec in CASES.items():
        scene = scene_of(case)
        t_from = spec["period"] * (spec["periods"] - WINDOW_PERIODS)
        runs = {"MoorDyn-C, file": moordyn_run(case, scene, 1),
                "cablefem, file": cablefem_run(case, scene, 1)}
        if not fast:
            runs["MoorDyn-C, refined"] = moordyn_run(case, scene, 2)
            runs["cablefem, refined"] = cablefem_run(case, scene, 2)
        reference = runs["MoorDyn-C, file" if fast else "MoorDyn-C, refined"]
        line = point_order(scene, reference["points"])[0]
        results[case] = {name: dict(compare(reference, result, t_from, None if name.startswith("MoorDyn") else line),
                                    wall_time_s=float(result["wall_time_s"]))
                         for name, result in runs.items()}
    return results


def table(results):
    rows = ["| case | run | mean force [kN] | RMS difference to MoorDyn-C refined | wall [s] |",
            "|---|---|---|---|---|"]
    for case, runs in results.items():
        for name, r in runs.items():
            rows.append(f"| {case} | {name} | {r['other_mean_N'] / 1e3:.2f} | {100 * r['rms']:.3f} % | "
                        f"{r['wall_time_s']:.1f} |")
    return "\n".join(rows)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fast", action="store_true")
    parser.add_argument("--out", default=str(HERE))
    args = parser.parse_args(argv)
    results = run(fast=args.fast)
    print(table(results))
    if not args.fast:
        Path(args.out, "results.json").write_text(json.dumps(results, indent=1) + "\n")


if __name__ == "__main__":
    main()
