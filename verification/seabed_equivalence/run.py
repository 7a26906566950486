"""One plane, five descriptions: the same static answer, and what the general projection costs.

desire2023 Sec. 2.2.2 (point-to-plane against vertex-normal projection), Sec. 5
and Table 6 (the general projection made a 120 s dynamic run 20 % slower on
the same flat seabed); issue 3's targets. Run
``python -m verification.seabed_equivalence.run [--fast] [--out DIR]``.

(a) equality: a 10 deg slope rising towards azimuth 60 deg (more across the
    line than along it, so the line rests on it sagging sideways) given as a
    plane, an STL mesh, a MoorDyn-C grid, a MoorDyn-F grid, scattered x y z
    soundings and a MoorDyn file with a SeafloorFile; the Table 5 chain
    anchored on it. Every scene is loaded as ``cablefem static`` loads it,
    with ``[seabed] simplify`` on (the planar file becomes the plane) and off
    (the grid's bilinear or the mesh's vertex-normal projection is used as
    is), and solved; fairlead and anchor forces and node positions are
    compared with the plane's (solved on the same mesh: statics fits a vertex
    to the touchdown on planes only).
(b) static cost: the solve over the planar mesh with detection on (it is the
    plane; plus the detection itself) and off (the general projection), in
    CPU time relative to the plane's, interleaved repeats.
(c) dynamic cost: the desire2023 flume flat case (Table 5 chain, 5 m / 6 s
    surge, friction, drag, added mass, BDF2 at dt = 0.01 s) over its 100 m
    floor as ``Horizontal`` and as triangulated horizontal surfaces taken as
    is (simplify off): the time steps with modified (the default) and full
    Newton, and the whole ``run_scene``, in CPU time relative to the
    horizontal's; and the cost of one ``project`` call inside the run on the
    flat mesh and on the non-planar steep flume step (the same code path, so
    the flat mesh stands for a non-planar one).
"""

import argparse
import json
import math
import statistics
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from cablefem.geometry import DepthGrid, Horizontal, Plane, TriangulatedSurface, simplify
from cablefem.geometry.planes import _grid_triangles

HERE = Path(__file__).resolve().parent

#: the plane: rises at SLOPE_DEG towards AZIMUTH_DEG (from +x), through the anchor
SLOPE_DEG, AZIMUTH_DEG = 10.0, 60.0
ANCHOR = (-595.0, 0.0, -150.0)
#: plan extent of the files [m]: the line and its downhill sag lie well inside
EXTENT = ((-800.0, 200.0), (-400.0, 400.0))
ELEMENTS = 40
#: Newton's relative residual for every solve of (a) (the scenes' default is 1e-8)
TOLERANCE = 1e-10

SCENE = """\
name = "{name}"

[line_types.chain]    # desire2023 Table 5 (cablefem.scenes.table5_chain)
diameter = 0.3539
mass = 835.4
EA = 3.15e9
damping = 0.001
Cd_normal = 2.5
Cd_tangential = 0.5
Ca_normal = 3.8
Ca_tangential = 0.0

[[lines]]
name = "line1"
anchor = [{ax!r}, {ay!r}, {az!r}]
fairlead = [0.0, 0.0, 0.0]
segments = [{{ type = "chain", length = 635.0, elements = {elements} }}]

[seabed]
{seabed}
stiffness = 3.0e5

[solver]
tolerance = {tolerance!r}
"""

MOORDYN = """\
--------------------- MoorDyn Input File ------------------------------------
The Table 5 chain on a 10 deg oblique slope given as a MoorDyn-C bathymetry grid
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam     Mass/m   EA       BA/-zeta   EI    Cd    Ca    CdAx                 CaAx
(name)     (m)      (kg/m)   (N)      (N-s/-)    (-)   (-)   (-)   (-)                  (-)
chain      0.3539   835.4    3.15e9   3.15e6     0.0   2.5   3.8   0.15915494309189535  0.0
---------------------- POINTS --------------------------------
ID     Attachment  X        Y     Z        M      V        CdA   CA
(-)    (-)         (m)      (m)   (m)      (kg)   (m^3)    (m^2) (-)
1      Fixed       {ax!r}   {ay!r}   {az!r}   0      0        0     0
2      Coupled     0.0      0.0   0.0      0      0        0     0
---------------------- LINES --------------------------------------
ID    LineType   AttachA  AttachB  UnstrLen  NumSegs  Outputs
(-)   (-)        (-)      (-)      (m)       (-)      (-)
1     chain      1        2        635.0     {elements}       -
---------------------- OPTIONS -----------------------------------------
{grid}   SeafloorFile
1025.0               WtrDnsty
9.81                 g
3.0e5                kBot
---------------------------------------------------------------------------
"""


