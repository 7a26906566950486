"""Speed against one common reference (issue 16, part 3): cablefem and MoorDyn-C on the frictionless
flume chain with aligned physics (``validation.moordyn_aligned``), both measured against the same
converged runs.

The study in ``run.py`` measures each code against its own finest run. Here every run of both codes
is measured against two references, the finest run of each code with aligned physics
(``validation/moordyn_aligned``): MoorDyn-C at 1280 segments (snap; 640 in slow surge) and
cablefem P1 x 640 (snap; P1 x 320 in slow surge). Without friction cablefem's rows and reference
have MoorDyn-C's seabed damper too (``[seabed] damping_when_opening``, ``SEABED_DAMPER_OPENING``:
the last difference validation/moordyn_aligned names with a switch); the references then differ by
0.011 % RMS in slow surge (0.022 % with Eq. 11's damper). For each MoorDyn error level (its runs at
the work-precision study's Pareto settings) the cheapest cablefem run at least as accurate against
the same reference gives the time ratio.

cablefem's rows (``Row``) are BDF2 unless a row names generalised-alpha and its rho_inf (labels
"P1 x 113, gen-a 0.9, dt 0.04"), in full Newton at tolerance 1e-4 unless the label names another.

Times are CPU seconds of the process (``time.process_time``), not wall time: the runs were made on
a shared machine whose load made wall times vary by 3-10x. cablefem's: statics, set-up and steps,
warm (numba's kernels loaded); MoorDyn's: its ``Create``, ``Init`` and ``Step`` calls only (the
peer's Python bookkeeping left out, in MoorDyn's favour), its initial-condition solve skipped
(TmaxIC 0), coupled every 0.01 s as in the study. Cheap runs are repeated and the least time kept;
the repeats come in passes over all rows of a motion, both codes' (``interleaved_least_cpu``).

With ``--friction`` the same study with the seabed friction of validation/moordyn and the
work-precision study (``common_friction``): references MoorDyn-C at 1280 segments, dtM 2e-5 s
(snap; 640 segments, dtM 1e-4 s, coupled every 5e-4 s in slow surge) and cablefem P1 x 640, dt
6.25e-4 s (snap; P1 x 320, dt 2.5e-3 s in slow surge), all with friction.

``python -m verification.work_precision.common [--friction] [--cache DIR] [--out DIR]`` (the
references are read from and kept in DIR: the aligned study's cache for the frictionless ones);
writes ``common.json`` (``common_friction.json``).
"""

import argparse
import contextlib
import sys
import time
from dataclasses import replace
from functools import partial
from pathlib import Path
from typing import NamedTuple

import numpy as np

if __package__ in (None, ""):
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.study import write_json  # noqa: E402
from validation.moordyn.run import COUPLING_DT, FLUME_FILE_SEGMENTS, run_moordyn_case  # noqa: E402
from validation.moordyn_aligned.run import (DURATION, MOORDYN_FILE, MOTIONS, WINDOW, aligned_scene,  # noqa: E402
                                            cablefem, compare, moordyn)
from verification.work_precision.common_friction import (CABLEFEM_ROWS_FRICTION, REFERENCES_FRICTION,  # noqa: E402
                                                          cablefem_friction, friction_scene, moordyn_friction)
from verification.work_precision.runs import run_cablefem_scene  # noqa: E402

HERE = Path(__file__).resolve().parent
#: MoorDyn's settings: the work-precision study's Pareto points (its results.json)
MOORDYN_ROWS = {"snap": [(20, 5e-3), (40, 2.5e-3), (80, 2.5e-3), (160, 2e-3), (320, 5e-4)],
                "slow": [(20, 5e-3), (40, 2.5e-3), (80, 2.5e-3), (160, 2e-3), (160, 1.25e-3), (320, 6.25e-4)]}


