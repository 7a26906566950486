"""cablefem's mooring networks (issue 18) against MoorDyn-C and MoorPy.

Run ``python -m validation.networks.run [--fast] [--out DIR]``; ``run(fast=True)`` returns the
numbers tests/test_validation_networks.py asserts on. The README has the cases, the choices and
the latest numbers.

1. Dynamics against MoorDyn-C: the semi-taut three-line system (a clump and a buoy per line) on a
   coupled platform in surge + heave + pitch + yaw, and two coupled platforms joined by a shared
   line; each network is ONE description (``systems``) written as a MoorDyn file and a TOML
   scene. Compared: each body's six-component mooring load, the fairlead tensions, the tensions
   of the lines at each clump and buoy and their positions.
2. Statics against MoorPy's System: the semi-taut system with the platform fixed (both ends of
   every string prescribed): fairlead and anchor tensions, clump and buoy positions, with a mesh
   convergence of cablefem's numbers.
"""

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # python validation/networks/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from cablefem.io import load_scene  # noqa: E402

from validation.moordyn.run import _json_ready, _version  # noqa: E402
from validation.networks import statics, systems  # noqa: E402
from validation.networks.dynamics import run_cablefem, run_moordyn, time_cablefem, without_end_inertia  # noqa: E402

HERE = Path(__file__).resolve().parent
COUPLING_DT = 0.01  # s between MoorDyn coupling calls and samples of both codes
CASES = {"semitaut": systems.semitaut, "shared": systems.shared}
#: per run kind: segment factor over the file's (25 m chain and polyester, 20 m top chain on the
#: semi-taut lines; 25 m chain, 20 m polyester on the shared case), MoorDyn's dtM and
#: initial-condition step [s], cablefem's dt [s], periods simulated after the one-period ramp
SETTINGS = {
    "full": {"segments": 2, "dtM": 2.5e-4, "ic_dtM": {"semitaut": 1e-3, "shared": 5e-4}, "dt": 0.005, "periods": 3},
    "coarse": {"segments": 1, "dtM": 5e-4, "ic_dtM": 2e-3, "dt": 0.02, "periods": 1},
    "fast": {"segments": 0.5, "dtM": 1e-3, "ic_dtM": 4e-3, "dt": 0.05, "periods": 1},
}
#: statics meshes (element order, elements over the file's): the fixed platform's convergence, the
#: free platform's (network statics: no vertex fitted to the touchdown, so slower to converge)
STATIC_MESHES = {"full": {"fixed": [(1, 1), (1, 2), (1, 4), (1, 8), (2, 1), (2, 2), (2, 4)],
                          "free": [(1, 2), (2, 1), (2, 2), (2, 4), (2, 8)]},
                 "fast": {"fixed": [(2, 1)], "free": [(2, 1)]}}
WINDOW_PERIODS = 2


