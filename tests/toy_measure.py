"""What ``tests/test_catalog_extension.py`` asserts of the toy loads (``toy_loads``), measured in a
process where they were registered before cablefem built its kernels."""

import os

import numpy as np

UNIFORM_SCENE = """
name = "uniform"
[line_types.chain]
diameter = 0.3539
mass = 835.4
EA = 3.15e9
[[lines]]
anchor = [-300.0, 0.0, -150.0]
fairlead = [0.0, 0.0, 0.0]
segments = [{ type = "chain", length = 400.0, elements = 30 }]
order = 2
[seabed]
kind = "horizontal"
depth = 1000.0
[uniform_force]
force = [0.0, 0.0, -500.0]
[solver]
dt = 0.05
duration = 2.0
"""

#: a neutrally buoyant rope, taut (2 %), moved along itself: every point moves s / L of the fairlead
PLASTIC_SCENE = """
name = "plastic"
[line_types.rope]
diameter = 0.1
mass = 8.050331174710919
EA = 1e11
Cd_normal = 0.0
Ca_normal = 0.0
[[lines]]
anchor = [0.0, 0.0, -50.0]
fairlead = [102.0, 0.0, -50.0]
segments = [{ type = "rope", length = 100.0, elements = 20 }]
[seabed]
kind = "horizontal"
depth = 500.0
[plastic_spring]
stiffness = 1e6
yield_force = 50.0
[motion]
kind = "harmonic"
amplitude = [1.0, 0.0, 0.0]
period = 20.0
ramp = 5.0
[solver]
dt = 1.0
duration = 40.0
[output]
every = 1.0
"""


def measure(folder):
    """The toy loads' numbers (a dict for JSON); scenes and outputs go to ``folder``."""
    from cablefem.io import load_scene

    results = {}
    results.update(_uniform(load_scene(_write(folder, "uniform.toml", UNIFORM_SCENE))))
    results.update(_plastic(load_scene(_write(folder, "plastic.toml", PLASTIC_SCENE)), folder))
    return results


def _write(folder, name, text):
    path = os.path.join(folder, name)
    with open(path, "w") as handle:
        handle.write(text)
    return path


def _uniform(scene):
    """The uniform force is extra weight: statics against the catenary of w + 500 N/m; both faces;
    a run held still stays at the static state."""
    from cablefem.statics.catenary import elastic_catenary
    from cablefem.statics.scene import solve_scene_static
    from cablefem.compiled.evaluator import FusedEvaluator
    from cablefem.model.network import boundary_path
    from cablefem.fem.system import build_system
    from cablefem.statics.scene import start_states
    from cablefem.dynamics.bdf2 import BDF2

    reports, _, _ = solve_scene_static(scene)
    line = scene.lines[0]
    w = line.segments[0].type.submerged_weight(scene.environment.water_density, scene.environment.gravity)
    closed = elastic_catenary(300.0, 150.0, 400.0, line.segments[0].type.EA, w + 500.0, seabed=False)
    system = build_system(scene, line)
    (X0,), _ = start_states(scene, systems=[system])
    rng = np.random.default_rng(1)
    X, V, A = X0 + 0.1 * rng.standard_normal(X0.shape), rng.standard_normal(X0.shape), rng.standard_normal(X0.shape)
    fused = FusedEvaluator.for_system(system, system.props["mass"])
    rows, _ = fused.evaluate(X, V, A, 0.0, 0.0)
    R, _ = system.evaluate(system.state(X, V, A), False)
    M = system.fem.vector_mass(system.props["mass"], free_only=False)
    reference = R + (M @ A.ravel()).reshape(A.shape)
    integ = BDF2(system, X0, boundary_path(scene, line), dt=0.05)
    static = np.linalg.norm(integ.reactions()[0])
    moved = np.linalg.norm(integ.march(np.arange(1, 41) * 0.05)[-1, 0])
    slope, added = _energy_slope(scene, line, X0, rng)
    return {"uniform_in_catalog_loads": [type(load).__name__ for load in system.loads],
            "uniform_energy_slope_error": slope, "uniform_energy_added_slope_error": added,
            "uniform_static_error": abs(reports[0].fairlead_tension / closed.fairlead_tension - 1.0),
            "uniform_faces_difference": float(np.abs(rows - reference).max() / np.abs(reference).max()),
            "uniform_compiled_steps": integ.stepper().packer is not None,
            "uniform_held_still_change": abs(moved / static - 1.0)}


