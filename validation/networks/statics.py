"""The semi-taut network in statics, cablefem against MoorPy's System (elastic catenaries with a
rigid, frictionless seabed: CB = 0, and free points with mass and volume).

MoorPy's line weight per length is w = (m - rho pi d^2 / 4) g, its buoyancy of a point rho g V,
as cablefem's. MoorPy's seabed is rigid; cablefem's a penalty (kBot [N/m^3] per unit area d l),
made stiff here (``STIFF_KBOT``: a lying chain sinks w / (kBot d) = 4e-6 m) so that the two
seabeds agree to far below 1e-4.
"""

import os
from dataclasses import replace

import numpy as np

from cablefem.model.line import Line
from cablefem.fem.system import build_system
from cablefem.statics.touchdown import solve_line
from cablefem.model.scene import Contact

from validation.moordyn.inputs import GRAVITY, WATER_DENSITY

STIFF_KBOT = 3.0e9  # N/m^3


def moorpy_system(net, fixed_body=True):
    """A MoorPy System of ``net`` with its body (one) fixed at rest, or free (MoorPy type 0) when
    ``fixed_body`` is False; returns (system, point index by name, line index by name)."""
    os.environ.setdefault("PYTHONBREAKPOINT", "0")  # MoorPy calls breakpoint() before some errors
    import moorpy

    ms = moorpy.System(depth=net.depth, rho=WATER_DENSITY, g=GRAVITY)
    for name, p in net.types.items():
        w = (p["MassDen"] - WATER_DENSITY * np.pi / 4 * p["Diam"] ** 2) * GRAVITY
        ms.setLineType(dnommm=1000 * p["Diam"], name=name, d_vol=p["Diam"], mass=p["MassDen"], EA=p["EA"], w=w)
    (body,) = net.bodies
    if fixed_body:
        ms.addBody(1, np.r_[body.position, 0.0, 0.0, 0.0])
    else:
        f = body.free
        ms.addBody(0, np.r_[body.position, 0.0, 0.0, 0.0], m=f["mass"], v=f["volume"], rCG=np.array(f["cg"]),
                   AWP=f["waterplane_area"], rM=np.array(f["cb"]), f6Ext=np.r_[f["force"], f["moment"]])
    index = {}
    for p in net.points:
        if p.body:
            ms.addPoint(1, np.asarray(p.position, dtype=float))
            ms.bodyList[0].attachPoint(len(ms.pointList), np.asarray(p.position, dtype=float))
        else:
            ms.addPoint(1 if p.kind == "fixed" else 0, np.asarray(p.position, dtype=float), m=p.mass, v=p.volume)
        index[p.name] = len(ms.pointList)
    lines = {}
    for line in net.lines:
        ms.addLine(line.length, line.type, pointA=index[line.a], pointB=index[line.b])
        lines[line.name] = len(ms.lineList)
    ms.initialize()
    return ms, index, lines


def moorpy_statics(net, tol=1e-10):
    """MoorPy's equilibrium of ``net`` (body fixed): end tensions [N] of each line (name -> (TA, TB))
    and the free points' positions (name -> (3,) [m])."""
    ms, index, lines = moorpy_system(net)
    ms.solveEquilibrium(tol=tol, maxIter=2000)
    tensions = {name: (float(ms.lineList[k - 1].TA), float(ms.lineList[k - 1].TB)) for name, k in lines.items()}
    points = {p.name: np.array(ms.pointList[index[p.name] - 1].r) for p in net.points if p.kind == "free"}
    return tensions, points


