"""Vertex-normal projection onto triangulated seabeds: exactness, continuity, convergence, cost.

desire2023 Sec. 2.2.2.2 (Eq. 6, 7, 10, after Orazi & Reggiani 2020), Sec. 2.4
and Table 6. Run ``python -m verification.projection.run [--fast] [--out DIR]``;
``run(fast=True)`` returns the numbers the tests assert on, in a few seconds.

(a) a tilted plane triangulated irregularly projects exactly as ``Plane``;
(b) along a path over a curved mesh the largest jump of d_P between
    neighbouring samples shrinks linearly with the spacing (face normals jump
    by a fixed amount), and so does the spread of d_P across an edge and
    around a vertex;
(c) d_G converges to the true distance to a sphere at order 2 as the mesh refines;
(d) points projected per second, cold (first call) and warm (the same points
    moved slightly, as between Newton iterations).
"""

import argparse
import time
from pathlib import Path

import numpy as np
from scipy.spatial import Delaunay

from cablefem.geometry import Horizontal, Plane, TriangulatedSurface
from cablefem.study import write_json

HERE = Path(__file__).resolve().parent


def _rate(spacing, values):
    """Observed order: slope of log(values) against log(spacing), least squares."""
    return float(np.polyfit(np.log(spacing), np.log(values), 1)[0])


def _grid(n, extent, height):
    """Vertices (n*n, 3) and triangles of a regular n x n grid over extent^2 [m] with z = height(x, y)."""
    from cablefem.geometry.planes import _grid_triangles

    x = np.linspace(-extent, extent, n)
    xx, yy = np.meshgrid(x, x)
    xy = np.column_stack([xx.ravel(), yy.ravel()])
    return np.column_stack([xy, height(xy)]), _grid_triangles(n, n)


def _wavy(xy, amplitude=3.0, wavelength=40.0, depth=50.0):
    """Elevation [m] of the test bathymetry z = -depth + A sin(kx) cos(ky) at xy (n, 2)."""
    k = 2.0 * np.pi / wavelength
    return -depth + amplitude * np.sin(k * xy[:, 0]) * np.cos(k * xy[:, 1])


def _irregular(n, extent, height, rng):
    """A jittered-grid Delaunay mesh over extent^2 [m] with vertices on z = height(x, y)."""
    x = np.linspace(-extent, extent, n)
    xx, yy = np.meshgrid(x, x)
    xy = np.column_stack([xx.ravel(), yy.ravel()])
    inner = (np.abs(xy) < extent).all(axis=1)
    xy[inner] += rng.uniform(-0.3, 0.3, (inner.sum(), 2)) * (x[1] - x[0])
    return TriangulatedSurface(np.column_stack([xy, height(xy)]), Delaunay(xy).simplices)


def plane_exactness(rng):
    """(a) Largest differences from Plane.project over 2000 points, for both windings."""
    plane = Plane([3.0, -2.0, -60.0], [0.15, -0.25, 1.0])
    mesh = _irregular(12, 50.0, plane.elevation, rng)
    inside = np.column_stack([rng.uniform(-49, 49, (1000, 2)), rng.uniform(-90, -30, 1000)])
    beyond = np.column_stack([rng.uniform(-80, 80, (1000, 2)), rng.uniform(-90, -30, 1000)])
    result = {}
    for winding, surface in (("up", mesh), ("down", TriangulatedSurface(mesh.vertices,
                                                                        mesh.triangles[:, ::-1]))):
        for where, points in (("inside", inside), ("beyond_edge", beyond)):
            ours, exact = surface.project(points), plane.project(points)
            result[f"{winding}_{where}"] = {
                field: float(np.abs(getattr(ours, field) - getattr(exact, field)).max())
                for field in ("gap", "direction", "closest", "gap_gradient", "direction_gradient")}
    return result


def _face_normals_along(surface, points):
    """Normal (n, 3) of the face each point (n, 3) is projected onto: the discontinuous alternative."""
    triangle = surface.locate(points)[0]
    return surface.face_normals[triangle]