def oblique_plane():
    """The reference seabed: a Plane through ANCHOR rising SLOPE_DEG towards AZIMUTH_DEG."""
    return Plane.from_slope(ANCHOR, math.radians(SLOPE_DEG), math.radians(AZIMUTH_DEG))


def _on_plane(plane, xy):
    """Points (n, 3) [m] of plane above xy (n, 2)."""
    return np.column_stack([xy, plane.elevation(xy)])


def write_seabed_files(folder, seed=3):
    """Write the plane as an STL mesh, MoorDyn-C and -F grids, x y z soundings and a MoorDyn
    input file with SeafloorFile into folder; {label: file name}."""
    import meshio

    from cablefem.geometry.readers import moordyn_c, moordyn_f

    folder = Path(folder)
    plane = oblique_plane()
    (x0, x1), (y0, y1) = EXTENT
    rng = np.random.default_rng(seed)
    # grid: 100 m cells
    x, y = np.linspace(x0, x1, 11), np.linspace(y0, y1, 9)
    gx, gy = np.meshgrid(x, y)
    grid = DepthGrid(x, y, plane.elevation(np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape))
    moordyn_c.write(folder / "grid_c.txt", grid)
    moordyn_f.write(folder / "grid_f.txt", grid)
    # mesh: the same nodes, interior ones jittered by up to 30 m, ASCII STL (full precision)
    xy = np.column_stack([gx.ravel(), gy.ravel()])
    inner = (xy[:, 0] > x0) & (xy[:, 0] < x1) & (xy[:, 1] > y0) & (xy[:, 1] < y1)
    xy[inner] += rng.uniform(-30.0, 30.0, (int(inner.sum()), 2))
    mesh = meshio.Mesh(_on_plane(plane, xy), [("triangle", _grid_triangles(len(x), len(y)))])
    mesh.write(folder / "slope.stl", binary=False)
    # soundings: 400 scattered points and the corners, Delaunay-triangulated by the reader
    xy = np.vstack([[[x0, y0], [x1, y0], [x0, y1], [x1, y1]],
                    np.column_stack([rng.uniform(x0, x1, 400), rng.uniform(y0, y1, 400)])])
    np.savetxt(folder / "soundings.xyz", _on_plane(plane, xy), fmt="%.17g",
               header="x y z [m]: a 10 deg plane, scattered")
    ax, ay, az = ANCHOR
    (folder / "mooring.dat").write_text(MOORDYN.format(ax=ax, ay=ay, az=az, elements=ELEMENTS,
                                                       grid="grid_c.txt"))
    return {"mesh (stl)": "slope.stl", "grid (MoorDyn-C)": "grid_c.txt",
            "grid (MoorDyn-F)": "grid_f.txt", "points (xyz)": "soundings.xyz",
            "MoorDyn SeafloorFile": "mooring.dat"}


def write_scenes(folder):
    """Write the seabed files and one scene per description and simplify setting into folder;
    [(label, simplify, scene file name)], the plane first."""
    folder = Path(folder)
    files = write_seabed_files(folder)
    ax, ay, az = ANCHOR

    def scene(name, seabed):
        text = SCENE.format(name=name, ax=ax, ay=ay, az=az, elements=ELEMENTS, seabed=seabed,
                            tolerance=TOLERANCE)
        (folder / f"{name}.toml").write_text(text)
        return f"{name}.toml"

    plane = f'kind = "plane"\npoint = [{ax!r}, {ay!r}, {az!r}]\nslope_deg = {SLOPE_DEG!r}\n' \
            f'azimuth_deg = {AZIMUTH_DEG!r}'
    scenes = [("plane", True, scene("plane", plane))]
    kinds = {"slope.stl": "mesh", "grid_c.txt": "grid", "grid_f.txt": "grid", "soundings.xyz": "points"}
    for label, file in files.items():
        stem = Path(file).stem
        if file == "mooring.dat":
            scenes.append((label, True, file))
            wrapper = f'[moordyn]\nfile = "{file}"\n[seabed]\nsimplify = false\n[solver]\n' \
                      f'tolerance = {TOLERANCE!r}\n'
            (folder / "mooring_general.toml").write_text(wrapper)
            scenes.append((label, False, "mooring_general.toml"))
            continue
        for on in (True, False):
            seabed = f'kind = "{kinds[file]}"\nfile = "{file}"\nsimplify = {str(on).lower()}'
            scenes.append((label, on, scene(f"{stem}_{'simplified' if on else 'general'}", seabed)))
    return scenes