def cablefem_statics(scene, net, order=1, factor=1, stiffness=STIFF_KBOT, tolerance=1e-11):
    """cablefem's statics of ``scene`` (every string's ends prescribed) with the seabed stiffness
    ``stiffness`` [N/m^3], ``factor`` times the elements and elements of ``order``: end tensions of
    each of ``net``'s lines (name -> (TA, TB), from the element tensions beside the joints and the
    reactions at the string ends) and the free points' positions."""
    lines = [replace(line, segments=tuple(replace(seg, elements=seg.elements * factor) for seg in line.segments),
                     order=order) for line in scene.lines]
    scene = replace(scene, lines=lines, contact=Contact(stiffness=stiffness, damping=0.0),
                    solver=replace(scene.solver, tolerance=tolerance, max_iterations=200))
    tensions, points = {}, {}
    for line in scene.lines:
        # a vertex fitted to the touchdown (cablefem.statics.touchdown): the element order then pays off
        system, result = solve_line(line, scene.seabed, scene.contact, scene.environment, tolerance=tolerance,
                                    max_iterations=200, sections=scene.load_settings)
        X = result.X
        for b, joint in line.joints:
            points[joint.name] = X[line.joint_vertices()[[j.name for _, j in line.joints].index(joint.name)]].copy()
        for part, (TA, TB) in zip(line.name.split("+"), part_end_forces(scene, system, X)):
            tensions[part] = (float(np.linalg.norm(TA)), float(np.linalg.norm(TB)))
    return tensions, points


def part_end_forces(scene, system, X):
    """Per piece of a string between its ends and joints (one per line of the network): the forces
    (3,), (3,) [N] it exerts on its two end vertices, the consistent FEM reactions of the piece
    alone (its elements' residual at its end rows, node loads excluded), its interior rows checked
    at rest (the rows picked as the FEM numbers them: vertices first, then each element's others)."""
    line, fem = system.line, system.fem
    order, n_vertices = line.order, fem.n_vertices
    cuts = np.cumsum([0] + [seg.elements for seg in line.segments])
    vertices = sorted(set(int(v) for v in line.joint_vertices()) - {0, int(cuts[-1])})
    bounds = [0] + vertices + [int(cuts[-1])]
    out = []
    for first, last in zip(bounds[:-1], bounds[1:]):
        segments = tuple(seg for seg, a, b in zip(line.segments, cuts[:-1], cuts[1:]) if a >= first and b <= last)
        rows = list(range(first, last + 1)) + list(range(n_vertices + first * (order - 1),
                                                         n_vertices + last * (order - 1)))
        part = Line(f"{line.name}-{first}", X[first], X[last], segments, order)
        sub = build_system(scene, part, dynamic=False)
        residual = sub.residual(X[rows])
        interior = np.abs(np.delete(residual, [sub.fem.anchor_dof, sub.fem.fairlead_dof], axis=0)).max()
        if interior > 1e-6 * np.abs(residual).max():
            raise RuntimeError(f"{line.name} vertices {first}-{last}: interior rows at {interior:.3g} N: the rows "
                               "were not picked as the FEM numbers them")
        out.append((-residual[sub.fem.anchor_dof], -residual[sub.fem.fairlead_dof]))
    return out


def compare_statics(net, scene, meshes=((1, 1), (1, 2), (2, 1), (2, 2)), log=print):
    """cablefem against MoorPy, the body fixed: per mesh (order, factor) the largest relative
    tension difference, the largest joint position difference [m] and the rows."""
    md_t, md_p = moorpy_statics(net)
    out = {"moorpy": {"tensions": md_t, "points": md_p}, "meshes": []}
    for order, factor in meshes:
        t, p = cablefem_statics(scene, net, order=order, factor=factor)
        rel = {name: [(a - b) / b for a, b in zip(t[name], md_t[name])] for name in md_t}
        gap = {name: float(np.linalg.norm(p[name] - md_p[name])) for name in md_p}
        worst = max(abs(x) for v in rel.values() for x in v)
        log(f"  statics order {order} x{factor}: largest tension difference {worst:.2e}, "
            f"largest point distance {max(gap.values()):.2e} m")
        out["meshes"].append({"order": order, "factor": factor, "tensions": t, "relative": rel,
                              "points": {k: v.tolist() for k, v in p.items()}, "point_distance_m": gap,
                              "largest_relative": worst, "largest_distance_m": max(gap.values())})
    return out


