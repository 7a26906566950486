"""cablefem against MoorDyn-C on a crowfoot: one line from a coupled fairlead down to a free junction
carrying a clump, two legs from the junction to anchors (issue 18, ``cablefem.coupled_steps``).

Run ``python -m validation.junction.run [--fast] [--out DIR]``; ``run(fast=True)`` returns the
numbers tests/test_validation_junction.py asserts on. The README has the case, the alignment of
the physics and the latest numbers.

1. One scene, two files: ``inputs/crowfoot.dat`` (MoorDyn v2: the junction a Free point joining
   three lines, the fairlead a Coupled point moved through MoorDyn's coupling API by
   ``validation.moordyn.peer``) and ``inputs/crowfoot.toml`` (cablefem: a coupled [points] entry
   following [motion]), both written by ``write_inputs`` from the constants below.
2. Statics: the junction's position and the tensions against MoorPy's ``System`` (cablefem's
   network statics, ``cablefem.coupling``, and MoorDyn's initial condition).
3. Dynamics: each code refined (MoorDyn's segments and dtM; cablefem's elements and dt) until it
   is converged; the fairlead tension, both anchor tensions and the junction's position of the
   finest runs compared; time per simulated second of each code.
"""

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # python validation/junction/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.coupling import solve_network  # noqa: E402
from cablefem.dynamics import INTEGRATORS  # noqa: E402
from cablefem.io import load_scene  # noqa: E402
from cablefem.motion import fairlead_motion  # noqa: E402
from cablefem.network import dynamic_lines  # noqa: E402
from cablefem.results import end_forces  # noqa: E402
from cablefem.run import anchor_path, boundary_path, build_system, junction_steps, start_states  # noqa: E402
from cablefem.schemes import integrator_options  # noqa: E402
from cablefem.study import jsonable  # noqa: E402

from validation.moordyn import peer  # noqa: E402
from validation.moordyn.run import (COUPLING_DT, IC_OPTIONS, LINE_HEADER, OPTIONS_HEADER, OUTPUTS,  # noqa: E402
                                    POINT_HEADER, TYPE_HEADER, _type_row, differences, moordyn_motion, on_grid)

HERE = Path(__file__).resolve().parent
WATER_DENSITY, GRAVITY = 1025.0, 9.81
DEPTH = 300.0  # m: the anchors at 180 m, every line clear of the seabed (no contact, no friction)
#: chain (benchmarks/crowfoot.toml): d, kg/m, EA [N], beta [s] (BA = beta EA), Cd, Ca, Cd_tangential
#: (desire2023's, on d: MoorDyn's CdAx = Cd_tangential / pi, on pi d), CaAx
CHAIN = {"diameter": 0.1, "mass": 60.0, "EA": 5.0e8, "damping": 0.001, "Cd_normal": 1.2, "Ca_normal": 1.0,
         "Cd_tangential": 0.4, "Ca_tangential": 0.0}
FAIRLEAD = (-10.0, 0.0, -10.0)
JUNCTION = (-131.09, 0.0, -149.68)  # the start of both codes' searches: MoorPy's equilibrium to 1 cm
CLUMP = {"mass": 2000.0, "volume": 1.0, "CdA": 2.0, "Ca": 1.0}  # kg, m^3, m^2, -
ANCHORS = ((-400.0, 150.0, -180.0), (-400.0, -150.0, -180.0))
LENGTHS = {"upper": 185.0, "leg1": 330.0, "leg2": 330.0}  # m
#: per line: MoorDyn's NumSegs in the file (5 m segments) and cablefem's elements in the TOML
FILE_SEGMENTS = {"upper": 37, "leg1": 66, "leg2": 66}
FILE_ELEMENTS = {"upper": 8, "leg1": 14, "leg2": 14}
ORDER = 2
#: MoorDyn's stationary initial-condition solve steps with IC_DTM at the file's segments (held at
#: rest 10 s after it, its tensions move by < 1e-4; with the file's 4e-4 s it takes 10 x longer
#: for the same state to 1e-4)
IC_DTM = 5e-3
#: the cases: the fairlead's surge and heave, in phase, ramped in over one period (smoothstep); each
#: simulated for the ramp and ``periods`` more, statistics over the last two (fast: the last one)
CASES = {
    "slow": {"motion": {"amplitude": (4.0, 0.0, 1.0), "period": 10.0, "offset": (0.0, 0.0, 0.0), "ramp": 10.0},
             "periods": 3},
    "dynamic": {"motion": {"amplitude": (3.0, 0.0, 1.5), "period": 5.0, "offset": (0.0, 0.0, 0.0), "ramp": 5.0},
                "periods": 4},
}
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