def solve(scene, fit_touchdown=None):
    """Static solve of a loaded scene's first line at TOLERANCE, as ``cablefem static`` does:
    (LineReport, StaticResult). ``fit_touchdown`` False solves a plane on the mesh as given
    (the statics' touchdown fitting, where it exists, applies to planes only)."""
    from cablefem.cli import solve_scene_static

    settings = {"tolerance": TOLERANCE}
    if fit_touchdown is not None and hasattr(scene.solver, "fit_touchdown"):
        settings["fit_touchdown"] = fit_touchdown
    reports, _, results = solve_scene_static(replace(scene, solver=replace(scene.solver, **settings)))
    return reports[0], results[0]


def _errors(report, reference):
    """Relative differences of a LineReport from the reference's: forces by the reference's
    magnitude, nodes by the line's length (NaN when the meshes differ)."""
    nodes = (float(np.max(np.abs(report.nodes - reference.nodes)) / 635.0)
             if report.nodes.shape == reference.nodes.shape else float("nan"))
    return {"fairlead_force_error": float(np.max(np.abs(report.fairlead_force - reference.fairlead_force))
                                          / np.linalg.norm(reference.fairlead_force)),
            "anchor_force_error": float(np.max(np.abs(report.anchor_force - reference.anchor_force))
                                        / np.linalg.norm(reference.anchor_force)),
            "node_error": nodes}


def equivalence(folder):
    """(a): every description of the plane, simplify on and off, against the plane: list of dicts.

    A simplified scene is compared with the plane solved as ``cablefem static`` solves it; a
    general one (simplify off) with the plane solved on the same mesh, without the touchdown
    fitting that statics gives planes only (its effect is the row "plane, fitted").
    """
    from cablefem.io import load_scene

    rows, references = [], {}
    for label, on, file in write_scenes(folder):
        scene = load_scene(Path(folder) / file)
        rep, res = solve(scene)
        if not references:
            references[True] = rep
            references[False] = solve(scene, fit_touchdown=False)[0]
            fitted = _errors(rep, references[False])
            fitted["node_error"] = float("nan")  # the fitted mesh moves a vertex to the touchdown
            rows.append({"seabed": "plane, fitted", "simplify": True, "model": "plane",
                         "model_class": "Plane", "compared_with": "plane, unfitted",
                         **fitted, "fairlead_tension": rep.fairlead_tension,
                         "touchdown_s": rep.touchdown_s, "newton_iterations": res.iterations,
                         "strategy": res.strategy, "note": "statics' touchdown fitting on the plane"})
        seabed_note = next(n for n in scene.notes if n.startswith("seabed:"))
        rows.append({
            "seabed": label, "simplify": on, "model": scene.seabed.kind,
            "model_class": type(scene.seabed).__name__,
            "compared_with": "plane" if on else "plane, unfitted",
            **_errors(rep, references[on]),
            "fairlead_tension": rep.fairlead_tension, "touchdown_s": rep.touchdown_s,
            "newton_iterations": res.iterations, "strategy": res.strategy, "note": seabed_note})
    return rows


# -- timing ------------------------------------------------------------------

def _clock():
    return time.process_time(), time.perf_counter()


def _since(start):
    cpu, wall = _clock()
    return cpu - start[0], wall - start[1]


def _spread(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values),
            "values": list(values)}


