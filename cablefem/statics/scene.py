"""The statics of a whole scene: every line's equilibrium and its network's coupling unknowns, as
``cablefem static`` reports them and as a run starts from them.

One function solves both (``static_lines``): ``cablefem static`` solves the scene as written, a run
solves it with the prescribed ends where their paths put them at t = 0 (the same problem when the
motion's displacement is zero there) and starts from that state on that mesh. A line alone is
solved on its mesh as given or, with ``[solver] fit_touchdown``, on a mesh fitted to its touchdown
(``cablefem.statics.touchdown``); a line in soil along its pretension path
(``cablefem.statics.pretension``); the strings that meet at junctions or free bodies together
(``cablefem.statics.network``).
"""

import copy
from dataclasses import replace

from cablefem.fem.system import build_system
from cablefem.model.network import anchor_path, boundary_path, check_steppable, coupling


#: ``cablefem static`` solves a single line of at most this many nodes on the numpy path: loading
#: numba's compiled kernels costs a process 0.25-0.3 s of CPU (its target and the kernels' cache),
#: and the numpy path ~9 us more per node and Newton iteration than the compiled one, so it wins
#: below ~3e4 node-iterations (measured, the whole solve in a fresh process: the default scene,
#: 41 nodes, 11 iterations, 0.16-0.31 s against 0.41-0.44 s; a 21-node line settling in 634
#: iterations 0.74 s against 0.88 s). Several lines add their iterations (three 61-node lines on
#: housner2022's slopes take 1666: 2.05 s against 1.46 s), so they keep the compiled path.
NUMPY_STATICS_NODES = 200


def numpy_statics(scene):
    """The scene as ``cablefem static`` solves it: a small one (one line of at most
    ``NUMPY_STATICS_NODES`` nodes, no junction or free body to solve for, no soil, the default
    assembly) on the numpy path, the catalog loads' numpy faces on precomputed basis data with a
    sparse LU and the seabed's numpy projection, which gives the compiled path's numbers to
    round-off (tests/test_startup.py) without loading a compiled kernel; any other scene as it is
    (docs/outputs.md, ``cablefem static``)."""
    nodes = sum(line.order * sum(seg.elements for seg in line.segments) + 1 for line in scene.lines)
    if (len(scene.lines) > 1 or nodes > NUMPY_STATICS_NODES or "soil" in scene.load_settings
            or scene.solver.assembly != "kernel"
            or ((scene.points or scene.bodies) and any(coupling(scene.lines, scene.points, scene.bodies)))):
        return scene
    seabed = scene.seabed
    if getattr(seabed, "compiled", False):  # a grid's or a mesh's compiled projection: its numpy twin
        seabed = copy.copy(seabed)
        seabed.compiled = False
    return replace(scene, seabed=seabed, solver=replace(scene.solver, assembly="numpy"))


def warm_imports():
    """Import the modules a static solve imports on first use (scipy.optimize among them, ~0.4 s
    in a fresh process), so that timing the solve times the solve."""
    import cablefem.loads.friction  # noqa: F401 (the contact load's builder)
    import cablefem.runs.results  # noqa: F401
    import cablefem.statics.touchdown  # noqa: F401


def solve_scene_static(scene):
    """Static equilibrium of every line of a scene: (list of LineReport, Newton iterations, results).
    With ``[soil]`` each line follows its pretension path (``cablefem.statics.pretension``)."""
    return static_network(scene)[:3]


def static_network(scene):
    """Static equilibrium of every line of a scene and of its network's coupling unknowns:
    (list of LineReport, Newton iterations, results per line (``StaticResult``), network) with
    network the ``NetworkStatics`` of the junctions and free bodies (None without any)."""
    from cablefem.runs.results import report

    systems, results, iterations, network = static_lines(scene)
    soil = "soil" in scene.load_settings
    reports = [report(system, result.X, result if soil else None) for system, result in zip(systems, results)]
    return reports, iterations, results, network


