"""MoorDyn's own test inputs in both codes under a smooth motion (issue 36, deliverable 6): the forces
on the moving points (and on a coupled body) compared over the last periods, each code at the file's
mesh and refined, and each code's statics at t = 0.

Cases (``CASES``), each a file of MoorDyn v2.7's ``tests/Mooring`` (``inputs/`` or
``tests/data/moordyn``; their READMEs name the sources), moved harmonically (ramped in over the first
period):

- ``polyester``: ``polyester/simple.txt``, a 1400 m polyester line (EA 3.339e8 N, BA -1: a
  critical damping ratio of 1 per segment) from an anchor on the seabed 372 m deep to a fairlead
  18 m below the surface, taut; its coupled point surged 5 m at 30 s.
- ``lines_body surge`` and ``lines_body surge+pitch``: ``lines_body.txt``, OC3-Hywind's three 902 m
  chain catenaries (BA -0.8) lying on the seabed 320 m deep, their fairleads points of a coupled body;
  the body surged 5 m at 30 s, and also pitched 3 deg in phase (its fairleads turned with it).
- ``bodyDrag``: ``body_tests/bodyDrag.txt``, a free 10 kg body (no volume, CdA 0.1 m^2) on a 4.5 m
  spring (10 kg/m, EA 500 N, BA -0.4, one segment) to a point 5 m below the surface, which the case
  makes Coupled and heaves 0.5 m at 5 s: the body hangs 10.8 m deep and swings 0.63 m.

Rows per case: MoorDyn-C on the file (its NumSegs and dtM) and refined (the case's factor on the
segments, its smaller dtM, BA given as the file's N s so that -zeta does not change with the segment
length); cablefem on the scene as ``cablefem run`` reads it (its default mesh, BDF2 at the case's dt)
and refined (P2 elements, the case's factor x as many as it reads, at its refined dt). Each row is
compared with MoorDyn-C's refined run over the last ``WINDOW_PERIODS`` periods:
``validation.moordyn.comparison.differences`` (RMS, relative to the reference's mean) of the force
magnitude on each coupled point (the largest over the points), on a coupled body's points summed
(force) and their moment about its reference point (``validation.moordyn_parity.bodies``), and of a
free body's height (RMS over the reference's half range). MoorDyn-C's force is the force on the
point with its end node's inertia subtracted (``forces_on_point``), the force cablefem's reaction gives.

MoorDyn-C starts from its initial-condition solve; the free body from the state MoorDyn-C settles in
with the driven point held (``settled_state``; the file's TmaxIC is 0), cablefem from its statics.
MoorDyn-C is coupled every 0.01 s (bodyDrag: 1e-3 s: its one short stiff spring turns the kinks of
the piecewise-linear coupled motion into a force 0.5 % RMS smaller at 0.01 s; README).

    python -m validation.moordyn_parity.run [--fast] [--case NAME ...] [--out DIR]

``--fast`` runs the file-mesh rows only, against MoorDyn-C on the file (bodyDrag: against MoorDyn-C
refined, which its one segment is far from; what tests/test_moordyn_parity.py asserts).
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
from validation.moordyn.runners import (COUPLING_DT, point_order, refined, run_cablefem_case,  # noqa: E402
                                        run_moordyn_case)
from validation.moordyn_parity.bodies import (cablefem_body_loads, run_cablefem_free,  # noqa: E402
                                              run_moordyn_body)

HERE = Path(__file__).resolve().parent
INPUTS = HERE / "inputs"
MOORDYN_FILES = HERE.parents[1] / "tests" / "data" / "moordyn"
WINDOW_PERIODS = 2
#: per case: the input, what moves ("points": [motion] on its coupled points; "coupled body": the
#: body's six-component motion; "free body": [motion] on the point ``driven``, made Coupled, with the
#: body free), the amplitude ([m] or 6 components [m, deg]) and period [s], periods simulated (the
#: first one a ramp), MoorDyn's IC step [s], its step refined [s] and its segments refined (a factor),
#: cablefem's step [s], its elements refined (a factor) and its step refined [s]; MoorDyn-C's coupling
#: interval [s] where not ``COUPLING_DT``; "fast_reference": "refined" where --fast compares with
#: MoorDyn-C refined (a few seconds), not with its file. polyester: half the
#: segment length doubles the damping ratio the file's BA gives a segment, and 1.25e-3 s went unstable;
#: bodyDrag: one segment in the file, whose lumped end node puts half the spring's 45 kg on the 10 kg
#: body (README), refined 16 times.
CASES = {
    "polyester": {"file": INPUTS / "polyester_simple.txt", "moves": "points", "amplitude": [5.0, 0.0, 0.0],
                  "period": 30.0, "periods": 4, "ic_dtM": 0.005, "refined_dtM": 2.5e-4, "segments": 2,
                  "dt": 0.1, "elements": 2, "refined_dt": 0.025},
    "lines_body surge": {"file": MOORDYN_FILES / "lines_body.txt", "moves": "coupled body",
                         "amplitude": [5.0, 0.0, 0.0, 0.0, 0.0, 0.0], "period": 30.0, "periods": 4,
                         "ic_dtM": 0.002, "refined_dtM": 5e-4, "segments": 4, "dt": 0.1, "elements": 2,
                         "refined_dt": 0.025},
    "lines_body surge+pitch": {"file": MOORDYN_FILES / "lines_body.txt", "moves": "coupled body",
                               "amplitude": [5.0, 0.0, 0.0, 0.0, 3.0, 0.0], "period": 30.0, "periods": 4,
                               "ic_dtM": 0.002, "refined_dtM": 5e-4, "segments": 4, "dt": 0.1, "elements": 2,
                               "refined_dt": 0.025},
    "bodyDrag": {"file": MOORDYN_FILES / "laws" / "bodyDrag.txt", "moves": "free body", "driven": "point2",
                 "amplitude": [0.0, 0.0, 0.5], "period": 5.0, "periods": 6, "ic_dtM": 0.002,
                 "refined_dtM": 5e-4, "segments": 16, "dt": 0.05, "elements": 4, "refined_dt": 0.0125,
                 "coupling_dt": 1e-3, "fast_reference": "refined"},
}
#: the free body's start in MoorDyn-C [s]: the file's TmaxIC is 0 (no initial-condition solve, the
#: body 5 m above its anchor) and its stationary solve stops with the body where it starts (its
#: convergence test compares errors dtIC apart); MoorDyn-C instead steps this long with the driven
#: point held, and the run starts from the state it settles in (``settled_state``)
SETTLE = 100.0
BODY = "body1"


def source_text(case):
    """The case's MoorDyn file text as both codes read it: a free body's driven point made Coupled."""
    spec = CASES[case]
    text = spec["file"].read_text()
    if spec["moves"] == "free body":
        number = spec["driven"].removeprefix("point")
        text, count = re.subn(rf"^(\s*{number}\s+)Fixed\b", r"\1Coupled", text, flags=re.M)
        if count != 1:
            raise ValueError(f"{spec['file']}: no Fixed point {number} to drive")
    return text


def scene_of(case):
    """The scene cablefem reads: the MoorDyn file wrapped in a TOML with the case's motion."""
    spec = CASES[case]
    amplitude = ", ".join(repr(float(a)) for a in spec["amplitude"])
    table = f"[bodies.{BODY}.motion]" if spec["moves"] == "coupled body" else "[motion]"
    with tempfile.TemporaryDirectory(prefix="parity-scene-") as folder:
        source = Path(folder) / spec["file"].name
        source.write_text(source_text(case))
        wrapper = Path(folder) / f"{case.replace(' ', '_').replace('+', '_')}.toml"
        wrapper.write_text(f'name = "{wrapper.stem}"\n[moordyn]\nfile = "{source.name}"\n{table}\n'
                           f'kind = "harmonic"\namplitude = [{amplitude}]\nperiod = {spec["period"]!r}\n'
                           f'ramp = {spec["period"]!r}\n')
        return load_scene(wrapper)


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
    """MoorDyn-C on the case's file (factor 1) or at the case's refined segments and dtM."""
    spec = CASES[case]
    source = spec["file"]
    duration = spec["period"] * spec["periods"]
    text = source_text(case)
    dtM = float(peer.option_value(text, "dtM"))
    fine = spec["refined_dtM"]
    coupling = spec.get("coupling_dt", COUPLING_DT)
    settings = {"segments": 1 if factor == 1 else spec["segments"], "dtM": dtM if factor == 1 else fine,
                "ic_dtM": spec["ic_dtM"] if factor == 1 else min(fine, spec["ic_dtM"])}
    with tempfile.TemporaryDirectory(prefix="parity-") as folder:
        work = Path(folder) / source.name
        work.write_text(absolute_damping(text, scene) if factor != 1 else text)
        if spec["moves"] == "coupled body":
            return run_moordyn_body(work, scene, BODY, duration, settings, coupling)
        if spec["moves"] == "free body":
            def height(moordyn, system):
                return moordyn.GetBodyState(moordyn.GetBody(system, 1))[0][2:3]
            start = settled_state(work, settings)
            result = run_moordyn_case(work, scene, duration, settings, probe=height, initial_state=start,
                                      coupling_dt=coupling)
            result["z"] = result["probes"][:, 0]
            return result
        return run_moordyn_case(work, scene, duration, settings, coupling_dt=coupling)


