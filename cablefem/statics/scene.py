"""The statics of a whole scene: every line's equilibrium and its network's coupling unknowns, as
``cablefem static`` reports them and as a run starts from them.

A line alone is solved with its mesh fitted to the touchdown (``cablefem.statics.touchdown``), a line in
soil along its pretension path (``cablefem.statics.pretension``), the strings that meet at junctions or
free bodies together (``cablefem.statics.network``).
"""

import copy
from dataclasses import replace

from cablefem.fem.system import build_system
from cablefem.model.network import anchor_path, boundary_path, check_no_coupling, coupling
from cablefem.statics.solve import solve_static


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
    from cablefem.model.network import coupling

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


def solve_scene_static(scene):
    """Static equilibrium of every line of a scene: (list of LineReport, Newton iterations, results).
    With ``[soil]`` each line follows its pretension path (``cablefem.statics.pretension``)."""
    return static_network(scene)[:3]


def static_network(scene):
    """Static equilibrium of every line of a scene and of its network's coupling unknowns:
    (list of LineReport, Newton iterations, results per line (``StaticResult``), network) with
    network the ``NetworkStatics`` of the junctions and free bodies (None without any)."""
    from cablefem.runs.results import report
    from cablefem.statics.touchdown import solve_line

    def static_system(line):
        from cablefem.fem.system import build_system  # the run module only for networks and soil

        return build_system(scene, line, dynamic=False)

    network, coupled = None, set()
    if scene.points or scene.bodies:
        from cablefem.statics.network import solve_network
        from cablefem.model.network import coupling

        if any(coupling(scene.lines, scene.points, scene.bodies)):
            network = solve_network(scene, static_system,
                                    tolerance=scene.solver.tolerance, max_iterations=scene.solver.max_iterations)
            coupled = {k for k, X in enumerate(network.states) if X is not None}
    reports, results, iterations = [], [], 0 if network is None else network.iterations
    for k, line in enumerate(scene.lines):
        if k in coupled:
            from cablefem.statics.newton import StaticResult, scale_free_residual

            system, X = network.systems[k], network.states[k]
            result = StaticResult(X, 0, network.residual, strategy="network",
                                  increment=scale_free_residual(system, X))
        else:
            if "soil" in scene.load_settings:
                from cablefem.statics.pretension import solve_pretension

                system = static_system(line)
                result = solve_pretension(system, scene.solver.tolerance, scene.solver.max_iterations)
            else:
                system, result = solve_line(line, scene.seabed, scene.contact, scene.environment,
                                            fit_touchdown=scene.solver.fit_touchdown,
                                            tolerance=scene.solver.tolerance,
                                            max_iterations=scene.solver.max_iterations,
                                            assembly=scene.solver.assembly, sections=scene.load_settings)
            iterations += result.iterations
            X = result.X
        results.append(result)
        reports.append(report(system, X, result if "soil" in scene.load_settings else None))
    return reports, iterations, results, network


def start_states(scene, t0=0.0, systems=None):
    """Static equilibrium of every line with its prescribed ends where their paths put them at t0
    (a network's junctions solved with their strings: ``cablefem.statics.network``); ``systems``: the
    lines' dynamic systems, whose FEM the static ones share and which start from the statics'
    history of the points."""
    check_no_coupling(scene)
    network = None
    if any(coupling(scene.lines, scene.points, scene.bodies)):
        from cablefem.statics.network import solve_network

        network = solve_network(scene, lambda line: build_system(scene, line, dynamic=False),
                                tolerance=scene.solver.tolerance,
                                max_iterations=scene.solver.max_iterations)
    states, iterations = [], 0 if network is None else network.iterations
    for k, line in enumerate(scene.lines):
        if network is not None and network.states[k] is not None:
            static, X = network.systems[k], network.states[k]
        else:
            anchor = anchor_path(scene, line)
            moved = line.with_ends(line.anchor if anchor is None else anchor(t0)[0],
                                   boundary_path(scene, line)(t0)[0])
            fem = None if systems is None else systems[k].fem
            static = build_system(scene, moved, dynamic=False, fem=fem)
            if "soil" in scene.load_settings:  # a line in soil starts where its pretension path ends
                from cablefem.statics.pretension import solve_pretension

                result = solve_pretension(static, scene.solver.tolerance, scene.solver.max_iterations)
            else:
                result = solve_static(static, tolerance=scene.solver.tolerance,
                                      max_iterations=scene.solver.max_iterations)
            X, iterations = result.X, iterations + result.iterations
        if systems is not None:
            for rule, (old, new) in static.history.items():
                systems[k].history[rule][0][...] = old
                systems[k].history[rule][1][...] = old
        states.append(X)
    return states, iterations
