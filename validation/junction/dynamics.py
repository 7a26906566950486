"""The crowfoot's dynamics: MoorDyn-C and cablefem's junction steps under the fairlead's motion,
each code's convergence ladder, and their comparison."""

import tempfile
import time
from pathlib import Path

import numpy as np

from cablefem.dynamics.registry import INTEGRATORS
from cablefem.model.motion import fairlead_motion
from cablefem.model.network import dynamic_lines
from cablefem.model.network import anchor_path, boundary_path
from cablefem.fem.system import build_system
from cablefem.dynamics.group import junction_groups
from cablefem.statics.scene import start_states
from cablefem.dynamics.registry import integrator_options

from validation.junction.inputs import (CASES, CLUMP, FILE_ELEMENTS, IC_DTM, ORDER, case_duration, moordyn_text,
                                        scene_of, toml_text)
from validation.moordyn import peer
from validation.moordyn.comparison import differences, on_grid
from validation.moordyn.runners import COUPLING_DT, moordyn_motion

QUANTITIES = ("fairlead", "anchor1", "anchor2")  # tension series compared (and the junction's position)

#: convergence ladders: MoorDyn (segments factor on the file's 5 m, dtM [s]); cablefem (elements
#: factor on the file's, dt [s]); the last entry of each is its reference (MoorDyn at 1.25 m segments
#: needs dtM <= 5e-5 s, ~9 s per simulated second here: not run). fast: the coarse runs of
#: the dynamic case over its ramp and one period (tests/test_validation_junction.py)
LADDERS = {
    "full": {"moordyn": [(1, 4e-4), (1, 2e-4), (2, 2e-4), (2, 1e-4)],
             "cablefem": [(1, 0.02), (1, 0.01), (2, 0.01), (2, 0.005), (4, 0.005)]},
    "fast": {"moordyn": [(0.5, 8e-4)], "cablefem": [(0.5, 0.02)]},
}


def probe(moordyn, system):
    """MoorDyn's junction position (3,) [m], then the forces (3,) [N] of lines 2 and 3 on their
    anchors (their node 0's net force: tension, half a segment's weight and drag)."""
    junction = moordyn.GetPointPos(moordyn.GetPoint(system, 2))
    anchors = [moordyn.GetLineNodeForce(moordyn.GetLine(system, i), 0) for i in (2, 3)]
    return np.concatenate([junction, *anchors])


def run_moordyn(scene, factor, dtM, duration, initial_states=None, coupling_dt=COUPLING_DT):
    """MoorDyn on the crowfoot (NumSegs times ``factor``, step dtM [s]) under the scene's motion:
    t (n,), fairlead, anchor1, anchor2 tensions (n,) [N] (the fairlead's with the end node's
    inertia taken out: the force on the point), junction (n, 3) [m], wall times [s].
    ``initial_states`` {factor: bytes}: MoorDyn's initial condition of an earlier run with the same
    segments is reused (its stationary solve, with steps of IC_DTM / factor, is kept there).
    ``coupling_dt`` [s]: the interval of MoorDyn's coupling calls (the README's coupling switch)."""
    initial_states = {} if initial_states is None else initial_states
    with tempfile.TemporaryDirectory(prefix="crowfoot-md-") as folder:
        path = Path(folder) / "crowfoot.dat"
        path.write_text(moordyn_text(factor))
        _, points = peer.coupled_points(path)
        r = peer.run_moordyn(path, moordyn_motion(scene, points), duration, coupling_dt, dtM=dtM, probe=probe,
                             ic_dtM=IC_DTM / factor, initial_state=initial_states.get(factor))
        initial_states.setdefault(factor, r["initial_state"])
    acceleration = fairlead_motion(scene.motion, r["t"])[2]
    fairlead = r["forces"][:, 0] - np.einsum("nab,nb->na", r["end_mass"][:, 0], acceleration)
    p = r["probes"]
    return {"t": r["t"], "fairlead": np.linalg.norm(fairlead, axis=1), "fairlead_raw": r["tensions"][:, 0],
            "anchor1": np.linalg.norm(p[:, 3:6], axis=1),
            "anchor2": np.linalg.norm(p[:, 6:9], axis=1), "junction": p[:, :3],
            "wall_time_s": r["wall_time_s"], "init_time_s": r["init_time_s"],
            "step_time_s": r["wall_time_s"] - r["init_time_s"], "segments": r["segments"], "dtM": dtM}


