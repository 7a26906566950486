"""(a) of verification/seabed_equivalence: every description of the plane, simplify on and off,
solved as ``cablefem static`` solves it with ``[solver] fit_touchdown = true`` and compared with the
plane's answer."""

from dataclasses import replace
from pathlib import Path

import numpy as np

from verification.seabed_equivalence.files import ELEMENTS, TOLERANCE, write_scenes


def solve(scene, fit_touchdown=None):
    """Static solve of a loaded scene's first line at TOLERANCE, as ``cablefem static`` does:
    (LineReport, StaticResult). ``fit_touchdown`` False solves a plane on the mesh as given
    (the statics' touchdown fitting, where it exists, applies to planes only)."""
    from cablefem.statics.scene import solve_scene_static

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
        if label.startswith("MoorDyn"):  # the MoorDyn file's line on the TOML scenes' mesh, not its default P2 one
            scene.lines = [line.with_order(1).with_elements(ELEMENTS) for line in scene.lines]
        rep, res = solve(scene, fit_touchdown=True)  # a plane on the fitted mesh, general models as given
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
        seabed_note = next((n for n in scene.notes if n.startswith("seabed:")),
                           f"seabed: {scene.seabed.describe()}")  # a plane is used as given: no note
        rows.append({
            "seabed": label, "simplify": on, "model": scene.seabed.kind,
            "model_class": type(scene.seabed).__name__,
            "compared_with": "plane" if on else "plane, unfitted",
            **_errors(rep, references[on]),
            "fairlead_tension": rep.fairlead_tension, "touchdown_s": rep.touchdown_s,
            "newton_iterations": res.iterations, "strategy": res.strategy, "note": seabed_note})
    return rows