def static_cost(folder, repeats=5):
    """(b): CPU seconds of the static solve over the planar mesh, detected and not, and the plane."""
    from cablefem.io import load_scene
    from cablefem.statics import solve_static
    from cablefem.system import LineSystem

    plane_scene = load_scene(Path(folder) / "plane.toml")
    general_scene = load_scene(Path(folder) / "slope_general.toml")
    mesh = general_scene.seabed
    detected = simplify(mesh)
    grid_scene = load_scene(Path(folder) / "grid_c_general.toml")
    line = plane_scene.lines[0]

    def system(seabed):
        return LineSystem(line, seabed, plane_scene.contact, plane_scene.environment)

    cases = {"plane": system(plane_scene.seabed), "mesh, detected": system(detected),
             "mesh, general": system(mesh), "grid, general": system(grid_scene.seabed)}
    times = {name: [] for name in cases}
    iterations = {}
    detection = []
    for _ in range(repeats):
        for name, sys_ in cases.items():
            if hasattr(sys_.seabed, "reset"):
                sys_.seabed.reset()  # each solve starts cold, as a new `cablefem static` does
            start = _clock()
            result = solve_static(sys_, tolerance=1e-8)
            times[name].append(_since(start)[0])
            iterations[name] = result.iterations
        start = _clock()
        for _ in range(20):
            simplify(mesh)
        detection.append(_since(start)[0] / 20)
    plane = times["plane"]
    rows = []
    for name in cases:
        ratios = [t / p for t, p in zip(times[name], plane)]
        per_iteration = [r * iterations["plane"] / iterations[name] for r in ratios]
        rows.append({"case": name, "newton_iterations": iterations[name],
                     "cpu_s": _spread(times[name]), "ratio": _spread(ratios),
                     "ratio_per_iteration": _spread(per_iteration)})
    with_detection = [(t + d) / p for t, d, p in zip(times["mesh, detected"], detection, plane)]
    rows.append({"case": "mesh, detected + detection", "newton_iterations": iterations["mesh, detected"],
                 "cpu_s": _spread([t + d for t, d in zip(times["mesh, detected"], detection)]),
                 "ratio": _spread(with_detection), "ratio_per_iteration": _spread(with_detection)})
    return {"rows": rows, "detection_cpu_s": _spread(detection), "mesh_triangles": len(mesh.triangles)}


def flat_meshes(fast=False):
    """Triangulated stand-ins of the flume's flat 100 m floor (x [-700, 100], y [-75, 75] m),
    taken as is: {label: TriangulatedSurface}."""
    from scipy.spatial import Delaunay

    def structured(spacing):
        x = np.arange(-700.0, 100.0 + spacing / 2, spacing)
        y = np.arange(-75.0, 75.0 + spacing / 2, spacing)
        gx, gy = np.meshgrid(x, y)
        vertices = np.column_stack([gx.ravel(), gy.ravel(), np.full(gx.size, -100.0)])
        return TriangulatedSurface(vertices, _grid_triangles(len(x), len(y)))

    meshes = {"mesh 25 m (flume step spacing)": structured(25.0)}
    if not fast:
        meshes["mesh 5 m"] = structured(5.0)
        rng = np.random.default_rng(7)
        corners = [[-700.0, -75.0], [100.0, -75.0], [-700.0, 75.0], [100.0, 75.0]]
        xy = np.vstack([corners, np.column_stack([rng.uniform(-700, 100, 600), rng.uniform(-75, 75, 600)])])
        meshes["scattered 604 soundings"] = TriangulatedSurface(
            np.column_stack([xy, np.full(len(xy), -100.0)]), Delaunay(xy).simplices)
    return meshes


def dynamic_run(seabed, duration, dt=0.01, kind="flat", count_projection=False, modified_newton=True):
    """The flume ``kind`` dynamic case over seabed, stepped as ``run_scene`` steps it (BDF2,
    fixed dt marched in compiled runs of steps, modified Newton unless ``modified_newton`` is
    False): (CPU s, wall s of the time steps, integrator, CPU s spent in seabed.project and its
    number of calls when ``count_projection``). Counting needs the calls in Python: those runs
    take the per-step Python path (``cablefem.march`` projects inside its compiled loop)."""
    from cablefem.run import StepControl
    from cablefem.scenes import flume_scene
    from cablefem.study import start_line

    scene = replace(flume_scene(kind, "dynamic", duration=duration, dt=dt), seabed=seabed)
    integrator = start_line(scene, integrator="bdf2", newton="modified" if modified_newton else "full")
    spent = [0.0, 0]
    if count_projection:  # an instance attribute shadows the method for this run only
        integrator.marcher = None
        project = seabed.project

        def counted(*args, **kwargs):
            start = time.process_time()
            result = project(*args, **kwargs)
            spent[0] += time.process_time() - start
            spent[1] += 1
            return result
        seabed.project = counted
    try:
        start = _clock()
        integrator.march(StepControl(scene.solver, dt).times(0.0, duration))
        cpu, wall = _since(start)
    finally:
        if count_projection:
            del seabed.project
    return cpu, wall, integrator, spent[0], spent[1]