def moorpy_free(net, tol=1e-10):
    """MoorPy's equilibrium of ``net`` with its body free: the body's reference point (3,) [m], its
    rotation matrix (3, 3) (MoorPy turns z-y-x: compared as matrices), every line's (TA, TB) [N]
    and the free points' positions."""
    from moorpy.helpers import rotationMatrix

    ms, index, lines = moorpy_system(net, fixed_body=False)
    ms.solveEquilibrium(tol=tol, maxIter=2000)
    r6 = np.array(ms.bodyList[0].r6)
    tensions = {name: (float(ms.lineList[k - 1].TA), float(ms.lineList[k - 1].TB)) for name, k in lines.items()}
    points = {p.name: np.array(ms.pointList[index[p.name] - 1].r) for p in net.points if p.kind == "free"}
    return r6[:3], rotationMatrix(*r6[3:]), tensions, points


def cablefem_free(scene, order=1, factor=1, stiffness=STIFF_KBOT, tolerance=1e-10):
    """cablefem's network statics (``cablefem.statics.network.solve_network``) of ``scene`` with its body
    free: reference point, rotation matrix, every line's (TA, TB) and the free points' positions."""
    from cablefem.statics.network import solve_network
    from cablefem.model.network import rotation

    lines = [replace(line, segments=tuple(replace(seg, elements=seg.elements * factor) for seg in line.segments),
                     order=order) for line in scene.lines]
    scene = replace(scene, lines=lines, contact=Contact(stiffness=stiffness, damping=0.0),
                    solver=replace(scene.solver, tolerance=tolerance, max_iterations=200))
    result = solve_network(scene, lambda line: build_system(scene, line, dynamic=False), tolerance=tolerance,
                           max_iterations=200)
    (pose,) = result.poses.values()
    tensions, points = {}, {}
    for system, X in zip(result.systems, result.states):
        line = system.line
        names = [j.name for _, j in line.joints]
        for name, vertex in zip(names, line.joint_vertices()):
            points[name] = X[vertex].copy()
        for part, (TA, TB) in zip(line.name.split("+"), part_end_forces(scene, system, X)):
            tensions[part] = (float(np.linalg.norm(TA)), float(np.linalg.norm(TB)))
    return pose[:3], rotation(pose[3:]), tensions, points, result


def compare_free(net, scene, meshes=((1, 1), (1, 2), (2, 1), (2, 2), (2, 4)), log=print):
    """cablefem against MoorPy with the body free under its steady load: per mesh the offset
    difference [m], the rotation difference, the largest relative tension difference."""
    r, R, md_t, md_p = moorpy_free(net)
    out = {"moorpy": {"offset": r.tolist(), "rotation": R.tolist(), "tensions": md_t,
                      "points": {k: v.tolist() for k, v in md_p.items()}}, "meshes": []}
    for order, factor in meshes:
        start = __import__("time").perf_counter()
        cr, cR, ct, cp, result = cablefem_free(scene, order=order, factor=factor)
        rel = {name: [(a - b) / b for a, b in zip(ct[name], md_t[name])] for name in md_t}
        worst = max(abs(x) for v in rel.values() for x in v)
        row = {"order": order, "factor": factor, "offset": cr.tolist(), "rotation": cR.tolist(), "tensions": ct,
               "relative": rel, "largest_relative": worst,
               "offset_difference_m": float(np.linalg.norm(cr - r)),
               "offset_relative": float(np.linalg.norm(cr - r) / np.linalg.norm(r[:2])),
               "rotation_difference": float(np.abs(cR - R).max()),
               "largest_distance_m": max(float(np.linalg.norm(cp[k] - md_p[k])) for k in md_p),
               "outer_iterations": len(result.history) - 1, "wall_time_s": __import__("time").perf_counter() - start}
        log(f"  free platform, order {order} x{factor}: offset {cr.round(4).tolist()} (MoorPy {r.round(4).tolist()}),"
            f" difference {row['offset_difference_m']:.2e} m, rotation {row['rotation_difference']:.2e}, "
            f"largest tension difference {worst:.2e}")
        out["meshes"].append(row)
    return out