class Row(NamedTuple):
    """One cablefem row: element order and count, step dt [s], Newton's relative tolerance, the
    integrator (``cablefem.dynamics.registry.INTEGRATORS``), generalised-alpha's rho_inf (unused by BDF2) and
    ``[solver] newton`` ("full", as the aligned study runs; "auto", the scenes' default)."""

    order: int
    elements: int
    dt: float
    tolerance: float = 1e-4
    integrator: str = "bdf2"
    rho_inf: float = 0.5
    newton: str = "full"

    def label(self):
        kind = f"gen-a {self.rho_inf:g}, " if self.integrator == "generalized-alpha" else ""
        newton = "" if self.newton == "full" else f", {self.newton} Newton"
        tolerance = "" if self.tolerance == 1e-4 else f", tol {self.tolerance:g}"
        return f"P{self.order} x {self.elements}, {kind}dt {self.dt:g}{newton}{tolerance}"


#: cablefem's rows (``Row``'s fields; the first four for BDF2): the study's Pareto rows and finer ones
CABLEFEM_ROWS = {
    "snap": [(1, 10, 0.25, 1e-4), (1, 10, 0.2, 1e-4), (1, 14, 0.16, 1e-4), (2, 7, 0.16, 1e-4), (2, 10, 0.16, 1e-4),
             (1, 40, 0.16, 1e-4), (1, 80, 0.08, 1e-4),
             (2, 40, 0.08, 1e-4), (1, 160, 0.04, 1e-4), (1, 160, 0.02, 1e-4), (1, 226, 0.04, 1e-4),
             (1, 226, 0.02, 1e-4), (1, 320, 0.04, 1e-4), (2, 113, 0.02, 1e-4), (2, 160, 0.02, 1e-4),
             (1, 320, 0.02, 1e-4), (1, 320, 0.01, 1e-4), (2, 160, 0.01, 1e-4), (1, 640, 0.005, 1e-4)],
    "slow": [(1, 14, 0.17, 1e-4), (2, 14, 0.17, 1e-4), (1, 28, 0.17, 1e-4), (1, 57, 0.085, 1e-4),
             (2, 28, 0.085, 1e-4), (1, 80, 0.04, 1e-4), (1, 113, 0.04, 1e-4), (2, 57, 0.04, 1e-4),
             (1, 160, 0.02, 1e-4), (2, 80, 0.02, 1e-4), (1, 320, 0.01, 1e-4), (2, 80, 0.01, 1e-4),
             # without friction BDF2's time error decides below 0.3 %: finer steps on coarse meshes
             (1, 40, 0.01, 1e-4), (2, 20, 0.01, 1e-4), (2, 40, 0.01, 1e-4), (1, 80, 0.01, 1e-4),
             (2, 40, 0.005, 1e-4), (1, 80, 0.005, 1e-4), (2, 40, 0.0025, 1e-4), (2, 80, 0.0025, 1e-4),
             (2, 28, 0.02, 1e-4), (1, 113, 0.01, 1e-4), (2, 80, 0.005, 1e-4),
             # generalised-alpha has BDF2's error at twice the step here (rho_inf 0.8-0.95 alike; 1.0
             # keeps undamped oscillations that grow on P2 x 80); compiled, at BDF2's CPU per step. At dt
             # 0.04 every mesh stays at 0.24-0.34 % (P1 x 40 to P2 x 80): the rows step at 0.02 and 0.01
             (1, 113, 0.04, 1e-4, "generalized-alpha", 0.9), (2, 80, 0.02, 1e-4, "generalized-alpha", 0.9),
             *((o, n, dt, 1e-4, "generalized-alpha", 0.9)
               for o, n, dt in ((1, 40, 0.02), (2, 28, 0.02), (1, 57, 0.02), (2, 40, 0.02), (1, 80, 0.02),
                                (2, 57, 0.01), (1, 80, 0.01), (2, 80, 0.01))),
             # "auto" Newton (the scenes' default: modified Newton, its LU kept across steps, full
             # Newton for a while after trouble) at the same settings: in slow surge the tangent
             # changes slowly and the same runs take ~0.7x the instructions of full Newton (P1 x 40,
             # gen-a 0.9, dt 0.02: 0.93 G against 1.33 G, the same error); in snap it costs (P2 x 113,
             # dt 0.02: 1.8x the CPU), so the snap rows stay in full Newton
             *((o, n, dt, 1e-4, "generalized-alpha", 0.9, "auto")
               for o, n, dt in ((1, 113, 0.04), (1, 40, 0.02), (2, 28, 0.02), (1, 57, 0.02), (2, 40, 0.02),
                                (1, 80, 0.02), (2, 80, 0.02), (2, 57, 0.01), (1, 80, 0.01), (2, 80, 0.01),
                                (1, 40, 0.025), (1, 48, 0.025), (1, 57, 0.025), (2, 57, 0.02), (1, 113, 0.02),
                                (2, 80, 0.015), (1, 72, 0.016), (1, 80, 0.016), (1, 90, 0.0125))),
             *((o, n, dt, 1e-4, "bdf2", 0.5, "auto")
               for o, n, dt in ((1, 57, 0.085), (1, 80, 0.04), (2, 40, 0.01), (1, 80, 0.01), (2, 80, 0.01),
                                (2, 80, 0.005))),
             # modified Newton with a looser tolerance, 1e-3: here the error moves by < 1 % of itself
             # from 1e-4 (P1 x 80, gen-a 0.9, dt 0.0125: 0.0723 against 0.0725 %) while a step takes fewer
             # iterations, many ending after the first (policy.newton's first-iteration stop); rho_inf
             # 0.7 damps the high-frequency ringing that the first iterations leave (1.15 iterations
             # a step against 1.29 at 0.9) and costs little accuracy at dt <= 0.014
             *((o, n, dt, 1e-3, "generalized-alpha", rho, "modified")
               for o, n, dt, rho in ((1, 48, 0.03, 0.7), (1, 48, 0.03, 0.9), (1, 48, 0.025, 0.7), (1, 57, 0.03, 0.7),
                                     (1, 64, 0.0125, 0.7), (1, 72, 0.0125, 0.7), (1, 80, 0.0125, 0.7),
                                     (1, 80, 0.014, 0.7), (1, 80, 0.0125, 0.9), (1, 80, 0.014, 0.9),
                                     (1, 90, 0.014, 0.7), (2, 80, 0.0125, 0.7), (2, 80, 0.01, 0.7)))]}