def continuity(rng, fast):
    """(b) Jumps of d_P along a path, across an edge and around a vertex, against the spacing."""
    surface = _irregular(21 if fast else 41, 50.0, _wavy, rng)
    start, end = np.array([-45.0, -38.0]), np.array([44.0, 41.0])
    counts = [200, 400, 800, 1600] if fast else [200, 400, 800, 1600, 3200, 6400, 12800]
    spacing, vertex_jump, face_jump, triangles_crossed = [], [], [], 0
    for count in counts:
        u = np.linspace(0.0, 1.0, count + 1)[:, None]
        xy = start + u * (end - start)
        points = np.column_stack([xy, _wavy(xy) + 0.5])
        surface.reset()
        direction = surface.project(points).direction
        faces = _face_normals_along(surface, points)
        spacing.append(float(np.linalg.norm(end - start) / count))
        vertex_jump.append(float(np.linalg.norm(np.diff(direction, axis=0), axis=1).max()))
        face_jump.append(float(np.linalg.norm(np.diff(faces, axis=0), axis=1).max()))
        triangles_crossed = int(len(np.unique(surface.locate(points)[0])))
    # across one interior edge and around one interior vertex, at distance eps
    interior = np.flatnonzero((surface.neighbours >= 0).all(axis=1))
    tri = interior[len(interior) // 2]
    corner_a, corner_b = surface.triangles[tri, 1], surface.triangles[tri, 2]  # edge opposite corner 0
    a, b = surface.vertices[corner_a], surface.vertices[corner_b]
    lift = 0.3 * (surface.vertex_normals[corner_a] + surface.vertex_normals[corner_b])
    across = np.cross(b - a, surface.face_normals[tri])
    across /= np.linalg.norm(across)
    vertex = surface.triangles[tri, 0]
    eps = 10.0 ** -np.arange(1, 6 if fast else 8)
    edge_jump, vertex_spread, face_spread = [], [], []
    angles = np.linspace(0.0, 2 * np.pi, 48, endpoint=False)
    ring = np.column_stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)])
    for e in eps:
        pair = 0.5 * (a + b) + lift + np.outer([-e, e], across)
        surface.reset()
        d = surface.project(pair).direction
        edge_jump.append(float(np.linalg.norm(d[1] - d[0])))
        around = surface.vertices[vertex] + 0.3 * surface.vertex_normals[vertex] + e * ring
        surface.reset()
        d = surface.project(around).direction
        vertex_spread.append(float(np.linalg.norm(d - surface.vertex_normals[vertex], axis=1).max()))
        f = _face_normals_along(surface, around)
        face_spread.append(float(np.linalg.norm(f - f.mean(axis=0), axis=1).max()))
    return {"path_spacing_m": spacing, "path_max_jump_vertex_normals": vertex_jump,
            "path_max_jump_face_normals": face_jump, "path_triangles_crossed": triangles_crossed,
            "path_rate": _rate(spacing, vertex_jump),
            "eps_m": eps.tolist(), "edge_jump": edge_jump, "edge_rate": _rate(eps, edge_jump),
            "vertex_spread": vertex_spread, "vertex_rate": _rate(eps, vertex_spread),
            "vertex_face_normal_spread": face_spread, "triangles": int(len(surface.triangles))}


def convergence(rng, fast):
    """(c) Largest |d_G - true distance| to a sphere cap against the mesh size, and the observed order."""
    radius, centre = 100.0, np.array([0.0, 0.0, -160.0])

    def cap(xy):
        return centre[2] + np.sqrt(radius ** 2 - (xy ** 2).sum(axis=1))

    direction = rng.normal(size=(2000, 3)) * [0.25, 0.25, 0.0] + [0.0, 0.0, 1.0]
    direction /= np.linalg.norm(direction, axis=1)[:, None]
    direction = direction[np.abs(direction[:, :2]).max(axis=1) < 0.3]
    height = rng.uniform(-10.0, 10.0, len(direction))
    points = centre + (radius + height)[:, None] * direction
    sizes, errors, normal_errors = [], [], []
    for n in ([9, 17, 33, 65] if fast else [9, 17, 33, 65, 129, 257]):
        surface = TriangulatedSurface(*_grid(n, 50.0, cap))
        proj = surface.project(points)
        sizes.append(100.0 / (n - 1))
        errors.append(float(np.abs(proj.gap - height).max()))
        normal_errors.append(float(np.linalg.norm(proj.direction - direction, axis=1).max()))
    return {"mesh_size_m": sizes, "gap_error_m": errors, "direction_error": normal_errors,
            "order": _rate(sizes[-3:], errors[-3:]), "direction_order": _rate(sizes[-3:], normal_errors[-3:]),
            "points": int(len(points)), "sphere_radius_m": radius, "heights_m": [-10.0, 10.0]}


