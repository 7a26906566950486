"""What the verification and validation studies share: the build-start-integrate loop of one line
of a scene, and JSON and provenance helpers. Each study's ``run.py`` keeps what is particular to it.
"""

import hashlib
import json
import math
import subprocess
from pathlib import Path

import numpy as np


def start_line(scene, index=0, dt=None, integrator=None, **options):
    """The integrator of line ``index`` of ``scene`` at its static start (``cablefem.run.start_states``),
    as ``run_scene`` starts it: the scene's integrator (or ``integrator``, a class or a registry name),
    its [solver] options, the step dt [s] (default: the scene's), ``options`` overriding any of them
    (``newton``, ``compiled``, ``lumped``, ``tolerance``, ...)."""
    from .dynamics import INTEGRATORS, integrator_options
    from .run import boundary_path, build_system, start_states

    line = scene.lines[index]
    systems = [build_system(scene, each) for each in scene.lines]
    states, _ = start_states(scene, systems=systems)
    cls = integrator if isinstance(integrator, type) else INTEGRATORS[integrator or scene.solver.integrator]
    settings = {**integrator_options(scene.solver, cls.name), **options}
    return cls(systems[index], states[index], boundary_path(scene, line), dt=scene.solver.dt if dt is None else dt,
               **settings)


def tensions(integ, times):
    """March ``integ`` to ``times`` (m,) [s]: the fairlead and anchor tensions after each step,
    (m,) and (m,) [N]."""
    forces = integ.march(np.asarray(times, dtype=float))
    return np.linalg.norm(forces[:, 0], axis=1), np.linalg.norm(forces[:, 1], axis=1)


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