REFERENCES = {"snap": {"moordyn": (1280, 2e-5, COUPLING_DT), "cablefem": (1, 640, 0.000625, 1e-8)},
              "slow": {"moordyn": (640, 1e-4, 5e-4), "cablefem": (1, 320, 0.0025, 1e-8)}}
REPEATS = ((0.2, 5), (1.0, 3), (3.0, 2))
#: frictionless cablefem rows and reference with MoorDyn-C's seabed damper (acting on points moving
#: out too): aligned physics (validation/moordyn_aligned, "the named differences and their switches")
SEABED_DAMPER_OPENING = True


def repeats(cpu):
    """How many times a row whose first run took ``cpu`` seconds runs (``REPEATS``)."""
    return next((n for limit, n in REPEATS if cpu < limit), 1)


def interleaved_least_cpu(runs):
    """``runs``: callables -> (result, cpu seconds). Each runs once, then again in passes over all of
    them until it has run as often as ``REPEATS`` says: a row's repeats are spread over the whole
    study, so that this machine's speed, which drifts by 1.5x over minutes, moves every row alike
    rather than the rows that happened to run in a slow minute. Returns [(result, least cpu)]."""
    found = [run() for run in runs]
    counts = [repeats(cpu) for _, cpu in found]
    for k in range(1, max(counts, default=1)):
        for i, run in enumerate(runs):
            if counts[i] > k:
                found[i] = (found[i][0], min(found[i][1], run()[1]))
    return found