def _energy_slope(scene, line, X0, rng):
    """The line search's merit with the uniform force (statics' ``newton`` takes Armijo's test on
    ``LineSystem.energy`` with slope G . d): along a direction d at a state off equilibrium, the
    relative error of the energy's central difference against G . d, and of what the scene's
    ``[uniform_force]`` adds to it (the slopes with it less those without) against what it adds
    to G . d."""
    from dataclasses import replace

    from cablefem.fem.system import build_system

    others = {key: value for key, value in scene.load_settings.items() if key != "uniform_force"}
    systems = [build_system(scene, line, dynamic=False),
               build_system(replace(scene, load_settings=others), line, dynamic=False)]
    fixed = systems[0].fixed_rows
    X = X0 + 0.5 * rng.standard_normal(X0.shape)
    X[fixed] = X0[fixed]
    d = rng.standard_normal(X0.shape)
    d[fixed] = 0.0
    h = 1e-4
    slopes = [(system.energy(X + h * d) - system.energy(X - h * d)) / (2 * h) for system in systems]
    expected = [float(np.sum(system.residual(X) * d)) for system in systems]
    return (abs(slopes[0] / expected[0] - 1.0),
            abs((slopes[0] - slopes[1]) / (expected[0] - expected[1]) - 1.0))


def _plastic(scene, folder):
    """Plastic work over the second period against the closed form, with and without halved steps,
    compiled and in Python; the rest positions in a run's frames."""
    from cablefem.io.vtk import read_collection
    from cablefem.runs.run import run_scene

    runs = {}
    for label, iterations, compiled in (("plain", 12, True), ("halved", 2, True), ("python", 2, False)):
        runs[label] = _cycle(scene, iterations, compiled)
    summary = run_scene(scene, os.path.join(folder, "out"), duration=3.0)
    import meshio

    _, frames = read_collection(os.path.join(folder, "out", "plastic.pvd"))
    last = meshio.read(frames[-1]).point_data
    return {"plastic_closed_form": runs["plain"]["closed"],
            **{f"plastic_{label}_{key}": value for label, run in runs.items() for key, value in run.items()
               if key != "closed"},
            "plastic_frames_fields": sorted(last),
            "plastic_run_completed": summary["completed"]}


def _cycle(scene, iterations, compiled):
    """One run over two periods in steps of 1 s, full Newton with at most ``iterations`` iterations:
    plastic work of the second period, its closed form, rejections, the end state."""
    from cablefem.model.network import boundary_path
    from cablefem.fem.system import build_system
    from cablefem.statics.scene import start_states
    from cablefem.dynamics.bdf2 import BDF2

    line = scene.lines[0]
    system = build_system(scene, line)
    (X0,), _ = start_states(scene, systems=[system])
    integ = BDF2(system, X0, boundary_path(scene, line), dt=1.0, tolerance=1e-10, max_iterations=iterations,
                 newton="full")
    if not compiled:
        integ.stepper().packer = None
    fem = system.fem
    weights = fem.full.dx  # (nel, nq)
    k, yield_force = 1e6, 50.0
    rest = system.history["full"][0]["plastic"]["rest"].copy()
    work = 0.0
    for step in range(1, 41):  # the fairlead's extremes, t = 25 and 35 s, are step times
        integ.march([1.0 * step])
        now = system.history["full"][0]["plastic"]["rest"]
        if step > 20:  # the second period, t in [20, 40] s
            work += yield_force * float(np.sum(weights * np.linalg.norm(now - rest, axis=-1)))
        rest = now.copy()
    amplitude = fem.full.s / line.unstretched_length * 1.0  # each point moves s / L of the fairlead
    closed = float(np.sum(weights * 4.0 * yield_force * np.maximum(amplitude - yield_force / k, 0.0)))
    return {"work": work, "closed": closed, "rejected": integ.rejected, "X": integ.X.tolist(),
            "rest": rest.tolist()}
