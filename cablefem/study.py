"""What the verification and validation studies share: the build-start-integrate loop of one line
of a scene, and JSON and provenance helpers. Each study's ``run.py`` keeps what is particular to it.
"""

import hashlib
import json
import math
import subprocess
import time
from pathlib import Path

import numpy as np


def start_line(scene, index=0, dt=None, integrator=None, **options):
    """The integrator of line ``index`` of ``scene`` at its static start (``cablefem.statics.scene.start_states``),
    as ``run_scene`` starts it: the scene's integrator (or ``integrator``, a class or a registry name),
    its [solver] options, the step dt [s] (default: the scene's), ``options`` overriding any of them
    (``newton``, ``compiled``, ``lumped``, ``tolerance``, ...)."""
    from cablefem.dynamics.registry import INTEGRATORS, integrator_options
    from cablefem.model.network import boundary_path
    from cablefem.fem.system import build_system
    from cablefem.statics.scene import start_states

    line = scene.lines[index]
    systems = [build_system(scene, each) for each in scene.lines]
    states, _ = start_states(scene, systems=systems)
    cls = integrator if isinstance(integrator, type) else INTEGRATORS[integrator or scene.solver.integrator]
    settings = {**integrator_options(scene.solver, cls), **options}
    return cls(systems[index], states[index], boundary_path(scene, line), dt=scene.solver.dt if dt is None else dt,
               **settings)


def tensions(integ, times):
    """March ``integ`` to ``times`` (m,) [s]: the fairlead and anchor tensions after each step,
    (m,) and (m,) [N]."""
    forces = integ.march(np.asarray(times, dtype=float))
    return np.linalg.norm(forces[:, 0], axis=1), np.linalg.norm(forces[:, 1], axis=1)


def observed_order(counts, errors, floor):
    """(pairwise orders, least-squares order over |errors| above ``floor``) of a convergence study:
    the errors (m,) (None: missing) against the element counts (m,); None where there are fewer
    than two points."""
    n = np.asarray(counts, dtype=float)
    e = np.abs(np.asarray([np.nan if v is None else v for v in errors], dtype=float))
    pairwise = [float(np.log(e[i] / e[i + 1]) / np.log(n[i + 1] / n[i])) if e[i] > 0 and e[i + 1] > 0 else None
                for i in range(len(n) - 1)]
    keep = e > floor
    fitted = float(-np.polyfit(np.log(n[keep]), np.log(e[keep]), 1)[0]) if keep.sum() >= 2 else None
    return pairwise, fitted


def observed_orders(counts, runs, floors, error=None):
    """``observed_order`` of each error of a convergence study: {key: {"pairwise", "fitted"}} for
    each ``key: floor`` of ``floors``, the errors ``error(run, key)`` of ``runs`` (default
    ``run[key]``) against the element counts."""
    error = error or (lambda run, key: run[key])
    return {key: dict(zip(("pairwise", "fitted"), observed_order(counts, [error(run, key) for run in runs], floor)))
            for key, floor in floors.items()}


def solve_on_mesh(line_of, seabed, contact, environment, mesh="uniform", touchdown=None, tolerance=1e-8):
    """(system, StaticResult, wall time [s]) of a static solve of the line ``line_of(vertex)`` (a
    ``Line``; ``vertex``: None or an arc length [m] that gets a mesh vertex) on ``mesh``: "uniform"
    (as given), "fitted" (statics' touchdown fitting, ``solve_line``) or "exact-vertex" (a vertex at
    ``touchdown`` [m])."""
    from cablefem.statics.touchdown import solve_line
    from cablefem.statics.solve import solve_static
    from cablefem.fem.system import LineSystem

    start = time.perf_counter()
    if mesh == "fitted":
        system, result = solve_line(line_of(None), seabed, contact, environment, fit_touchdown=True,
                                    tolerance=tolerance)
    else:
        system = LineSystem(line_of(touchdown if mesh == "exact-vertex" else None), seabed, contact, environment)
        result = solve_static(system, tolerance=tolerance)
    return system, result, time.perf_counter() - start


def position_errors(fem, X, reference, length):
    """Largest distances [m] of a solution X from ``reference(s)`` ((n, 3) at unstretched arc
    lengths s (n,)): at the mesh's vertices, and along the line (4001 points and the vertices
    over ``length`` [m])."""
    vertices = fem.mesh.p[0]
    dense = np.union1d(np.linspace(0.0, length, 4001), vertices)
    nodes = np.linalg.norm(fem.evaluate(X, vertices) - reference(vertices), axis=1)
    curve = np.linalg.norm(fem.evaluate(X, dense) - reference(dense), axis=1)
    return float(nodes.max()), float(curve.max())


def jsonable(value, private=False, finite=False, drop=()):
    """``value`` for JSON: numpy arrays and scalars as Python lists and numbers, keys as strings;
    ``private``: keep keys starting with "_" (dropped otherwise); ``finite``: NaN and infinity as
    None; ``drop``: keys left out wherever they are."""
    if isinstance(value, dict):
        return {str(k): jsonable(v, private, finite, drop) for k, v in value.items()
                if (private or not str(k).startswith("_")) and k not in drop}
    if isinstance(value, (list, tuple)):
        return [jsonable(v, private, finite, drop) for v in value]
    if isinstance(value, np.ndarray):
        return jsonable(value.tolist(), private, finite, drop)
    if isinstance(value, (np.integer, np.bool_)):
        return value.item()
    if isinstance(value, (float, np.floating)):
        value = float(value)
        return None if finite and not math.isfinite(value) else value
    return value


def write_json(path, results, **options):
    """Write ``jsonable(results, **options)`` to ``path`` (indented), the folder made if need be."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(jsonable(results, **options), indent=1))
    return path


def package_version(name):
    """The installed version of the distribution ``name`` (e.g. "moordyn"), None if it is not installed."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(name)
    except PackageNotFoundError:
        return None


def provenance():
    """Which cablefem the numbers come from: git HEAD, its uncommitted files under cablefem/ (None:
    not a git checkout), and a digest of its source files (several people edit the tree at once)."""
    import cablefem

    root = Path(cablefem.__file__).resolve().parent
    digest = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        digest.update(str(path.relative_to(root)).encode() + b"\0" + path.read_bytes())

    def git(*args):
        try:
            return subprocess.run(["git", *args], cwd=root, capture_output=True, text=True, timeout=30).stdout.strip()
        except (OSError, subprocess.SubprocessError):
            return ""

    head = git("rev-parse", "--short", "HEAD") or None
    changed = [line[3:] for line in git("status", "--porcelain", ".").splitlines() if line[3:]] if head else None
    return {"git_head": head, "cablefem_dirty": None if changed is None else bool(changed),
            "cablefem_uncommitted": changed, "cablefem_sha256": digest.hexdigest()[:16], "cablefem_path": str(root)}


def stamp(started):
    """Provenance at the start and end of a study (``started``: ``provenance()`` at its start), and
    whether cablefem changed in between (a warning is printed then)."""
    ended = provenance()
    changed = started["cablefem_sha256"] != ended["cablefem_sha256"]
    if changed:
        print("warning: cablefem/ changed during this run; modules were imported at its start")
    return {"start": started, "end": ended, "cablefem_changed_during_run": changed}