@contextlib.contextmanager
def moordyn_cpu_clock():
    """Inside the block, MoorDyn's Create, Init and Step add their CPU seconds to the yielded list's item 0."""
    import moordyn

    spent, saved = [0.0], {}
    for name in ("Create", "Init", "Step"):
        function = saved[name] = getattr(moordyn, name)

        def timed(*args, _function=function):
            begin = time.process_time()
            try:
                return _function(*args)
            finally:
                spent[0] += time.process_time() - begin
        setattr(moordyn, name, timed)
    try:
        yield spent
    finally:
        for name, function in saved.items():
            setattr(moordyn, name, function)


def moordyn_row(motion, segments, dtM, friction=False):
    """MoorDyn at ``segments`` and ``dtM``, frictionless unless ``friction`` (the file's, FricDamp
    scaled with the segments): (t, tension) dict and its CPU seconds."""
    from cablefem.model.builtin import flume_scene

    scene = flume_scene("flat", MOTIONS[motion])
    with moordyn_cpu_clock() as spent:
        run = run_moordyn_case(MOORDYN_FILE, scene, DURATION[motion],
                               {"segments": segments / FLUME_FILE_SEGMENTS, "dtM": dtM, "ic_dtM": None},
                               options={"TmaxIC": 0.0, **({} if friction else {"FrictionCoefficient": 0.0})})
    return {"t": run["t"][1:], "tension": np.linalg.norm(run["forces_on_point"][1:, 0], axis=1)}, spent[0]


def cablefem_row(motion, row, friction=False):
    """cablefem on the aligned scene (with the flume's friction if ``friction``) with the settings of
    ``row`` (a ``Row``): (t, tension) dict and its CPU seconds."""
    if friction:
        scene = friction_scene(motion, row.order, row.elements, row.dt, tolerance=row.tolerance)
    else:
        scene = aligned_scene(motion, row.order, row.elements, row.dt, tolerance=row.tolerance,
                              damping_when_opening=SEABED_DAMPER_OPENING)
    scene.solver = replace(scene.solver, integrator=row.integrator, rho_inf=row.rho_inf, newton=row.newton)
    begin = time.process_time()
    run = run_cablefem_scene(scene)
    return run, time.process_time() - begin


def cheapest(moordyn_rows, cablefem_rows, key):
    """For every MoorDyn row (by CPU time; a row joins when 2 % better than the last): the cheapest
    cablefem row at least as accurate in ``key`` ("moordyn" or "cablefem" reference) and the ratio."""
    table, best = [], np.inf
    for md in sorted(moordyn_rows, key=lambda r: r["cpu_s"]):
        error = md["error"][key]["rms"]
        if error >= best * 0.98:
            continue
        best = error
        good = [r for r in cablefem_rows if r["error"][key]["rms"] <= error]
        cf = min(good, key=lambda r: r["cpu_s"]) if good else None
        table.append({"moordyn": md["label"], "error": error, "moordyn_peak": md["error"][key]["peak"],
                      "moordyn_cpu_s": md["cpu_s"], "cablefem": cf["label"] if cf else None,
                      "cablefem_error": cf["error"][key]["rms"] if cf else None,
                      "cablefem_peak": cf["error"][key]["peak"] if cf else None,
                      "cablefem_cpu_s": cf["cpu_s"] if cf else None,
                      "ratio": cf["cpu_s"] / md["cpu_s"] if cf else None})
    return table