def run_cablefem(case, factor, dt, duration, order=ORDER, compiled=True, **changes):
    """cablefem's BDF2 junction steps on the crowfoot under ``case``'s motion (elements times
    ``factor``, step dt [s]; ``changes``: ``toml_text``'s switches), from the network statics: the
    same dict as ``run_moordyn`` plus Newton counters."""
    scene = scene_of(toml_text(case, factor, order, dt, duration, **changes))
    start = time.perf_counter()
    lines = dynamic_lines(scene)
    systems = [build_system(scene, line) for line in lines]
    states, _ = start_states(scene, systems=systems)
    options = {**integrator_options(scene.solver), "compiled": compiled}
    integrators = [INTEGRATORS["bdf2"](s, X, boundary_path(scene, line), dt=dt, anchor=anchor_path(scene, line),
                                       **options) for s, line, X in zip(systems, scene.lines, states)]
    group = junction_groups(scene, integrators)[0]
    initialised = time.perf_counter()
    names = [line.name for line in scene.lines]
    upper, leg1, leg2 = (integrators[names.index(n)] for n in ("upper", "leg1", "leg2"))
    k = group.members.index(leg1)
    junction_dof = group.ends[k][0][3]
    steps = int(round(duration / dt))
    t = np.arange(steps + 1) * dt
    series = np.empty((steps + 1, 6))

    def sample(i):
        series[i, 0] = np.linalg.norm(upper.reactions()[0])
        series[i, 1] = np.linalg.norm(leg1.reactions()[1])
        series[i, 2] = np.linalg.norm(leg2.reactions()[1])
        series[i, 3:] = leg1.X[junction_dof]

    sample(0)
    for i in range(1, steps + 1):
        integrators[0].march(t[i:i + 1])
        sample(i)
    finished = time.perf_counter()
    return {"t": t, "fairlead": series[:, 0], "anchor1": series[:, 1], "anchor2": series[:, 2],
            "junction": series[:, 3:], "wall_time_s": finished - start, "init_time_s": initialised - start,
            "step_time_s": finished - initialised, "newton_iterations": int(group.members[0].newton_iterations),
            "halvings": int(group.members[0].rejected), "elements": {n: int(round(FILE_ELEMENTS[n] * factor)) for n in names}, "dt": dt,
            "order": order}


def compare(reference, other, t_from):
    """``other`` against ``reference`` over t >= t_from [s] on the coarser of their time grids: per
    tension ``differences`` (relative to the reference's mean), and for the junction the RMS and
    largest distance [m] and the RMS distance over the reference junction's RMS excursion."""
    grid = reference["t"] if len(reference["t"]) <= len(other["t"]) else other["t"]
    out = {}
    for name in QUANTITIES:
        a, b = (on_grid(run["t"], run[name], grid) for run in (reference, other))
        out[name] = differences(grid, a, b, t_from)
    a, b = (on_grid(run["t"], run["junction"], grid) for run in (reference, other))
    window = grid >= t_from - 1e-9
    a, b = a[window], b[window]
    distance = np.linalg.norm(b - a, axis=1)
    excursion = float(np.sqrt(np.mean(np.sum((a - a.mean(axis=0)) ** 2, axis=1))))
    out["junction"] = {"rms_m": float(np.sqrt(np.mean(distance ** 2))), "max_m": float(distance.max()),
                       "mean_m": float(np.linalg.norm(b.mean(axis=0) - a.mean(axis=0))),
                       "excursion_rms_m": excursion,
                       "rms": float(np.sqrt(np.mean(distance ** 2)) / excursion)}
    return out


def _label(code, run):
    if code == "moordyn":
        return f"MoorDyn {run['segments']['1']}/{run['segments']['2']} segments, dtM {run['dtM']:g} s"
    return f"cablefem P{run['order']} {run['elements']['upper']}/{run['elements']['leg1']} elements, dt {run['dt']:g} s"


