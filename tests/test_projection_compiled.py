"""The compiled seabed projections (numba) against their numpy references.

``TriangulatedSurface`` walks and evaluates in ``_vertex_normal_jit`` and leaves the points
its walk does not place to the numpy search; ``DepthGrid`` evaluates in ``grid._project``.
Both must give the numpy answer (``compiled = False``) on every path: cold and warm starts,
walks across triangles, far jumps, points beyond the mesh's edge (the edge rule), far above
rough ground, curved and planar meshes of either winding, lines sharing a seabed.

Tolerances: 1e-12 (absolute, plus 1e-12 relative for the large derivatives near focal
points): both solve the same cubic from different starts and the compiled evaluation
multiplies by reciprocals, so they differ by round-off (~1e-14 m measured on 100 m
coordinates); the grid's arithmetic is the same operation for operation, so bit for bit.
"""

import numpy as np
import pytest
from scipy.spatial import Delaunay

from cablefem.geometry import DepthGrid, TriangulatedSurface
from cablefem.geometry.planes import _grid_triangles

FIELDS = ("gap", "direction", "closest", "gap_gradient", "direction_gradient")


def _pair(vertices, triangles):
    """The same surface twice: compiled, and the numpy reference."""
    compiled, reference = TriangulatedSurface(vertices, triangles), TriangulatedSurface(vertices, triangles)
    reference.compiled = False
    return compiled, reference


def _wavy(xy, amplitude):
    k = 2.0 * np.pi / 40.0
    return -50.0 + amplitude * np.sin(k * xy[:, 0]) * np.cos(k * xy[:, 1])


def _mesh(kind, rng):
    """Vertices (m, 3) and triangles (k, 3) of a test surface over [-50, 50]^2 m."""
    if kind.startswith("grid"):
        x = np.linspace(-50.0, 50.0, 21)
        xx, yy = np.meshgrid(x, x)
        xy = np.column_stack([xx.ravel(), yy.ravel()])
        triangles = _grid_triangles(21, 21)
    else:
        corners = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]) * 50.0
        xy = np.vstack([corners, rng.uniform(-50.0, 50.0, (250, 2))])
        triangles = Delaunay(xy).simplices
    if kind.endswith("tilted"):
        z = -60.0 + 0.15 * xy[:, 0] - 0.25 * xy[:, 1]
    elif kind.endswith("flat"):
        z = np.full(len(xy), -50.0)
    else:
        z = _wavy(xy, 8.0 if kind.endswith("rough") else 3.0)
    return np.column_stack([xy, z]), triangles


def _assert_same(got, want, what):
    for field in FIELDS:
        a, b = getattr(got, field), getattr(want, field)
        assert a.shape == b.shape, (what, field)
        assert np.allclose(a, b, rtol=1e-12, atol=1e-12), (what, field, np.abs(a - b).max())