def references(motion, friction, cache):
    """Both codes' finest runs (``REFERENCES`` or ``REFERENCES_FRICTION``): settings and series."""
    ref = (REFERENCES_FRICTION if friction else REFERENCES)[motion]
    if friction:
        return ref, {"moordyn": moordyn_friction(motion, *ref["moordyn"], cache=cache),
                     "cablefem": cablefem_friction(motion, *ref["cablefem"], cache=cache)}
    variant = "two-sided-contact-damping" if SEABED_DAMPER_OPENING else None
    return ref, {"moordyn": moordyn(motion, *ref["moordyn"], cache=cache),
                 "cablefem": cablefem(motion, *ref["cablefem"], variant=variant, cache=cache)}


def run(cache=None, log=print, friction=False):
    """Both codes' rows against both references, and the ratio tables, per motion. The timed rows
    run first, the references (read from ``cache`` when there) after them."""
    from verification.work_precision.run import warm_up

    warm_up()
    results = {"clock": "process CPU seconds", "friction": friction, "references": {},
               "damping_when_opening": SEABED_DAMPER_OPENING and not friction}
    for motion in ("slow", "snap"):
        md_rows = MOORDYN_ROWS[motion]
        cf_rows = [Row(*r) for r in (CABLEFEM_ROWS_FRICTION if friction else CABLEFEM_ROWS)[motion]]
        timed = interleaved_least_cpu(
            [partial(moordyn_row, motion, segments, dtM, friction) for segments, dtM in md_rows]
            + [partial(cablefem_row, motion, row, friction) for row in cf_rows])
        series = {"moordyn": [(f"{segments} segments, dtM {dtM:g}", cpu, found)
                              for (segments, dtM), (found, cpu) in zip(md_rows, timed)],
                  "cablefem": [(row.label(), cpu, found) for row, (found, cpu) in zip(cf_rows, timed[len(md_rows):])]}
        ref, refs = references(motion, friction, cache)
        t_from = WINDOW[motion]
        results["references"][motion] = {"moordyn": ref["moordyn"], "cablefem": ref["cablefem"],
                                         "cablefem_vs_moordyn": compare(refs["cablefem"], refs["moordyn"], t_from)}
        rows = {code: [{"label": label, "cpu_s": cpu, "error": {k: compare(found, r, t_from) for k, r in refs.items()}}
                       for label, cpu, found in series[code]] for code in series}
        for code in rows:
            for row in rows[code]:
                e = row["error"]
                log(f"  {motion} {code:<8} {row['label']:<58} {row['cpu_s']:7.3f} s CPU | vs MoorDyn ref: RMS "
                    f"{100 * e['moordyn']['rms']:6.2f} % peak {100 * e['moordyn']['peak']:+6.2f} % | vs cablefem ref: "
                    f"RMS {100 * e['cablefem']['rms']:6.2f} % peak {100 * e['cablefem']['peak']:+6.2f} %")
        results[motion] = {"rows": rows, "ratios": {key: cheapest(rows["moordyn"], rows["cablefem"], key)
                                                    for key in ("moordyn", "cablefem")}}
        for key, table in results[motion]["ratios"].items():
            log(f"== {motion}, against the {key} reference")
            for r in table:
                log(f"  MoorDyn {r['moordyn']:<26} RMS {100 * r['error']:6.2f} % peak {100 * r['moordyn_peak']:+6.2f} % "
                    f"{r['moordyn_cpu_s']:7.3f} s | cablefem {r['cablefem']} "
                    + ("" if r["cablefem"] is None else
                       f"RMS {100 * r['cablefem_error']:6.2f} % peak {100 * r['cablefem_peak']:+6.2f} % "
                       f"{r['cablefem_cpu_s']:7.3f} s | ratio {r['ratio']:.2f}"))
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cache", type=Path, default=None, help="the aligned study's run cache (references)")
    parser.add_argument("--out", type=Path, default=HERE)
    parser.add_argument("--friction", action="store_true", help="with the flume's seabed friction")
    args = parser.parse_args(argv)
    results = run(cache=args.cache, friction=args.friction)
    write_json(args.out / ("common_friction.json" if args.friction else "common.json"), results)


if __name__ == "__main__":
    main()