def _run_scene_cpu(seabed, duration):
    """CPU s of ``cablefem.run.run_scene`` on the flume flat dynamic case over seabed, outputs
    (VTK frames every 0.1 s, tensions.csv, summary.json) into a scratch folder."""
    from cablefem.run import run_scene
    from cablefem.scenes import flume_scene

    scene = replace(flume_scene("flat", "dynamic", duration=duration), seabed=seabed)
    with tempfile.TemporaryDirectory() as out:
        start = _clock()
        run_scene(scene, out_dir=out, progress=False)
        return _since(start)[0]


def dynamic_cost(duration=4.0, repeats=7, fast=False, scene_duration=20.0):
    """(c): CPU time of the flume flat dynamic run over triangulated flat floors taken as is,
    relative to ``Horizontal``; runs interleaved, the order alternating between repeats.

    The ratio of the fastest runs is the least disturbed by other work on the machine; the
    median [min, max] of the ratios of the runs of one repeat shows the spread. Also: the
    same through ``run_scene`` (outputs written), and the CPU time per ``project`` call on
    the flat mesh and on the non-planar steep flume step (the same code, so the flat mesh
    stands for a non-planar one).
    """
    from cablefem.scenes import flume_seabed

    meshes = flat_meshes(fast)
    labels = ["horizontal", *meshes]
    rows = []
    for modified in (True, False):
        times = {label: [] for label in labels}
        walls = {label: [] for label in labels}
        differences, iterations = {}, {}
        for repeat in range(repeats):
            finals = {}
            for label in (labels if repeat % 2 == 0 else labels[::-1]):
                seabed = Horizontal(100.0) if label == "horizontal" else meshes[label]
                if label != "horizontal":
                    seabed.reset()
                cpu, wall, integrator, _, _ = dynamic_run(seabed, duration, modified_newton=modified)
                times[label].append(cpu)
                walls[label].append(wall)
                iterations[label] = integrator.newton_iterations
                finals[label] = integrator.X
            for label in meshes:
                differences[label] = float(np.max(np.abs(finals[label] - finals["horizontal"])))
        base, base_wall = times["horizontal"], walls["horizontal"]
        for label in labels:
            rows.append({"newton": "modified" if modified else "full", "seabed": label,
                         "triangles": len(meshes[label].triangles) if label in meshes else None,
                         "newton_iterations": iterations[label], "cpu_s": _spread(times[label]),
                         "ratio_of_fastest": min(times[label]) / min(base),
                         "ratio": _spread([t / b for t, b in zip(times[label], base)]),
                         "wall_ratio": _spread([t / b for t, b in zip(walls[label], base_wall)]),
                         "final_position_difference_m": differences.get(label, 0.0)})
    flat = next(iter(meshes.values()))
    scene_runs = {"horizontal": [], "mesh": []}
    for repeat in range(1 if fast else 3):
        for label in (("horizontal", "mesh") if repeat % 2 == 0 else ("mesh", "horizontal")):
            seabed = Horizontal(100.0) if label == "horizontal" else flat
            if label == "mesh":
                seabed.reset()
            scene_runs[label].append(_run_scene_cpu(seabed, scene_duration))
    per_call = {}
    for label, kind, seabed in (("horizontal", "flat", Horizontal(100.0)), ("flat mesh", "flat", flat),
                                ("steep step (non-planar)", "steep", flume_seabed("steep"))):
        if hasattr(seabed, "reset"):
            seabed.reset()
        cpu, _, _, spent, calls = dynamic_run(seabed, duration, kind=kind, count_projection=True)
        # a plane is projected inside the compiled step kernel: no calls to count there
        per_call[label] = {"us_per_call": 1e6 * spent / calls if calls else None, "calls": calls,
                           "share_of_run": spent / cpu}
    scene_ratios = [m / h for m, h in zip(scene_runs["mesh"], scene_runs["horizontal"])]
    return {"duration_s": duration, "dt": 0.01, "repeats": repeats, "rows": rows,
            "run_scene": {"duration_s": scene_duration,
                          "cpu_s": {k: _spread(v) for k, v in scene_runs.items()},
                          "ratio_of_fastest": min(scene_runs["mesh"]) / min(scene_runs["horizontal"]),
                          "ratio": _spread(scene_ratios)},
            "projection_per_call": per_call}