# ----------------------------------------------------------------------------- input files
def _vector(values):
    return "[" + ", ".join(repr(float(v)) for v in values) + "]"


def _row(pid, kind, xyz, mass=0.0, volume=0.0, cda=0.0, ca=0.0):
    x, y, z = (repr(float(c)) for c in xyz)
    return f"{pid:<3} {kind:<11} {x:<10} {y:<10} {z:<10} {mass!r:<8} {volume!r:<6} {cda!r:<6} {ca!r}\n"


def moordyn_text(factor=1):
    """The crowfoot as MoorDyn v2 text, NumSegs the file's times ``factor``: points 1 fairlead
    (Coupled), 2 junction (Free, the clump), 3-4 anchors (Fixed); lines 1 upper (A junction, B
    fairlead), 2-3 legs (A anchor, B junction)."""
    props = {"Diam": CHAIN["diameter"], "MassDen": CHAIN["mass"], "EA": CHAIN["EA"], "Cd": CHAIN["Cd_normal"],
             "Ca": CHAIN["Ca_normal"], "CdAx": CHAIN["Cd_tangential"] / np.pi, "CaAx": CHAIN["Ca_tangential"]}
    points = (_row(1, "Coupled", FAIRLEAD)
              + _row(2, "Free", JUNCTION, CLUMP["mass"], CLUMP["volume"], CLUMP["CdA"], CLUMP["Ca"])
              + _row(3, "Fixed", ANCHORS[0]) + _row(4, "Fixed", ANCHORS[1]))
    segments = {name: int(round(n * factor)) for name, n in FILE_SEGMENTS.items()}
    lines = (f"1   chain     2        1        {LENGTHS['upper']!r}     {segments['upper']}       -\n"
             f"2   chain     3        2        {LENGTHS['leg1']!r}     {segments['leg1']}       -\n"
             f"3   chain     4        2        {LENGTHS['leg2']!r}     {segments['leg2']}       -\n")
    return ("--------------------- MoorDyn Input File ------------------------------------\n"
            "crowfoot: a coupled fairlead, a free junction with a clump, two legs to anchors; validation/junction\n"
            + TYPE_HEADER + _type_row("chain", props, CHAIN["damping"]) + "\n"
            + POINT_HEADER + points + LINE_HEADER + lines + OPTIONS_HEADER
            + "0.0004                dtM           - s, MoorDyn's explicit step\n"
            + f"{DEPTH!r:<21} WtrDpth       - m: every line clear of the seabed\n"
            + f"{WATER_DENSITY!r:<21} WtrDnsty      - kg/m^3\n"
            + f"{GRAVITY!r:<21} g             - m/s^2\n"
            + IC_OPTIONS
            + OUTPUTS.format(channels="FairTen1\nAnchTen2\nAnchTen3"))


def toml_text(case="dynamic", factor=1, order=ORDER, dt=0.01, duration=None, clump=None, slack_damping=True):
    """The same crowfoot as a cablefem TOML scene under ``case``'s motion, elements the file's times
    ``factor``; ``clump`` replaces keys of CLUMP, ``slack_damping`` False takes cablefem's own
    damping law (the switches)."""
    motion = CASES[case]["motion"]
    duration = case_duration(case) if duration is None else duration
    chain = "".join(f"{key} = {value!r}\n" for key, value in CHAIN.items())
    clump = "".join(f"{key} = {value!r}\n" for key, value in {**CLUMP, **(clump or {})}.items())
    lines = ""
    for name, (anchor, fairlead) in {"upper": ("j", "f"), "leg1": ("a1", "j"), "leg2": ("a2", "j")}.items():
        lines += (f"[[lines]]\nname = \"{name}\"\nanchor = \"{anchor}\"\nfairlead = \"{fairlead}\"\norder = {order}\n"
                  f"segments = [{{ type = \"chain\", length = {LENGTHS[name]!r}, "
                  f"elements = {int(round(FILE_ELEMENTS[name] * factor))} }}]\n")
    return ("# crowfoot: a coupled fairlead, a free junction with a clump, two legs to anchors; validation/junction\n"
            "# the same physics as crowfoot.dat (MoorDyn v2); damping_when_slack: MoorDyn-C's law\n"
            f"name = \"crowfoot\"\n[environment]\nwater_density = {WATER_DENSITY!r}\ngravity = {GRAVITY!r}\n"
            f"[line_types.chain]\n{chain}damping_when_slack = {str(slack_damping).lower()}\n"
            f"[points.f]\nkind = \"coupled\"\nposition = {_vector(FAIRLEAD)}\n"
            f"[points.j]\nkind = \"free\"\nposition = {_vector(JUNCTION)}\n{clump}"
            f"[points.a1]\nkind = \"fixed\"\nposition = {_vector(ANCHORS[0])}\n"
            f"[points.a2]\nkind = \"fixed\"\nposition = {_vector(ANCHORS[1])}\n"
            + lines
            + f"[seabed]\nkind = \"horizontal\"\ndepth = {DEPTH!r}\n"
            f"[motion]\nkind = \"harmonic\"\namplitude = {_vector(motion['amplitude'])}\n"
            f"period = {motion['period']!r}\n"
            f"offset = {_vector(motion['offset'])}\nramp = {motion['ramp']!r}\n"
            f"[solver]\nintegrator = \"bdf2\"\ndt = {dt!r}\nduration = {duration!r}\n")


