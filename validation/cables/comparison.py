"""The lazy wave's runs in both codes at a range of meshes, and what is compared: the static hang-off
tension and curvature peak, and over the run after its ramp the largest hang-off tension and the
largest curvature peak; each against MoorDyn-C's finest run (the reference) and the time each
code takes to come within 1 % of it."""

import numpy as np

from cablefem.model.motion import FairleadPath
from validation.cables import cablefem_side, case, moordyn_side

#: MoorDyn-C's coupling interval [s]: its coupled Rod moves at the secant velocity between two calls,
#: a velocity jump at each; the clamped cable rings with them (hang-off force at t = 10 s: -14.4 kN at
#: 0.05 s, -18.2 kN at 0.01, -18.65 at 0.005, -18.90 at 0.002; cablefem -18.77 at dt -> 0, 52 segments)
COUPLING = 0.002
OUTPUT = 0.05  # s between the compared values
#: cablefem's step [s] and integrator: BDF2 at 0.01 s is within 0.1 % of dt -> 0 at 10 s (0.05 s: 16 %)
DT, INTEGRATOR = 0.01, "bdf2"
TOLERANCE = 0.01  # the 1 %
QUANTITIES = ("static_tension", "static_peak", "run_tension", "run_peak")


def moordyn_dt(length):
    """MoorDyn's dtM [s] for segments of about ``length`` [m]: 1e-4 s, halved below 1 m (the axial
    wave crosses 0.6 m in 1.7e-4 s)."""
    return 1e-4 if length >= 1.0 else 5e-5


def summary(out):
    """The compared numbers of one run (``moordyn_side.run`` or ``cablefem_side.run``)."""
    after = out["times"] >= case.MOTION["ramp"]
    tension = np.linalg.norm(out["run_force"], axis=1)
    return {"static_tension": float(np.linalg.norm(out["force"])), "static_peak": float(out["curvature_peak"][0]),
            "static_peak_s": out["curvature_peak"][1], "run_tension": float(tension[after].max()),
            "run_peak": float(out["run_peak"][after].max()),
            "run_time_of_peak": float(out["times"][after][np.argmax(out["run_peak"][after])]),
            "static_wall_time_s": out["static_wall_time_s"], "run_wall_time_s": out["run_wall_time_s"]}


def static_start(elements, folder):
    """cablefem's static shape on a fine mesh, positions(s) -> (n, 3): MoorDyn's relaxation starts there."""
    from cablefem.fem.system import build_system
    from cablefem.statics.solve import solve_static

    scene = case.cablefem_scene(elements, folder)
    system = build_system(scene, scene.lines[0], dynamic=False)
    X = solve_static(system).X
    return lambda s: system.fem.evaluate(X, s)


def runs(moordyn_lengths, cablefem_lengths, duration, folder):
    """Both codes on the lazy wave: a list per code of (mesh, summary, series) where series holds the
    times and the hang-off tension and curvature peak at each ``OUTPUT``."""
    scene = case.cablefem_scene(case.segments_for(1.0), folder)
    path = FairleadPath(scene.motion, np.array(case.HANG_OFF))
    start = static_start(case.segments_for(1.0), folder)
    every = int(round(OUTPUT / COUPLING))
    out = {"moordyn": [], "cablefem": []}
    for length in moordyn_lengths:
        segments = case.segments_for(length)
        result = moordyn_side.run(segments, moordyn_dt(length), start, duration, COUPLING,
                                  lambda t: path(t)[0], every=every)
        out["moordyn"].append(_entry({"segments": int(sum(segments)), "length": length, "dtM": moordyn_dt(length),
                                      "coupling": COUPLING}, result))
    for length in cablefem_lengths:
        elements = case.segments_for(length)
        result = cablefem_side.run(case.cablefem_scene(elements, folder), duration, OUTPUT, DT, INTEGRATOR)
        entry = _entry({"elements": int(sum(elements)), "length": length, "dt": DT, "integrator": INTEGRATOR,
                        "steps": result["steps"], "newton_iterations": result["newton_iterations"],
                        "static_iterations": result["iterations"],
                        "least_strain": float(result["run_least_strain"].min())}, result)
        out["cablefem"].append(entry)
    return out


def _entry(mesh, result):
    return {**mesh, **summary(result), "series": {"t": result["times"],
                                                  "tension": np.linalg.norm(result["run_force"], axis=1),
                                                  "peak": result["run_peak"]}}


def against(reference, entries):
    """Each entry's relative differences from ``reference`` in ``QUANTITIES`` (in place: "differences")."""
    for entry in entries:
        entry["differences"] = {q: entry[q] / reference[q] - 1.0 for q in QUANTITIES}
    return entries


def time_to_tolerance(entries, quantity, tolerance=TOLERANCE):
    """The cheapest entry (by static + run wall time) within ``tolerance`` of the reference in
    ``quantity`` from which every finer one stays within it; None if none does."""
    inside = [abs(e["differences"][quantity]) <= tolerance for e in entries]
    for k, entry in enumerate(entries):
        if all(inside[k:]):
            return entry
    return None