def settled_state(path, settings):
    """MoorDyn-C's state (bytes of ``moordyn.Serialize``) after ``SETTLE`` s of the file ``path`` at
    ``settings``' segments and dtM, its coupled points held where the file has them."""
    import moordyn

    text = path.read_text()
    segments = {line: n * settings["segments"] for line, n in peer.line_segments(text).items()}
    _, points = peer.coupled_points(path)
    with tempfile.TemporaryDirectory(prefix="parity-settle-") as folder:
        work = Path(folder) / path.name
        work.write_text(peer.rewrite_input(text, settings["dtM"], segments))
        with peer.silenced_stdout():
            system = moordyn.Create(str(work))
            try:
                moordyn.Init(system, points.ravel(), np.zeros(points.size))
                moordyn.Step(system, points.ravel(), np.zeros(points.size), 0.0, SETTLE)
                return moordyn.Serialize(system)
            finally:
                moordyn.Close(system)


def cablefem_run(case, scene, factor):
    """cablefem's BDF2 on the scene as read (factor 1), or on P2 elements the case's factor x as many
    as it reads, at its refined step."""
    spec = CASES[case]
    duration = spec["period"] * spec["periods"]
    dt = spec["dt"]
    if factor != 1:
        scene = refined(scene, spec["elements"])
        scene = replace(scene, lines=[replace(line, order=2) for line in scene.lines])
        dt = spec["refined_dt"]
    if spec["moves"] == "free body":
        return run_cablefem_free(scene, duration, dt, BODY, spec["driven"])
    result = run_cablefem_case(scene, duration, dt)
    if spec["moves"] == "coupled body":
        loads = cablefem_body_loads(scene, BODY, result)
        result["forces_on_point"], result["body_force"], result["body_moment"] = loads
    return result