# -- report ------------------------------------------------------------------

def _fmt(spread, digits=3):
    return f"{spread['median']:.{digits}f} [{spread['min']:.{digits}f}, {spread['max']:.{digits}f}]"


def print_tables(results):
    """The three tables of results (a dict as ``run`` returns it)."""
    print("(a) the same plane, five descriptions: errors relative to the plane's answer "
          f"(tolerance {TOLERANCE:g})")
    print(f"{'seabed':<22} {'simplify':>8} {'model':>10} {'against':>16} {'|dF_fair|/|F|':>14} "
          f"{'|dF_anch|/|F|':>14} {'|dX|/L':>10} {'iters':>6}")
    for row in results["equivalence"]:
        print(f"{row['seabed']:<22} {str(row['simplify']).lower():>8} {row['model']:>10} "
              f"{row['compared_with']:>16} {row['fairlead_force_error']:14.2e} "
              f"{row['anchor_force_error']:14.2e} {row['node_error']:10.2e} {row['newton_iterations']:6d}")
    static = results["static_cost"]
    print(f"\n(b) static solve, CPU time relative to the plane's; median [min, max] of "
          f"{len(static['rows'][0]['cpu_s']['values'])} interleaved repeats; mesh of "
          f"{static['mesh_triangles']} triangles")
    print(f"{'case':<28} {'iters':>6} {'CPU s':>8} {'ratio':>24} {'per iteration':>24}")
    for row in static["rows"]:
        print(f"{row['case']:<28} {row['newton_iterations']:6d} {row['cpu_s']['median']:8.4f} "
              f"{_fmt(row['ratio']):>24} {_fmt(row['ratio_per_iteration']):>24}")
    print(f"detection (simplify) alone: {1e3 * static['detection_cpu_s']['median']:.3f} ms")
    dynamic = results["dynamic_cost"]
    print(f"\n(c) flume flat dynamic run, {dynamic['duration_s']:g} s at dt = {dynamic['dt']:g} s, "
          f"time steps only, CPU time; {dynamic['repeats']} interleaved repeats: ratio of the fastest "
          "runs, and median [min, max] of the ratios within a repeat")
    print(f"{'Newton':<9} {'seabed':<32} {'triangles':>9} {'iters':>6} {'CPU s':>7} {'fastest':>8} "
          f"{'CPU ratio':>24} {'wall ratio':>24} {'|dX| end [m]':>12}")
    for row in dynamic["rows"]:
        print(f"{row['newton']:<9} {row['seabed']:<32} {row['triangles'] or '-':>9} "
              f"{row['newton_iterations']:6d} "
              f"{row['cpu_s']['median']:7.3f} {row['ratio_of_fastest']:8.3f} {_fmt(row['ratio']):>24} "
              f"{_fmt(row['wall_ratio']):>24} {row['final_position_difference_m']:12.2e}")
    scene = dynamic["run_scene"]
    print(f"run_scene, {scene['duration_s']:g} s (static start, VTK frames, tensions.csv): "
          f"mesh / horizontal CPU {scene['ratio_of_fastest']:.3f} (fastest), {_fmt(scene['ratio'])}")
    print("seabed.project inside the run:", ", ".join(
        f"{label} {v['us_per_call']:.0f} us/call ({100 * v['share_of_run']:.0f} % of the run)"
        if v["calls"] else f"{label} inside the step kernel"
        for label, v in dynamic["projection_per_call"].items()))


def run(fast=False, folder=None):
    """All three parts; ``fast`` shortens the timings (for tests and CI). A dict of results."""
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(folder or scratch)
        results = {"equivalence": equivalence(folder)}
        results["static_cost"] = static_cost(folder, repeats=2 if fast else 7)
    results["dynamic_cost"] = dynamic_cost(duration=2.0 if fast else 4.0, repeats=1 if fast else 7,
                                           fast=fast, scene_duration=2.0 if fast else 30.0)
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="short timings (seconds, not minutes)")
    parser.add_argument("--out", type=Path, default=HERE, help="folder for results.json")
    args = parser.parse_args(argv)
    results = run(fast=args.fast)
    print_tables(results)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "results.json").write_text(json.dumps({"fast": args.fast, **results}, indent=1))


if __name__ == "__main__":
    main()