def _seconds(call, repeats):
    """Best wall time [s] of call() over repeats."""
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        best = min(best, time.perf_counter() - start)
    return best


def cost(rng, fast):
    """(d) Points projected per second, cold and warm, for each seabed model and size."""
    counts = [1000, 10000] if fast else [1000, 10000, 100000]
    sizes = [10, 71] if fast else [8, 71, 708]  # vertices per side: ~1e2, 1e4, 1e6 triangles
    extent = 500.0
    seabeds = [("horizontal", lambda: Horizontal(50.0)),
               ("plane", lambda: Plane([0.0, 0.0, -50.0], [0.05, -0.02, 1.0]))]
    for n in sizes:
        seabeds.append((f"mesh {2 * (n - 1) ** 2} triangles",
                        lambda n=n: TriangulatedSurface(*_grid(n, extent, lambda xy: _wavy(xy, 3.0, 400.0)))))
    try:
        from cablefem.geometry.grid import DepthGrid
    except ImportError:
        DepthGrid = None
    if DepthGrid is not None:
        for n in sizes:
            x = np.linspace(-extent, extent, n)
            xx, yy = np.meshgrid(x, x)
            z = _wavy(np.column_stack([xx.ravel(), yy.ravel()]), 3.0, 400.0).reshape(n, n)
            seabeds.append((f"grid {n - 1}x{n - 1} cells", lambda x=x, z=z: DepthGrid(x, x, z)))
    rows = []
    for name, make in seabeds:
        start = time.perf_counter()
        seabed = make()
        build = time.perf_counter() - start
        for count in counts:
            xy = rng.uniform(-0.95 * extent, 0.95 * extent, (count, 2))
            points = np.column_stack([xy, _wavy(xy, 3.0, 400.0) + rng.uniform(-1.0, 1.0, count)])
            moved = points + rng.normal(0.0, 0.01, points.shape)
            repeats = 3 if count >= 100000 else 7

            def cold():
                seabed.reset()
                seabed.project(points)

            cold_s = _seconds(cold, repeats) if hasattr(seabed, "reset") else None
            seabed.project(points)
            warm_s = _seconds(lambda: seabed.project(moved), repeats)
            rows.append({"seabed": name, "points": count, "build_s": build,
                         "cold_s": cold_s, "warm_s": warm_s, "warm_points_per_s": count / warm_s,
                         "cold_points_per_s": None if cold_s is None else count / cold_s})
    return rows


def run(fast=False, seed=0):
    """All four studies; a dict of plain numbers (JSON-ready)."""
    rng = np.random.default_rng(seed)
    start = time.perf_counter()
    results = {"fast": fast, "plane": plane_exactness(rng), "continuity": continuity(rng, fast),
               "convergence": convergence(rng, fast), "cost": cost(rng, fast)}
    results["wall_time_s"] = time.perf_counter() - start
    return results