def _series(run):
    return {key: run[key] for key in ("t", "fairlead", "anchor1", "anchor2", "junction")}


#: cablefem variants run at the coarse settings of the dynamic case against MoorDyn's coarse run:
#: what each part of the physics is worth (none is needed to reach the targets)
SWITCHES = {
    "clump_without_added_mass": {"clump": {"Ca": 0.0}},
    "clump_without_drag": {"clump": {"CdA": 0.0}},
    "clump_mass_10_percent_high": {"clump": {"mass": 1.1 * CLUMP["mass"]}},
    "cablefem_damping_law": {"slack_damping": False},
}


def run_case(case, fast, log=print, initial_states=None):
    """Both codes' ladders on ``case`` and their comparison: a dict (series of the finest runs
    under "series")."""
    mode = "fast" if fast else "full"
    motion = CASES[case]["motion"]
    duration = motion["ramp"] + motion["period"] if fast else case_duration(case)
    t_from = duration - (1 if fast else 2) * motion["period"]
    scene = scene_of(toml_text(case))
    runs = {"moordyn": [], "cablefem": []}
    for factor, dtM in LADDERS[mode]["moordyn"]:
        runs["moordyn"].append(run_moordyn(scene, factor, dtM, duration, initial_states))
        log(f"{case}: {_label('moordyn', runs['moordyn'][-1])}: {runs['moordyn'][-1]['wall_time_s']:.1f} s")
    for factor, dt in LADDERS[mode]["cablefem"]:
        runs["cablefem"].append(run_cablefem(case, factor, dt, duration))
        log(f"{case}: {_label('cablefem', runs['cablefem'][-1])}: {runs['cablefem'][-1]['wall_time_s']:.1f} s")
    md_ref, cf_ref = runs["moordyn"][-1], runs["cablefem"][-1]
    out = {"duration_s": duration, "statistics_from_s": t_from, "motion": motion,
           "initial_conditions": [{"label": _label("moordyn", r), "junction_m": r["junction"][0],
                                   "fairlead_N": r["fairlead"][0], "anchor1_N": r["anchor1"][0],
                                   "anchor2_N": r["anchor2"][0]} for r in runs["moordyn"]]}
    out["ladders"] = {code: [{"label": _label(code, r), "against_own_reference": compare(ref, r, t_from),
                              "against_other_reference": compare(other, r, t_from),
                              "wall_time_s": r["wall_time_s"], "init_time_s": r["init_time_s"],
                              "step_time_s": r["step_time_s"], "s_per_simulated_s": r["step_time_s"] / duration,
                              **({"newton_iterations": r["newton_iterations"], "halvings": r["halvings"]}
                                 if code == "cablefem" else {})}
                             for r in runs[code]]
                      for code, ref, other in (("moordyn", md_ref, cf_ref), ("cablefem", cf_ref, md_ref))}
    out["comparison"] = compare(md_ref, cf_ref, t_from)
    out["references"] = {"moordyn": _label("moordyn", md_ref), "cablefem": _label("cablefem", cf_ref)}
    if case == "dynamic" and not fast:
        coarse_md, coarse_cf = runs["moordyn"][0], runs["cablefem"][1]
        out["switches"] = {"base": {"label": f"{_label('cablefem', coarse_cf)} against {_label('moordyn', coarse_md)}",
                                    "comparison": compare(coarse_md, coarse_cf, t_from)}}
        for name, changes in SWITCHES.items():
            variant = run_cablefem(case, LADDERS["full"]["cablefem"][1][0], coarse_cf["dt"], duration, **changes)
            out["switches"][name] = {"changes": changes, "comparison": compare(coarse_md, variant, t_from)}
            log(f"{case}: switch {name}: {variant['wall_time_s']:.1f} s")
        raw = dict(coarse_md, fairlead=coarse_md["fairlead_raw"])
        out["switches"]["moordyn_end_node_inertia_kept"] = {
            "changes": "MoorDyn's coupled-point force as it returns it (the end node's inertia not taken out)",
            "comparison": compare(raw, coarse_cf, t_from)}
    out["series"] = {code: _series(r[-1]) for code, r in runs.items()}
    return out