def case_duration(case):
    """Simulated time [s] of ``case``: its ramp and its periods."""
    motion = CASES[case]["motion"]
    return motion["ramp"] + CASES[case]["periods"] * motion["period"]


def write_inputs(folder):
    """Write crowfoot.dat and crowfoot-<case>.toml (the files' settings) into ``folder``; the .dat's
    path and {case: the TOML's path}."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    dat = folder / "crowfoot.dat"
    dat.write_text(moordyn_text())
    tomls = {case: folder / f"crowfoot-{case}.toml" for case in CASES}
    for case, path in tomls.items():
        path.write_text(toml_text(case))
    return dat, tomls


def scene_of(text):
    """A cablefem Scene from TOML text."""
    with tempfile.TemporaryDirectory(prefix="crowfoot-") as folder:
        path = Path(folder) / "crowfoot.toml"
        path.write_text(text)
        return load_scene(path)


# ----------------------------------------------------------------------------- statics
def moorpy_statics():
    """MoorPy's System of the crowfoot: junction position (3,) [m], tensions [N] at both ends of
    every line ({line: (end A, end B)}; A the junction for the upper line, the anchor for a leg)."""
    import moorpy

    ms = moorpy.System(depth=DEPTH, rho=WATER_DENSITY, g=GRAVITY)
    d, m = CHAIN["diameter"], CHAIN["mass"]
    ms.setLineType(dnommm=100.0, name="chain", d_vol=d, mass=m, EA=CHAIN["EA"],
                   w=(m - WATER_DENSITY * np.pi / 4 * d * d) * GRAVITY)
    ms.addPoint(1, np.array(FAIRLEAD))
    ms.addPoint(0, np.array(JUNCTION), m=CLUMP["mass"], v=CLUMP["volume"])
    ms.addPoint(1, np.array(ANCHORS[0]))
    ms.addPoint(1, np.array(ANCHORS[1]))
    ms.addLine(LENGTHS["upper"], "chain", pointA=2, pointB=1)
    ms.addLine(LENGTHS["leg1"], "chain", pointA=3, pointB=2)
    ms.addLine(LENGTHS["leg2"], "chain", pointA=4, pointB=2)
    ms.initialize()
    ms.solveEquilibrium(tol=1e-10, maxIter=2000)
    tensions = {name: (float(line.TA), float(line.TB)) for name, line in zip(LENGTHS, ms.lineList)}
    return np.array(ms.pointList[1].r, dtype=float), tensions


def cablefem_statics(scene):
    """cablefem's network statics (``cablefem.coupling``): junction position (3,) and tensions
    {line: (anchor end, fairlead end)} [N] (the lines' ends as MoorPy's A, B)."""
    result = solve_network(scene, lambda line: build_system(scene, line, dynamic=False),
                           tolerance=1e-10, max_iterations=100)
    tensions = {}
    for line, system, X in zip(scene.lines, result.systems, result.states):
        fairlead, anchor = end_forces(system, X)
        tensions[line.name] = (float(np.linalg.norm(anchor)), float(np.linalg.norm(fairlead)))
    return np.array(result.points["j"], dtype=float), tensions


def probe(moordyn, system):
    """MoorDyn's junction position (3,) [m], then the forces (3,) [N] of lines 2 and 3 on their
    anchors (their node 0's net force: tension, half a segment's weight and drag)."""
    junction = moordyn.GetPointPos(moordyn.GetPoint(system, 2))
    anchors = [moordyn.GetLineNodeForce(moordyn.GetLine(system, i), 0) for i in (2, 3)]
    return np.concatenate([junction, *anchors])


def static_check(scene, log=print):
    """The junction's static position and the tensions: cablefem's network statics against MoorPy
    (MoorDyn's initial condition is the first sample of its runs: ``run_case``)."""
    mp_junction, mp = moorpy_statics()
    start = time.perf_counter()
    cf_junction, cf = cablefem_statics(scene)
    cf_time = time.perf_counter() - start
    names = {"fairlead": ("upper", 1), "anchor1": ("leg1", 0), "anchor2": ("leg2", 0),
             "upper at the junction": ("upper", 0), "leg1 at the junction": ("leg1", 1),
             "leg2 at the junction": ("leg2", 1)}
    rows = [{"quantity": name, "moorpy_N": mp[line][end], "cablefem_N": cf[line][end],
             "cablefem_rel": (cf[line][end] - mp[line][end]) / mp[line][end]} for name, (line, end) in names.items()]
    out = {"rows": rows, "junction_moorpy_m": mp_junction, "junction_cablefem_m": cf_junction,
           "junction_cablefem_error_m": float(np.linalg.norm(cf_junction - mp_junction)), "cablefem_statics_s": cf_time}
    log(f"statics: junction cablefem - MoorPy {out['junction_cablefem_error_m']:.2e} m, tensions "
        f"{max(abs(row['cablefem_rel']) for row in rows):.1e}")
    return out


# ----------------------------------------------------------------------------- dynamics
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
    group = junction_steps(scene, integrators)
    initialised = time.perf_counter()
    names = [line.name for line in scene.lines]
    upper, leg1, leg2 = (integrators[names.index(n)] for n in ("upper", "leg1", "leg2"))
    k = group.integrators.index(leg1)
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
            "step_time_s": finished - initialised, "newton_iterations": group.newton_iterations,
            "halvings": group.halvings, "elements": {n: int(round(FILE_ELEMENTS[n] * factor)) for n in names}, "dt": dt,
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


def run(fast=False, log=print, cases=None):
    """The static check, both codes' ladders per case and their comparison; the results dict."""
    cases = list(cases or (("dynamic",) if fast else CASES))
    with tempfile.TemporaryDirectory(prefix="crowfoot-") as folder:
        _, tomls = write_inputs(folder)
        results = {"fast": fast, "coupling_dt_s": COUPLING_DT, "statics": static_check(load_scene(tomls["slow"]), log),
                   "cases": {}}
    initial_states = {}  # MoorDyn's initial conditions per segments, shared by the cases
    for case in cases:
        results["cases"][case] = run_case(case, fast, log, initial_states)
    return results


# ----------------------------------------------------------------------------- report
def _pct(x):
    return "–" if x is None else f"{100 * x:+.2f}"


def report(results):
    """The tables as markdown text."""
    s = results["statics"]
    out = ["## Statics (fairlead at rest): cablefem's network statics against MoorPy's System", "",
           "| tension | MoorPy [N] | cablefem [N] | cablefem − MoorPy [%] |", "|---|---|---|---|"]
    for row in s["rows"]:
        out.append(f"| {row['quantity']} | {row['moorpy_N']:.1f} | {row['cablefem_N']:.1f} | "
                   f"{100 * row['cablefem_rel']:+.6f} |")
    out += ["", f"Junction: MoorPy {np.round(np.asarray(s['junction_moorpy_m']), 4).tolist()} m; cablefem "
            f"{s['junction_cablefem_error_m']:.2e} m from it.", "",
            "MoorDyn's initial condition (each run's first sample) against MoorPy:", "",
            "| run | fairlead [%] | anchor 1 [%] | anchor 2 [%] | junction [m] |", "|---|---|---|---|---|"]
    mp = {row["quantity"]: row["moorpy_N"] for row in s["rows"]}
    seen = set()
    for case in results["cases"].values():
        for ic in case["initial_conditions"]:
            label = ic["label"].split(", dtM")[0]
            if label in seen:
                continue
            seen.add(label)
            cells = [_pct((ic[f"{q}_N"] - mp[q]) / mp[q]) for q in QUANTITIES]
            off = np.linalg.norm(np.asarray(ic["junction_m"]) - np.asarray(s["junction_moorpy_m"]))
            out.append(f"| {label} | " + " | ".join(cells) + f" | {off:.2e} |")
    header = ("| run | fairlead RMS / mean / peak [%] | anchor 1 RMS / mean / peak [%] | anchor 2 RMS / mean / peak [%] "
              "| junction RMS [m] (of its excursion [%]) | stepping [s per simulated s] |")
    rule = "|---|---|---|---|---|---|"
    for name, case in results["cases"].items():
        m = case["motion"]
        out += ["", f"## Case {name}: surge {m['amplitude'][0]:g} m, heave {m['amplitude'][2]:g} m, period "
                f"{m['period']:g} s; {case['duration_s']:g} s simulated, statistics from {case['statistics_from_s']:g} s", ""]
        out += ["cablefem − MoorDyn, finest runs (relative to MoorDyn's mean):", "", header, rule]
        out.append(_ladder_row(f"{case['references']['cablefem']} against {case['references']['moordyn']}",
                               case["comparison"], case["ladders"]["cablefem"][-1]["s_per_simulated_s"]))
        for code in ("moordyn", "cablefem"):
            out += ["", f"{code}: each run against its own finest run, and against the other code's finest run "
                    "(second row):", "", header, rule]
            for entry in case["ladders"][code]:
                out.append(_ladder_row(entry["label"], entry["against_own_reference"], entry["s_per_simulated_s"]))
                out.append(_ladder_row("  against the other", entry["against_other_reference"],
                                       entry["s_per_simulated_s"]))
        out += ["", "Cost at comparable accuracy: each code's cheapest run whose every tension is within the "
                "threshold (RMS of the mean) of ONE common reference, cablefem's finest run (the codes' finest "
                "runs agree to the first table's row):", "",
                "| threshold | MoorDyn run | its largest RMS [%] | s per simulated s | cablefem run | "
                "its largest RMS [%] | s per simulated s |", "|---|---|---|---|---|---|---|"]
        for threshold, picks in comparable_costs(case).items():
            cells = []
            for code in ("moordyn", "cablefem"):
                entry, error = picks[code]
                cells += (["none", "–", "–"] if entry is None else
                          [entry["label"], f"{100 * error:.2f}", f"{entry['s_per_simulated_s']:.3f}"])
            out.append(f"| {100 * threshold:g} % | " + " | ".join(cells) + " |")
        if "switches" in case:
            out += ["", f"Switches ({case['switches']['base']['label']}):", "", header.replace(
                " | stepping [s per simulated s] |", " |"), rule[:-4]]
            for switch, entry in case["switches"].items():
                out.append(_ladder_row(switch, entry["comparison"], None))
    return "\n".join(out)


def comparable_costs(case, thresholds=(0.02, 0.01, 0.005)):
    """{threshold: {code: (ladder entry, its largest tension RMS)}}: each code's cheapest run (by
    stepping time) within ``threshold`` of cablefem's finest run in every tension (None if none)."""
    def error(code, entry):
        c = entry["against_other_reference" if code == "moordyn" else "against_own_reference"]
        return max(c[q]["rms"] for q in QUANTITIES)

    out = {}
    for threshold in thresholds:
        out[threshold] = {}
        for code in ("moordyn", "cablefem"):
            fits = [(entry["s_per_simulated_s"], i) for i, entry in enumerate(case["ladders"][code])
                    if error(code, entry) <= threshold]
            entry = case["ladders"][code][min(fits)[1]] if fits else None
            out[threshold][code] = (entry, None if entry is None else error(code, entry))
    return out


def _ladder_row(label, c, seconds):
    cells = [f"{100 * c[q]['rms']:.2f} / {_pct(c[q]['mean'])} / {_pct(c[q]['peak'])}" for q in QUANTITIES]
    j = c["junction"]
    tail = "" if seconds is None else f" {seconds:.3f} |"
    return f"| {label} | " + " | ".join(cells) + f" | {j['rms_m']:.4f} ({100 * j['rms']:.2f}) |" + tail


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="coarse settings only (what the test asserts)")
    parser.add_argument("--out", default=str(HERE), help="folder for inputs/ and results.json")
    parser.add_argument("--series", help="also keep the finest runs' time series in this .npz")
    parser.add_argument("--report", metavar="JSON", help="print the tables of a results.json without running")
    args = parser.parse_args(argv)
    if args.report:
        print(report(json.loads(Path(args.report).read_text())))
        return
    out = Path(args.out)
    write_inputs(out / "inputs")
    start = time.perf_counter()
    results = run(fast=args.fast, log=lambda line: print(line, file=sys.stderr, flush=True))
    results["wall_time_s"] = time.perf_counter() - start
    print(report(results))
    series = {case: entry.pop("series") for case, entry in results["cases"].items()}
    (out / "results.json").write_text(json.dumps(jsonable(results), indent=1) + "\n")
    if args.series:
        np.savez_compressed(args.series, **{f"{case}_{code}_{k}": v for case, runs in series.items()
                                             for code, s in runs.items() for k, v in s.items()})


if __name__ == "__main__":
    main()