def write_inputs(folder, factor=1.0):
    """The MoorDyn file and the TOML scene of each network into ``folder``; {case: (dat, toml)}."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    paths = {}
    for case, make in CASES.items():
        net = make(factor)
        dat, toml = folder / f"{case}.dat", folder / f"{case}.toml"
        dat.write_text(systems.moordyn_text(net))
        toml.write_text(systems.toml_text(net))
        paths[case] = (dat, toml)
    (folder / "semitaut-free.toml").write_text(systems.toml_text(systems.free_platform(systems.semitaut(factor))))
    return paths


def watch_list(net):
    """MoorDyn IDs to record: the body points (fairleads), the free points (joints), and per joint
    the (line ID, node) of the line ending there and of the line starting there."""
    ids = {p.name: i + 1 for i, p in enumerate(net.points)}
    fairleads = [p.name for p in net.points if p.body]
    joints = [p.name for p in net.points if p.kind == "free"]
    ends = []
    for joint in joints:
        into = [(i + 1, line.segments) for i, line in enumerate(net.lines) if line.b == joint]
        out = [(i + 1, 0) for i, line in enumerate(net.lines) if line.a == joint]
        ends += into + out
    fairlead_ends = [next((i + 1, line.segments if line.b == name else 0) for i, line in enumerate(net.lines)
                          if name in (line.a, line.b)) for name in fairleads]
    return {"fairleads": [ids[n] for n in fairleads], "fairlead_names": fairleads, "fairlead_ends": fairlead_ends,
            "joints": [ids[n] for n in joints], "joint_names": joints, "ends": ends}


def statistics(t, reference, other, t_from, scale=None):
    """cablefem (``other``) against MoorDyn (``reference``), series (n,) over t >= t_from: RMS and
    largest difference, difference of the means, peaks and troughs, relative to ``scale`` (default:
    MoorDyn's mean over the window)."""
    window = t >= t_from - 1e-9
    a, b = reference[window], other[window]
    scale = float(abs(a.mean())) if scale is None else float(scale)
    return {"reference_mean": float(a.mean()), "scale": scale,
            "rms": float(np.sqrt(np.mean((b - a) ** 2)) / scale), "max": float(np.max(np.abs(b - a)) / scale),
            "mean": float((b.mean() - a.mean()) / scale), "peak": float((b.max() - a.max()) / scale),
            "trough": float((b.min() - a.min()) / scale)}


def on_grid(t, series, grid):
    """Series (n, ...) at times t (n,) interpolated to times grid (m,)."""
    flat = series.reshape(len(t), -1)
    return np.column_stack([np.interp(grid, t, column) for column in flat.T]).reshape((len(grid),) + series.shape[1:])


def coarser(md, cf):
    """Both runs on the coarser of their two time grids: (t, md, cf) with the compared arrays."""
    t = cf["t"] if len(cf["t"]) <= len(md["t"]) else md["t"]
    keys = ("body", "fairleads", "joints", "ends")
    return (t, {k: on_grid(md["t"], md[k], t) for k in keys},
            dict({k: on_grid(cf["t"], cf[k], t) for k in keys}, fairlead_names=cf["fairlead_names"]))


def compare(case, md, cf, net, t_from):
    """Rows of ``statistics`` for each compared quantity: body force and moment components (relative
    to the magnitude of the body's mean force / moment), fairlead tensions, tensions beside each
    joint (relative to their means), joint positions (RMS difference in m, relative to the
    joint's motion range)."""
    t, md, cf = coarser(md, cf)
    rows = []
    watch = watch_list(net)
    for k, body in enumerate(net.bodies):
        window = t >= t_from - 1e-9
        force_scale = np.linalg.norm(md["body"][window, k, :3].mean(axis=0))
        moment_scale = max(np.linalg.norm(md["body"][window, k, 3:].mean(axis=0)),
                           np.abs(md["body"][window, k, 3:]).max())
        for c, label in enumerate(("Fx", "Fy", "Fz", "Mx", "My", "Mz")):
            scale = force_scale if c < 3 else moment_scale
            rows.append({"what": f"{body.name} {label}", "unit": "N" if c < 3 else "N m",
                         **statistics(t, md["body"][:, k, c], cf["body"][:, k, c], t_from, scale)})
    order = [cf["fairlead_names"].index(name) for name in watch["fairlead_names"]]
    for m, name in enumerate(watch["fairlead_names"]):
        rows.append({"what": f"{name} tension", "unit": "N",
                     **statistics(t, np.linalg.norm(md["fairleads"][:, m], axis=1),
                                  np.linalg.norm(cf["fairleads"][:, order[m]], axis=1), t_from)})
    labels = [f"{line} at {joint}" for joint in watch["joint_names"]
              for line in [l.name for l in net.lines if l.b == joint] + [l.name for l in net.lines if l.a == joint]]
    for m, label in enumerate(labels):
        rows.append({"what": f"{label} tension", "unit": "N", **statistics(t, md["ends"][:, m], cf["ends"][:, m], t_from)})
    for m, name in enumerate(watch["joint_names"]):
        a, b = md["joints"][:, m], cf["joints"][:, m]
        window = t >= t_from - 1e-9
        span = float(np.max(np.ptp(a[window], axis=0)))
        gap = np.linalg.norm(b - a, axis=1)[window]
        rows.append({"what": f"{name} position", "unit": "m", "reference_mean": a[window].mean(axis=0).tolist(),
                     "rms_m": float(np.sqrt(np.mean(gap**2))), "max_m": float(gap.max()), "range_m": span,
                     "rms": float(np.sqrt(np.mean(gap**2)) / span)})
    return rows


def run_case(case, folder, settings, log=print, switches=()):
    """Both codes on one network: the comparison rows, wall times and the series."""
    net = CASES[case](settings["segments"])
    dat, toml = folder / f"{case}-ref.dat", folder / f"{case}-ref.toml"
    dat.write_text(systems.moordyn_text(net))
    toml.write_text(systems.toml_text(net))
    scene = load_scene(toml)
    period = net.bodies[0].period
    duration = period * (1 + settings["periods"])
    t_from = duration - min(WINDOW_PERIODS, settings["periods"]) * period
    watch = watch_list(net)
    log(f"{case}: {duration:g} s; MoorDyn dtM {settings['dtM']:g} s, cablefem dt {settings['dt']:g} s, "
        f"segments x{settings['segments']}")
    ic_dtM = settings["ic_dtM"][case] if isinstance(settings["ic_dtM"], dict) else settings["ic_dtM"]
    md = run_moordyn(dat, scene, duration, COUPLING_DT, settings["dtM"], ic_dtM, watch)
    log(f"  MoorDyn {md['wall_time_s']:.1f} s (initial condition {md['init_time_s']:.1f} s)")
    cf = run_cablefem(toml, duration, COUPLING_DT, settings["dt"], watch["joint_names"], scene=scene)
    log(f"  cablefem {cf['wall_time_s']:.1f} s (statics {cf['init_time_s']:.1f} s)")
    cf_stepping, _ = time_cablefem(toml, duration, settings["dt"], scene=scene)
    log(f"  cablefem's steps alone, one march per string: {cf_stepping:.1f} s")
    rows = compare(case, md, cf, net, t_from)
    entry = {"title": net.title, "duration_s": duration, "window_s": [t_from, duration], "period_s": period,
             "settings": settings, "rows": rows,
             "elements": {line.name: line.segments for line in net.lines},
             "moordyn_wall_time_s": md["wall_time_s"], "moordyn_init_time_s": md["init_time_s"],
             "cablefem_wall_time_s": cf["wall_time_s"], "cablefem_init_time_s": cf["init_time_s"],
             "cablefem_newton_iterations": cf["newton_iterations"],
             "cablefem_stepping_time_s": cf_stepping,
             "moordyn_s_per_simulated_s": (md["wall_time_s"] - md["init_time_s"]) / duration,
             "cablefem_s_per_simulated_s": cf_stepping / duration}
    series = {"moordyn": md, "cablefem": cf}
    # MoorDyn's point force leaves out the inertia of the line end node (as validation/moordyn's RMS*)
    entry["switches"] = {"moordyn_end_node_inertia": {
        "rows": compare(case, without_end_inertia(md, scene, watch["fairlead_names"]), cf, net, t_from)}}
    if "moordyn_points_not_body" in switches:
        points_dat = folder / f"{case}-points.dat"
        points_dat.write_text(systems.moordyn_text(net, bodies_as_points=True))
        md_points = run_moordyn(points_dat, scene, duration, COUPLING_DT, settings["dtM"], ic_dtM, watch,
                                as_points=True)
        entry["switches"]["moordyn_points_not_body"] = {"rows": compare(case, md_points, cf, net, t_from),
                                                       "moordyn_wall_time_s": md_points["wall_time_s"]}
        series["moordyn_points_not_body"] = md_points
    return entry, series


def report(results):
    out = []
    for key, case, e in [(k, c, e) for k in ("dynamics", "coarse") for c, e in results.get(k, {}).items()]:
        out.append(f"{case} ({'reference' if key == 'dynamics' else 'coarse'} settings "
                   f"{e['settings']}): {e['title']}")
        out.append(f"  {'quantity':<34} {'MoorDyn mean':>14} {'mean':>8} {'peak':>8} {'trough':>8} {'RMS':>8} {'max':>8}")
        for r in e["rows"]:
            if r["unit"] == "m":
                out.append(f"  {r['what']:<34} RMS {r['rms_m']:.3f} m, max {r['max_m']:.3f} m, "
                           f"range {r['range_m']:.2f} m: RMS {100 * r['rms']:.2f} % of the range")
                continue
            out.append(f"  {r['what']:<34} {r['reference_mean']:14.4g} " + " ".join(
                f"{100 * r[k]:+7.2f}%" for k in ("mean", "peak", "trough")) + " " +
                " ".join(f"{100 * r[k]:7.2f}%" for k in ("rms", "max")))
        for name, sw in e["switches"].items():
            out.append(f"  switch {name}:")
            for r0, r in zip(e["rows"], sw["rows"]):
                if r["unit"] != "m":
                    out.append(f"    {r['what']:<34} RMS {100 * r0['rms']:.2f}% -> {100 * r['rms']:.2f}%")
        out.append(f"  time per simulated second: MoorDyn {e['moordyn_s_per_simulated_s']:.3f} s, cablefem "
                   f"{e['cablefem_s_per_simulated_s']:.3f} s (after MoorDyn's initial condition "
                   f"{e['moordyn_init_time_s']:.1f} s, cablefem's statics {e['cablefem_init_time_s']:.1f} s)")
    if "statics_fixed" in results:
        out.append("Statics, platform fixed, against MoorPy: largest relative end-tension difference over the 18 "
                   "line ends, largest clump/buoy distance")
        for m in results["statics_fixed"]["meshes"]:
            out.append(f"  P{m['order']} x{m['factor']}: {m['largest_relative']:.2e}, {m['largest_distance_m']:.2e} m")
    if "statics_free" in results:
        f = results["statics_free"]
        out.append(f"Statics, platform free, against MoorPy (offset {np.round(f['moorpy']['offset'], 4).tolist()} m): "
                   "offset difference, rotation matrix difference, largest relative tension difference, point distance")
        for m in f["meshes"]:
            out.append(f"  P{m['order']} x{m['factor']}: {m['offset_difference_m']:.2e} m "
                       f"({m['offset_relative']:.1e} of the offset), {m['rotation_difference']:.1e}, "
                       f"{m['largest_relative']:.2e}, {m['largest_distance_m']:.2e} m ({m['wall_time_s']:.0f} s)")
    return "\n".join(out)


def run(fast=False, out_dir=None, log=print, cases=None, parts=("dynamics", "statics")):
    """The study (``fast``: the shared case at half the file's segments and one period after the
    ramp, statics at the file's mesh in P2: what the tests assert); returns (results, series)."""
    import tempfile

    out_dir = Path(out_dir or HERE)
    paths = write_inputs(out_dir / "inputs")
    cases = cases or (("shared",) if fast else tuple(CASES))
    kind = "fast" if fast else "full"
    results = {"fast": fast, "coupling_dt_s": COUPLING_DT, "moordyn_version": _version("moordyn"),
               "moorpy_version": _version("moorpy"), "dynamics": {}}
    series = {}
    start = time.perf_counter()
    if "dynamics" in parts:
        # full: the reference settings, then the file's segments with twice the steps ("coarse"), which
        # also runs the switch (MoorDyn's fairleads as coupled points instead of its body's points)
        runs = [("dynamics", kind, ())] + ([] if fast else [("coarse", "coarse", ("moordyn_points_not_body",))])
        with tempfile.TemporaryDirectory(prefix="networks-") as folder:
            for key, setting, switches in runs:
                results.setdefault(key, {})
                for case in cases:
                    results[key][case], series[(key, case)] = run_case(case, Path(folder), SETTINGS[setting], log,
                                                                        switches=switches)
    if "statics" in parts:
        net = systems.semitaut()
        log("statics, platform fixed: cablefem against MoorPy")
        results["statics_fixed"] = statics.compare_statics(net, load_scene(paths["semitaut"][1]),
                                                           meshes=STATIC_MESHES[kind]["fixed"], log=log)
        free = systems.free_platform(net)
        free_toml = out_dir / "inputs" / "semitaut-free.toml"
        log("statics, platform free under a steady load: cablefem against MoorPy")
        results["statics_free"] = statics.compare_free(free, load_scene(free_toml),
                                                       meshes=STATIC_MESHES[kind]["free"], log=log)
    results["wall_time_s"] = time.perf_counter() - start
    return results, series


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="coarse settings, one period: what the tests assert")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for inputs/ and results.json")
    parser.add_argument("--cases", nargs="*", help="dynamics cases (default: all; --fast: shared)")
    parser.add_argument("--parts", nargs="*", default=["dynamics", "statics"])
    args = parser.parse_args(argv)
    results, _ = run(fast=args.fast, out_dir=args.out, cases=args.cases, parts=args.parts)
    print(report(results))
    (args.out / "results.json").write_text(json.dumps(_json_ready(results), indent=1))


if __name__ == "__main__":
    main()