def report(results):
    """The tables, as text."""
    lines = ["(a) tilted plane, irregular mesh: max |ours - Plane|"]
    for case, errors in results["plane"].items():
        lines.append(f"  {case:18s} " + "  ".join(f"{k} {v:.1e}" for k, v in errors.items()))
    c = results["continuity"]
    lines.append(f"(b) continuity over {c['triangles']} triangles; path crosses {c['path_triangles_crossed']}")
    lines.append("  spacing [m]   max jump d_P (vertex normals)   max jump (face normals)")
    for row in zip(c["path_spacing_m"], c["path_max_jump_vertex_normals"], c["path_max_jump_face_normals"]):
        lines.append("  {:10.4g}    {:12.3e}                    {:10.3e}".format(*row))
    lines.append(f"  observed rate along the path {c['path_rate']:.3f} (expect 1)")
    lines.append("  eps [m]      edge jump      vertex spread   face-normal spread at the vertex")
    for row in zip(c["eps_m"], c["edge_jump"], c["vertex_spread"], c["vertex_face_normal_spread"]):
        lines.append("  {:8.0e}    {:10.3e}     {:10.3e}      {:10.3e}".format(*row))
    lines.append(f"  rates: edge {c['edge_rate']:.3f}, vertex {c['vertex_rate']:.3f} (expect 1)")
    v = results["convergence"]
    lines.append(f"(c) sphere R = {v['sphere_radius_m']:g} m, {v['points']} points within 10 m of it")
    lines.append("  mesh size [m]   max |d_G - distance| [m]   max |d_P - normal|")
    for row in zip(v["mesh_size_m"], v["gap_error_m"], v["direction_error"]):
        lines.append("  {:10.4g}      {:12.3e}               {:10.3e}".format(*row))
    lines.append(f"  observed order: gap {v['order']:.3f} (expect 2), direction {v['direction_order']:.3f}")
    lines.append("(d) cost: points projected per second (best of repeats)")
    lines.append(f"  {'seabed':30s} {'points':>7s} {'build s':>8s} {'cold pts/s':>11s} {'warm pts/s':>11s} {'warm ms':>8s}")
    for r in results["cost"]:
        cold = "-" if r["cold_points_per_s"] is None else f"{r['cold_points_per_s']:.3g}"
        lines.append(f"  {r['seabed']:30s} {r['points']:7d} {r['build_s']:8.3f} {cold:>11s} "
                     f"{r['warm_points_per_s']:11.3g} {1e3 * r['warm_s']:8.3f}")
    lines.append(f"wall time {results['wall_time_s']:.1f} s")
    return "\n".join(lines)


def figures(results, out):
    """PNG figures of (b), (c) and (d) in directory out."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    c, v = results["continuity"], results["convergence"]
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ax[0].loglog(c["path_spacing_m"], c["path_max_jump_vertex_normals"], "o-", label="vertex normals (Eq. 10)")
    ax[0].loglog(c["path_spacing_m"], c["path_max_jump_face_normals"], "s--", label="face normals")
    ax[0].set(xlabel="sample spacing [m]", ylabel="max |d_P jump|", title="along a path")
    ax[1].loglog(c["eps_m"], c["edge_jump"], "o-", label="across an edge")
    ax[1].loglog(c["eps_m"], c["vertex_spread"], "^-", label="around a vertex")
    ax[1].loglog(c["eps_m"], c["vertex_face_normal_spread"], "s--", label="face normals at the vertex")
    ax[1].set(xlabel="distance eps [m]", ylabel="d_P difference", title="at an edge and a vertex")
    for a in ax:
        a.legend()
        a.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "continuity.png", dpi=120)
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.loglog(v["mesh_size_m"], v["gap_error_m"], "o-", label=f"d_G, order {v['order']:.2f}")
    ax.loglog(v["mesh_size_m"], v["direction_error"], "^-", label=f"d_P, order {v['direction_order']:.2f}")
    ax.set(xlabel="mesh size [m]", ylabel="max error", title="sphere R = 100 m")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "convergence.png", dpi=120)
    fig, ax = plt.subplots(figsize=(7, 4))
    names = list(dict.fromkeys(r["seabed"] for r in results["cost"]))
    for name in names:
        rows = [r for r in results["cost"] if r["seabed"] == name]
        ax.loglog([r["points"] for r in rows], [r["warm_points_per_s"] for r in rows], "o-", label=name)
    ax.set(xlabel="points per call", ylabel="points per second (warm)", title="projection cost")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "cost.png", dpi=120)
    plt.close("all")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="small sizes, a few seconds")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for results.json and PNGs")
    args = parser.parse_args(argv)
    results = run(fast=args.fast)
    print(report(results))
    args.out.mkdir(parents=True, exist_ok=True)
    write_json(args.out / "results.json", results, private=True)
    figures(results, args.out)
    print(f"wrote {args.out / 'results.json'} and 3 figures")


if __name__ == "__main__":
    main()