def magnitudes(run, key, grid):
    """|run[key]| on ``grid``: (m, k) for forces on k points, (m,) for a body's (n, 3)."""
    return np.linalg.norm(on_grid(run["t"], run[key], grid), axis=-1)


def compare(case, scene, reference, run, t_from):
    """A run against MoorDyn-C's ``reference`` over t >= t_from, on the coarser of the two time grids:
    ``differences`` of the force magnitude on each coupled point (the largest RMS of them; cablefem's
    lines matched to MoorDyn-C's points), of a coupled body's force and moment, and of a free body's
    height (its RMS relative to the reference's half range). ``static``: the forces' difference at
    t = 0, each code's statics (relative, the largest over the points)."""
    grid = run["t"] if len(run["t"]) <= len(reference["t"]) else reference["t"]
    moves = CASES[case]["moves"]
    ref = magnitudes(reference, "forces_on_point", grid)
    if "forces_on_point" in run:
        other = magnitudes(run, "forces_on_point", grid)
    else:  # cablefem's reactions, lines in scene order
        order = [0] if moves == "free body" else point_order(scene, reference["points"])
        other = magnitudes(run, "forces", grid)[:, order]
    rows = [differences(grid, ref[:, k], other[:, k], t_from) for k in range(ref.shape[1])]
    result = dict(max(rows, key=lambda row: row["rms"]))
    result["static"] = float(max(abs(other[0, k] / ref[0, k] - 1.0) for k in range(ref.shape[1])))
    if moves == "coupled body":
        for key in ("body_force", "body_moment"):
            found = differences(grid, magnitudes(reference, key, grid), magnitudes(run, key, grid), t_from)
            result[f"{key}_rms"], result[f"{key}_mean_N"] = found["rms"], found["reference_mean_N"]
    if moves == "free body":
        window = grid >= t_from - 1e-9
        z_ref, z = (np.interp(grid, r["t"], r["z"])[window] for r in (reference, run))
        half_range = 0.5 * (z_ref.max() - z_ref.min())
        result.update(heave_rms=float(np.sqrt(np.mean((z - z_ref) ** 2)) / half_range),
                      heave_half_range_m=float(half_range), z_mean_m=float(z.mean()),
                      static_z_m=float(np.interp(0.0, run["t"], run["z"])))
    return result