def _points(surface, rng, count=160):
    """Points near the surface, beyond its edge, and far above it (n, 3) [m]."""
    near = rng.uniform(-48.0, 48.0, (count, 2))
    beyond = rng.uniform(-80.0, 80.0, (count // 4, 2))
    xy = np.vstack([near, beyond])
    above = np.concatenate([rng.uniform(-1.0, 3.0, count), rng.uniform(-2.0, 4.0, count // 4)])
    z = surface.elevation(xy) + above
    points = np.column_stack([xy, z])
    points[:8, 2] += 60.0  # far above: far roots, crossing prisms
    return points


@pytest.mark.parametrize("kind", ["grid wavy", "grid tilted", "grid flat",
                                  "irregular wavy", "irregular rough", "irregular tilted"])
@pytest.mark.parametrize("flip", [False, True])
def test_compiled_projection_equals_numpy_cold_warm_and_after_jumps(kind, flip, rng):
    vertices, triangles = _mesh(kind, rng)
    compiled, reference = _pair(vertices, triangles[:, ::-1] if flip else triangles)
    points = _points(reference, rng)
    for call in range(6):
        if call == 4:  # a far jump: most points leave their triangles by several triangles
            points = points + np.array([17.0, -11.0, 0.5])
        elif call:  # Newton iterations and time steps: small moves, some across edges
            points = points + rng.normal(0.0, 0.2, points.shape)
        _assert_same(compiled.project(points), reference.project(points), (kind, flip, call))
        lean, want = compiled.project(points, derivatives=False), reference.project(points, derivatives=False)
        assert np.allclose(lean.gap, want.gap, rtol=0.0, atol=1e-12)
        assert np.allclose(lean.direction, want.direction, rtol=0.0, atol=1e-12)
        assert np.allclose(compiled.gap_only(points), reference.gap_only(points), rtol=0.0, atol=1e-12)


def test_compiled_locate_equals_numpy_locate(rng):
    compiled, reference = _pair(*_mesh("irregular rough", rng))
    points = _points(reference, rng)
    for shift in (0.0, 0.3):
        points = points + shift
        got, want = compiled.locate(points), reference.locate(points)
        assert np.array_equal(got[0], want[0])  # the same triangle
        for a, b in zip(got[1:], want[1:]):
            assert np.allclose(a, b, rtol=0.0, atol=1e-12)


def test_compiled_projection_equals_numpy_on_a_notched_mesh_and_beyond_its_edge(rng):
    vertices, triangles = _mesh("grid wavy", rng)
    centroid = vertices[triangles].mean(axis=1)
    triangles = triangles[~((centroid[:, 0] > 0) & (centroid[:, 1] > 0))]  # not convex
    compiled, reference = _pair(vertices, triangles)
    assert not compiled.convex_footprint
    points = np.column_stack([rng.uniform(-70.0, 70.0, (300, 2)), rng.uniform(-54.0, -46.0, 300)])
    for _ in range(3):
        points = points + rng.normal(0.0, 0.5, points.shape)
        _assert_same(compiled.project(points), reference.project(points), "notched")


def test_lines_sharing_a_seabed_get_the_numpy_answer(rng):
    compiled, reference = _pair(*_mesh("irregular wavy", rng))
    lines = [_points(reference, rng, count) for count in (80, 80, 120)]
    for _ in range(3):  # three lines, two of as many points, alternate on one seabed
        for k, points in enumerate(lines):
            lines[k] = points + rng.normal(0.0, 0.1, points.shape)
            _assert_same(compiled.project(lines[k]), reference.project(lines[k]), k)


def test_a_line_moving_as_in_a_time_step_needs_no_numpy_search(rng, monkeypatch):
    surface = TriangulatedSurface(*_mesh("irregular wavy", rng))
    x = np.linspace(-40.0, 30.0, 80)  # clear of the mesh's edge: points there may take the edge rule
    xy = np.column_stack([x, 10.0 * np.sin(x / 20.0)])
    points = np.column_stack([xy, surface.elevation(xy) + 0.05])
    surface.project(points)  # cold: the numpy search may help
    searches = []
    search = surface._locate
    monkeypatch.setattr(surface, "_locate", lambda *args: searches.append(1) or search(*args))
    for _ in range(20):  # 20 steps of 0.3 m: points cross edges, and the walk follows them
        points = points + np.array([0.3, 0.1, 0.0])
        surface.project(points)
    assert not searches


@pytest.mark.parametrize("uniform", [True, False])
def test_compiled_grid_projection_equals_numpy_bit_for_bit(uniform, rng):
    x = np.linspace(-100.0, 100.0, 12) if uniform else np.sort(rng.uniform(-100.0, 100.0, 12))
    y = np.linspace(-50.0, 50.0, 9) if uniform else np.sort(rng.uniform(-50.0, 50.0, 9))
    grid = DepthGrid(x, y, rng.uniform(-60.0, -40.0, (9, 12)))
    reference = DepthGrid(x, y, grid.z)
    reference.compiled = False
    points = np.column_stack([rng.uniform(-130.0, 130.0, 400), rng.uniform(-70.0, 70.0, 400),
                              rng.uniform(-70.0, -30.0, 400)])
    points[:5, 0], points[5:10, 1] = x[3], y[2]  # on grid lines
    points[10, :2], points[11, :2] = (x[0], y[-1]), (x[-1], y[0])  # on corners
    got, want = grid.project(points), reference.project(points)
    for field in FIELDS:
        assert np.array_equal(getattr(got, field), getattr(want, field)), field
    assert np.array_equal(grid.gap_only(points), reference.gap_only(points))
