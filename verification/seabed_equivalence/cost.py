"""(b) and (c) of verification/seabed_equivalence: the CPU time of the static solve over the
planar mesh, and of the flume flat dynamic run over triangulated flat floors, against the plane's."""

import statistics
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from cablefem.geometry import Horizontal, TriangulatedSurface, simplify
from cablefem.geometry.planes import _grid_triangles


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
    from cablefem.statics.solve import solve_static
    from cablefem.fem.system import LineSystem

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
    take the per-step Python path (``cablefem.compiled.steps`` projects inside its compiled loop)."""
    from cablefem.runs.run import step_times
    from cablefem.model.builtin import flume_scene
    from cablefem.study import start_line

    scene = replace(flume_scene(kind, "dynamic", duration=duration, dt=dt), seabed=seabed)
    integrator = start_line(scene, integrator="bdf2", newton="modified" if modified_newton else "full")
    spent = [0.0, 0]
    if count_projection:  # an instance attribute shadows the method for this run only
        integrator.stepper().packer = None
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
        integrator.march(step_times(0.0, duration, dt))
        cpu, wall = _since(start)
    finally:
        if count_projection:
            del seabed.project
    return cpu, wall, integrator, spent[0], spent[1]


def _run_scene_cpu(seabed, duration):
    """CPU s of ``cablefem.runs.run.run_scene`` on the flume flat dynamic case over seabed, outputs
    (VTK frames every 0.1 s, tensions.csv, summary.json) into a scratch folder."""
    from cablefem.runs.run import run_scene
    from cablefem.model.builtin import flume_scene

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
    from cablefem.model.builtin import flume_seabed

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
