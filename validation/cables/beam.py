"""MoorDyn's own beam inputs (MoorDyn's tests/Mooring, copied unchanged in tests/data/moordyn/beam/), in
both codes: ``BeamSimplySupported.txt``, a 10 m beam of EI = 1e7 N m², EA = 1.5e9 N, 100 kg/m between
two Fixed points 10 m above the still water (in the air), sagging under its own weight; and
``BeamCantilevered.txt``, the same beam from the end of a Fixed Rod, clamped to the rod's axis, its
other end on a massless free point: a cantilever under its own weight, tip w L^4 / (8 EI) (Timoshenko
& Gere 1961), the clamp's moment w L^2 / 2.

Closed forms: Euler-Bernoulli's simply supported beam, midspan 5 w L^4 / (384 EI) (MoorDyn's test
asserts its nodes within 50 % of w x (L^3 - 2 L x^2 + x^3) / (24 EI)); and, since both ends are fixed
points, the beam stretched by its own sag: the beam-string under the tension N it makes, EI w'''' -
N w'' = w, with N = EA / (2 L) int w'^2 dx (solved by a root finder), whose deflection is the
reference for a line that carries its axial force.
"""

import math
import time
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

ROOT = Path(__file__).resolve().parents[2]
FILE = ROOT / "tests" / "data" / "moordyn" / "beam" / "BeamSimplySupported.txt"
CANTILEVER = FILE.with_name("BeamCantilevered.txt")
L, EI, EA, MASS, HEIGHT = 10.0, 1e7, 1.5e9, 100.0, 10.0
GRAVITY = 9.80665  # MoorDyn's


def euler_bernoulli(x):
    """Deflection [m] (down) of the simply supported beam at x (n,) [m]."""
    w = MASS * GRAVITY
    return w * x * (L**3 - 2.0 * L * x**2 + x**3) / (24.0 * EI)


def stretched(x):
    """Deflection [m] (down) at x (n,) of the beam-string under the tension its sag makes, and that
    tension [N]."""
    w = MASS * GRAVITY
    fine = np.linspace(0.0, L, 20001)

    def shape(N, at):
        k = math.sqrt(N / EI)
        return (w / (N * k * k) * (np.cosh(k * (at - L / 2)) / math.cosh(k * L / 2) - 1.0)
                + w * at * (L - at) / (2.0 * N))

    def mismatch(N):
        slope = np.gradient(shape(N, fine), fine)
        return EA * 0.5 * np.trapezoid(slope**2, fine) / L - N

    N = brentq(mismatch, 1.0, 1e7, xtol=1e-10)
    return shape(N, x), N


def cablefem_beam(elements=None):
    """cablefem's static solve of the file (its NumSegs, or ``elements``): node x (n,), deflection (n,),
    the end tension [N], Newton's iterations and the wall time [s]."""
    from cablefem.io import load_scene
    from cablefem.fem.system import build_system
    from cablefem.statics.solve import solve_static
    from cablefem.runs.results import report

    scene = load_scene(FILE)
    line = scene.lines[0] if elements is None else scene.lines[0].with_elements(elements)
    system = build_system(scene, line, dynamic=False)
    begin = time.perf_counter()
    result = solve_static(system)
    wall = time.perf_counter() - begin
    rep = report(system, result.X)
    horizontal = float(abs(rep.fairlead_force[0]))
    return {"elements": line.segments[0].elements, "x": rep.nodes[:, 0], "deflection": HEIGHT - rep.nodes[:, 2],
            "axial_force": horizontal, "iterations": result.iterations, "wall_time_s": wall,
            "midspan_moment": float(np.interp(L / 2, rep.nodes[:, 0], rep.bending_moment))}