def static_lines(scene, t0=None, systems=None):
    """Static equilibrium of every line of a scene: (static ``LineSystem`` per line, ``StaticResult``
    per line, Newton iterations, network), network the ``NetworkStatics`` of the junctions and free
    bodies (None without any). ``t0`` [s]: the lines' prescribed ends where their paths put them at
    t0 (None: where the scene has them). The mesh is the scene's, fitted to the touchdown with
    ``[solver] fit_touchdown``, or the FEM of ``systems`` (other systems of the same lines) when given."""
    from cablefem.statics.newton import StaticResult, scale_free_residual
    from cablefem.statics.touchdown import solve_line

    solver = scene.solver
    network, coupled = None, set()
    if (scene.points or scene.bodies) and any(coupling(scene.lines, scene.points, scene.bodies)):
        from cablefem.statics.network import solve_network

        network = solve_network(scene, lambda line: build_system(scene, line, dynamic=False),
                                tolerance=solver.tolerance, max_iterations=solver.max_iterations)
        coupled = {k for k, X in enumerate(network.states) if X is not None}
    statics, results, iterations = [], [], 0 if network is None else network.iterations
    for k, line in enumerate(scene.lines):
        if k in coupled:
            system, X = network.systems[k], network.states[k]
            result = StaticResult(X, network.string_iterations[k], network.residual, strategy=network.strategy(k),
                                  increment=scale_free_residual(system, X))  # its iterations are the network's
        else:
            if t0 is not None:
                anchor = anchor_path(scene, line)
                line = line.with_ends(line.anchor if anchor is None else anchor(t0)[0],
                                      boundary_path(scene, line)(t0)[0])
            fem = None if systems is None else systems[k].fem
            if "soil" in scene.load_settings:
                from cablefem.statics.pretension import solve_pretension

                system = build_system(scene, line, dynamic=False, fem=fem)
                result = solve_pretension(system, solver.tolerance, solver.max_iterations)
            else:
                system, result = solve_line(line, scene.seabed, scene.contact, scene.environment,
                                            fit_touchdown=solver.fit_touchdown and fem is None,
                                            tolerance=solver.tolerance, max_iterations=solver.max_iterations,
                                            assembly=solver.assembly, sections=scene.load_settings, fem=fem)
            iterations += result.iterations
        statics.append(system)
        results.append(result)
    return statics, results, iterations, network


def start_states(scene, t0=0.0, systems=None):
    """Static equilibrium of every line with its prescribed ends where their paths put them at t0
    (``static_lines``; a network's junctions solved with their strings): (states, Newton
    iterations). ``systems``: the lines' dynamic systems, whose FEM the static ones share and which
    start from the statics' history of the points."""
    check_steppable(scene)
    statics, results, iterations, _ = static_lines(scene, t0, systems)
    if systems is not None:
        for static, system in zip(statics, systems):
            start_history(static, system)
    return [result.X for result in results], iterations


def start_history(static, system):
    """The dynamic ``system`` starts from the history of the points that its ``static`` system
    (the same FEM) ended with."""
    for rule, (old, new) in static.history.items():
        system.history[rule][0][...] = old
        system.history[rule][1][...] = old


def run_start(scene, t0=0.0):
    """A run's start: (dynamic ``LineSystem`` per line of ``dynamic_lines``, start state per line,
    Newton iterations). Each line starts from ``static_lines``' equilibrium at t0 on the mesh its
    statics solved (fitted to the touchdown with ``[solver] fit_touchdown``), from the history of
    points its statics ended with; a string of a network on its own FEM (its junction ends are
    unknowns in a run, held in the network's statics)."""
    return network_start(scene, t0)[:3]


def network_start(scene, t0=0.0):
    """``run_start`` and the network's statics (``NetworkStatics``, None without junctions or free
    bodies), whose poses the free bodies start from."""
    from cablefem.model.network import dynamic_lines

    check_steppable(scene)
    statics, results, iterations, network = static_lines(scene, t0)
    systems = []
    for k, (static, line) in enumerate(zip(statics, dynamic_lines(scene))):
        if network is not None and network.states[k] is not None:
            system = build_system(scene, line)
        else:
            if static.line.segments != line.segments:  # split at the touchdown
                line = replace(line, segments=static.line.segments, joints=static.line.joints)
            system = build_system(scene, line, fem=static.fem)
        start_history(static, system)
        systems.append(system)
    return systems, [result.X for result in results], iterations, network