def run(fast=False, cases=None):
    """Every case's rows: {case: {row: differences against the reference, with wall_time_s}}."""
    results = {}
    for case in cases or CASES:
        spec = CASES[case]
        scene = scene_of(case)
        t_from = spec["period"] * (spec["periods"] - WINDOW_PERIODS)
        runs = {"MoorDyn-C, file": moordyn_run(case, scene, 1),
                "cablefem, file": cablefem_run(case, scene, 1)}
        if not fast or spec.get("fast_reference") == "refined":
            runs["MoorDyn-C, refined"] = moordyn_run(case, scene, 2)
        if not fast:
            runs["cablefem, refined"] = cablefem_run(case, scene, 2)
        reference = runs.get("MoorDyn-C, refined", runs["MoorDyn-C, file"])
        results[case] = {name: dict(compare(case, scene, reference, result, t_from),
                                    wall_time_s=float(result["wall_time_s"]))
                         for name, result in runs.items()}
    return results


def table(results):
    rows = [("| case | run | mean force [kN] | statics | RMS: points (largest) | body force | body moment "
             "| body heave | wall [s] |"), "|---|---|---|---|---|---|---|---|---|"]
    for case, runs in results.items():
        for name, r in runs.items():
            body = (f"{100 * r['body_force_rms']:.3f} % | {100 * r['body_moment_rms']:.3f} % | –"
                    if "body_force_rms" in r else f"– | – | {100 * r['heave_rms']:.2f} %" if "heave_rms" in r
                    else "– | – | –")
            rows.append(f"| {case} | {name} | {r['other_mean_N'] / 1e3:.3f} | {100 * r['static']:.3f} % | "
                        f"{100 * r['rms']:.3f} % | {body} | {r['wall_time_s']:.1f} |")
    return "\n".join(rows)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fast", action="store_true")
    parser.add_argument("--out", default=str(HERE))
    parser.add_argument("--case", action="append", choices=sorted(CASES),
                        help="run this case only (repeatable); results.json keeps the other cases' rows")
    args = parser.parse_args(argv)
    results = run(fast=args.fast, cases=args.case)
    print(table(results))
    if not args.fast:
        stored = Path(args.out, "results.json")
        kept = json.loads(stored.read_text()) if args.case and stored.exists() else {}
        kept.update(results)
        stored.write_text(json.dumps({case: kept[case] for case in CASES if case in kept}, indent=1) + "\n")


if __name__ == "__main__":
    main()
