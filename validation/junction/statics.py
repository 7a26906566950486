"""The crowfoot's statics: cablefem's network statics (``cablefem.statics.network``) against MoorPy's
``System``."""

import time

import numpy as np

from cablefem.statics.network import solve_network
from cablefem.runs.results import end_forces
from cablefem.fem.system import build_system

from validation.junction.inputs import (ANCHORS, CHAIN, CLUMP, DEPTH, FAIRLEAD, GRAVITY, JUNCTION, LENGTHS,
                                        WATER_DENSITY)


def moorpy_statics():
    """MoorPy's System of the crowfoot: junction position (3,) [m], tensions [N] at both ends of
    every line ({line: (end A, end B)}; A the junction for the upper line, the anchor for a leg)."""
    import moorpy

    ms = moorpy.System(depth=DEPTH, rho=WATER_DENSITY, g=GRAVITY)
    d, m = CHAIN["diameter"], CHAIN["mass"]
    ms.setLineType(dnommm=100.0, name="chain", d_vol=d, mass=m, EA=CHAIN["EA"],
                   w=(m - WATER_DENSITY * np.pi / 4 * d * d) * GRAVITY)
    ms.addPoint(1, np.array(FAIRLEAD))
    ms.addPoint(0, np.array(JUNCTION), m=CLUMP["mass"], v=CLUMP["volume"])
    ms.addPoint(1, np.array(ANCHORS[0]))
    ms.addPoint(1, np.array(ANCHORS[1]))
    ms.addLine(LENGTHS["upper"], "chain", pointA=2, pointB=1)
    ms.addLine(LENGTHS["leg1"], "chain", pointA=3, pointB=2)
    ms.addLine(LENGTHS["leg2"], "chain", pointA=4, pointB=2)
    ms.initialize()
    ms.solveEquilibrium(tol=1e-10, maxIter=2000)
    tensions = {name: (float(line.TA), float(line.TB)) for name, line in zip(LENGTHS, ms.lineList)}
    return np.array(ms.pointList[1].r, dtype=float), tensions


def cablefem_statics(scene):
    """cablefem's network statics (``cablefem.statics.network``): junction position (3,) and tensions
    {line: (anchor end, fairlead end)} [N] (the lines' ends as MoorPy's A, B)."""
    result = solve_network(scene, lambda line: build_system(scene, line, dynamic=False),
                           tolerance=1e-10, max_iterations=100)
    tensions = {}
    for line, system, X in zip(scene.lines, result.systems, result.states):
        fairlead, anchor = end_forces(system, X)
        tensions[line.name] = (float(np.linalg.norm(anchor)), float(np.linalg.norm(fairlead)))
    return np.array(result.points["j"], dtype=float), tensions


def static_check(scene, log=print):
    """The junction's static position and the tensions: cablefem's network statics against MoorPy
    (MoorDyn's initial condition is the first sample of its runs: ``run_case``)."""
    mp_junction, mp = moorpy_statics()
    start = time.perf_counter()
    cf_junction, cf = cablefem_statics(scene)
    cf_time = time.perf_counter() - start
    names = {"fairlead": ("upper", 1), "anchor1": ("leg1", 0), "anchor2": ("leg2", 0),
             "upper at the junction": ("upper", 0), "leg1 at the junction": ("leg1", 1),
             "leg2 at the junction": ("leg2", 1)}
    rows = [{"quantity": name, "moorpy_N": mp[line][end], "cablefem_N": cf[line][end],
             "cablefem_rel": (cf[line][end] - mp[line][end]) / mp[line][end]} for name, (line, end) in names.items()]
    out = {"rows": rows, "junction_moorpy_m": mp_junction, "junction_cablefem_m": cf_junction,
           "junction_cablefem_error_m": float(np.linalg.norm(cf_junction - mp_junction)), "cablefem_statics_s": cf_time}
    log(f"statics: junction cablefem - MoorPy {out['junction_cablefem_error_m']:.2e} m, tensions "
        f"{max(abs(row['cablefem_rel']) for row in rows):.1e}")
    return out