def moordyn_beam():
    """MoorDyn-C's initial-condition solve of the file as it stands: node x (n,), deflection (n,) and
    the wall time [s]."""
    import shutil
    import tempfile

    from validation.cables.moordyn_side import initialised

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / FILE.name
        shutil.copy(FILE, path)
        with initialised(path) as (moordyn, system, wall):
            line = moordyn.GetLine(system, 1)
            nodes = np.array([moordyn.GetLineNodePos(line, i) for i in range(moordyn.GetLineNumberNodes(line))])
    return {"segments": len(nodes) - 1, "x": nodes[:, 0], "deflection": HEIGHT - nodes[:, 2], "wall_time_s": wall}


def compare():
    """Both codes against both closed forms: the largest deflection of each, its ratio to 5 w L^4 /
    (384 EI), and each code's largest difference from the stretched beam at its own nodes
    (relative to its midspan)."""
    w = MASS * GRAVITY
    midspan = 5.0 * w * L**4 / (384.0 * EI)
    out = {"euler_bernoulli_midspan": midspan}
    _, out["stretched_axial_force"] = stretched(np.array([L / 2]))
    out["stretched_midspan"] = float(stretched(np.array([L / 2]))[0][0])
    for name, run in (("cablefem", cablefem_beam()), ("cablefem_fine", cablefem_beam(152)), ("moordyn", moordyn_beam())):
        reference, _ = stretched(run["x"])
        run.update(largest=float(run["deflection"].max()), ratio_to_euler_bernoulli=float(run["deflection"].max() / midspan),
                   error_to_stretched=float(np.max(np.abs(run["deflection"] - reference)) / out["stretched_midspan"]))
        run["x"], run["deflection"] = run["x"].tolist(), run["deflection"].tolist()
        out[name] = run
    return out


def cablefem_cantilever():
    """cablefem's static solve of ``BeamCantilevered.txt``: the tip's drop [m], the clamp's moment
    [N m] (its reaction, ``fem.clamp``), Newton's iterations and the wall time [s]."""
    from cablefem.io import load_scene
    from cablefem.fem.system import build_system
    from cablefem.statics.solve import solve_static
    from cablefem.runs.results import report

    scene = load_scene(CANTILEVER)
    system = build_system(scene, scene.lines[0], dynamic=False)
    begin = time.perf_counter()
    result = solve_static(system)
    wall = time.perf_counter() - begin
    rep = report(system, result.X)
    return {"elements": scene.lines[0].segments[0].elements, "tip_drop": float(HEIGHT - rep.nodes[-1, 2]),
            "clamp_moment": float(rep.bending_moment[0]), "iterations": result.iterations, "wall_time_s": wall}


def moordyn_cantilever():
    """MoorDyn-C's initial condition of ``BeamCantilevered.txt`` (relaxed for its TmaxIC 40 s): the
    tip's drop [m] (its free point) and the wall time [s]."""
    import shutil
    import tempfile

    from validation.cables.moordyn_side import initialised

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / CANTILEVER.name
        shutil.copy(CANTILEVER, path)
        with initialised(path) as (moordyn, system, wall):
            tip = np.array(moordyn.GetPointPos(moordyn.GetPoint(system, 1)))
            line = moordyn.GetLine(system, 1)
            segments = moordyn.GetLineNumberNodes(line) - 1
    return {"segments": segments, "tip_drop": float(HEIGHT - tip[2]), "wall_time_s": wall}


def compare_cantilever():
    """Both codes' tip drop against w L^4 / (8 EI), and cablefem's clamp moment against w L^2 / 2."""
    w = MASS * GRAVITY
    out = {"euler_bernoulli_tip": w * L**4 / (8.0 * EI), "clamp_moment_exact": w * L**2 / 2.0}
    for name, run in (("cablefem", cablefem_cantilever()), ("moordyn", moordyn_cantilever())):
        run["tip_error"] = run["tip_drop"] / out["euler_bernoulli_tip"] - 1.0
        out[name] = run
    out["cablefem"]["clamp_moment_error"] = out["cablefem"]["clamp_moment"] / out["clamp_moment_exact"] - 1.0
    return out
