"""Triangulated seabeds with the vertex-normal projection (desire2023 Sec. 2.2.2.2, Eq. 10) and
their readers (meshio surfaces, xyz soundings).

Tolerances: 1e-12 m for plane exactness (coordinates of order 100 m, so a few hundred ulps);
1e-6 relative for central differences with a 1e-6 m step (round-off ~1e-16 x 100 / 1e-6 = 1e-8,
truncation ~1e-12); observed orders from the fast verification in ``verification/projection``.
"""

import sys
from pathlib import Path

import meshio
import numpy as np
import pytest
from scipy.spatial import Delaunay

from cablefem.errors import InputError
from cablefem.geometry import Plane, TriangulatedSurface
from cablefem.geometry.planes import _grid_triangles
from cablefem.geometry.readers import meshio_surface, xyz

from verification.projection import run as study

FIELDS = ("gap", "direction", "closest", "gap_gradient", "direction_gradient")


def wavy(xy):
    """z = -50 + 3 sin(kx) cos(ky), wavelength 40 m [m]."""
    k = 2 * np.pi / 40.0
    return -50.0 + 3.0 * np.sin(k * xy[:, 0]) * np.cos(k * xy[:, 1])


def grid_mesh(height, n=21, extent=50.0):
    x = np.linspace(-extent, extent, n)
    xx, yy = np.meshgrid(x, x)
    xy = np.column_stack([xx.ravel(), yy.ravel()])
    return np.column_stack([xy, height(xy)]), _grid_triangles(n, n)


def irregular_mesh(height, rng, count=200, extent=50.0):
    corners = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]) * extent
    xy = np.vstack([corners, rng.uniform(-extent, extent, (count, 2))])
    return np.column_stack([xy, height(xy)]), Delaunay(xy).simplices


@pytest.fixture
def tilted():
    return Plane([3.0, -2.0, -60.0], [0.15, -0.25, 1.0])


@pytest.fixture
def wavy_surface():
    return TriangulatedSurface(*grid_mesh(wavy))


def test_tilted_plane_projects_exactly_as_the_plane_for_either_winding(tilted, rng):
    vertices, triangles = irregular_mesh(tilted.elevation, rng)
    points = np.column_stack([rng.uniform(-49, 49, (500, 2)), rng.uniform(-90, -30, 500)])
    beyond = np.column_stack([rng.uniform(-90, 90, (500, 2)), rng.uniform(-90, -30, 500)])
    for winding in (triangles, triangles[:, ::-1]):
        surface = TriangulatedSurface(vertices, winding)
        for p in (points, beyond):  # beyond the edge the surface goes on as its tangent plane
            ours, exact = surface.project(p), tilted.project(p)
            for field in FIELDS:
                assert np.abs(getattr(ours, field) - getattr(exact, field)).max() < 1e-12, field


def test_gap_sign_and_direction_do_not_depend_on_the_winding(rng):
    vertices, triangles = grid_mesh(wavy)
    up, down = TriangulatedSurface(vertices, triangles), TriangulatedSurface(vertices, triangles[:, ::-1])
    xy = rng.uniform(-45, 45, (400, 2))
    offset = rng.uniform(0.05, 2.0, 400) * rng.choice([-1.0, 1.0], 400)
    points = np.column_stack([xy, up.elevation(xy) + offset])  # above or below the facets
    a, b = up.project(points), down.project(points)
    assert np.array_equal(np.sign(a.gap), np.sign(offset))  # above > 0, buried < 0
    assert np.all(a.direction[:, 2] > 0.8)  # towards the water
    assert np.abs(up.gap_only(points) - a.gap).max() < 1e-12
    for field in FIELDS:
        assert np.allclose(getattr(a, field), getattr(b, field), rtol=0, atol=1e-12), field


def test_gap_is_zero_on_the_surface_and_closest_is_the_point(wavy_surface, rng):
    corners = wavy_surface.vertices[wavy_surface.triangles[:200]]
    weights = rng.dirichlet(np.ones(3), 200)
    on_faces = np.einsum("kic,ki->kc", corners, weights)
    for points in (on_faces, wavy_surface.vertices):
        proj = wavy_surface.project(points)
        assert np.abs(proj.gap).max() < 1e-12
        assert np.abs(proj.closest - points).max() < 1e-12


@pytest.mark.parametrize("spread", [(5.0, 45.0), (-70.0, 70.0)], ids=["inside", "beyond-the-edge"])
def test_gradients_match_central_differences(wavy_surface, rng, spread):
    xy = rng.uniform(*spread, (300, 2))
    points = np.column_stack([xy, wavy(np.clip(xy, -50, 50)) + rng.uniform(-2.0, 2.0, 300)])
    step = 1e-6
    exact = wavy_surface.project(points)
    assert np.abs(exact.direction_gradient).max() > 0.05  # curved: the test has teeth
    for axis in range(3):
        shift = np.zeros(3)
        shift[axis] = step
        plus, minus = wavy_surface.project(points + shift), wavy_surface.project(points - shift)
        gap = (plus.gap - minus.gap) / (2 * step)
        direction = (plus.direction - minus.direction) / (2 * step)
        assert np.abs(gap - exact.gap_gradient[:, axis]).max() < 1e-6
        assert np.abs(direction - exact.direction_gradient[:, :, axis]).max() < 1e-6


def test_warm_starts_give_the_cold_answer_for_lines_sharing_a_seabed(wavy_surface, rng):
    lines = [np.column_stack([rng.uniform(-60, 60, (300, 2)), rng.uniform(-55, -45, 300)]) for _ in range(2)]
    for _ in range(3):  # two lines of as many points alternate, each moving a little
        for k, points in enumerate(lines):
            lines[k] = points + rng.normal(0.0, 0.05, points.shape)
            warm = wavy_surface.project(lines[k])
            cold = TriangulatedSurface(wavy_surface.vertices, wavy_surface.triangles).project(lines[k])
            for field in FIELDS:
                assert np.allclose(getattr(warm, field), getattr(cold, field), rtol=0, atol=1e-9), field


def test_l_shaped_mesh_projects_smoothly_and_the_same_warm_or_cold(rng):
    vertices, triangles = grid_mesh(wavy)
    centroid = vertices[triangles].mean(axis=1)
    triangles = triangles[~((centroid[:, 0] > 0) & (centroid[:, 1] > 0))]  # a notch: not convex
    surface = TriangulatedSurface(vertices, triangles)
    assert not surface.convex_footprint
    points = np.column_stack([rng.uniform(-70, 70, (600, 2)), rng.uniform(-54, -46, 600)])
    for _ in range(2):
        points = points + rng.normal(0.0, 0.05, points.shape)
        warm = surface.project(points)
        cold = TriangulatedSurface(vertices, triangles).project(points)
        assert np.abs(warm.gap - cold.gap).max() < 1e-9
    step = 1e-6
    for axis in range(3):
        shift = np.zeros(3)
        shift[axis] = step
        gap = (surface.project(points + shift).gap - surface.project(points - shift).gap) / (2 * step)
        assert np.abs(gap - warm.gap_gradient[:, axis]).max() < 1e-6


def test_direction_is_continuous_along_a_path_across_edges_and_around_vertices():
    result = study.continuity(np.random.default_rng(0), fast=True)
    assert result["path_triangles_crossed"] > 30
    # jumps shrink linearly with the spacing (rate 1); face normals keep jumping
    assert result["path_rate"] >= 0.9
    assert result["edge_rate"] >= 0.9 and result["vertex_rate"] >= 0.9
    assert result["edge_jump"][-1] < 1e-5 and result["vertex_spread"][-1] < 1e-5
    assert min(result["path_max_jump_face_normals"]) > 0.1
    assert min(result["vertex_face_normal_spread"]) > 0.05


def test_gap_converges_at_order_2_to_a_sphere():
    result = study.convergence(np.random.default_rng(0), fast=True)
    assert result["order"] >= 1.8
    assert result["gap_error_m"][-1] < 0.02  # R = 100 m sphere, 1.6 m mesh


def test_plane_study_numbers_are_round_off():
    result = study.plane_exactness(np.random.default_rng(0))
    assert max(v for errors in result.values() for v in errors.values()) < 1e-12


def test_elevation_interpolates_the_triangles_and_clamps_beyond(rng, tilted):
    surface = TriangulatedSurface(*irregular_mesh(tilted.elevation, rng))
    xy = rng.uniform(-49, 49, (300, 2))
    assert np.abs(surface.elevation(xy) - tilted.elevation(xy)).max() < 1e-12
    vertices, triangles = grid_mesh(wavy)
    grid = TriangulatedSurface(vertices, triangles)
    assert np.abs(grid.elevation(vertices[:, :2]) - vertices[:, 2]).max() < 1e-12
    beyond = grid.elevation(np.array([[80.0, 0.0], [50.0, 0.0]]))
    assert beyond[0] == pytest.approx(beyond[1], abs=1e-12)  # flat beyond the edge


def test_surface_bounds_describe_and_vertices(wavy_surface):
    points, triangles = wavy_surface.surface(((-10.0, 10.0), (-10.0, 10.0)))
    assert 0 < len(triangles) < len(wavy_surface.triangles)
    assert triangles.max() == len(points) - 1
    assert np.all(np.abs(points[:, :2]).max(axis=1) <= 15.0 + 1e-9)
    assert "441 vertices, 800 triangles" in wavy_surface.describe()
    assert wavy_surface.vertices.shape == (441, 3)


@pytest.mark.parametrize("case, vertices, triangles, words", [
    ("vertical face", [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 1, 0]], [[0, 1, 2], [0, 1, 3]], "vertical"),
    ("zero area", [[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1, 2]], "zero area"),
    ("folded over", [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0.5, 0.6, 0.1]], [[0, 1, 2], [0, 1, 3]], "folds over"),
    ("non-manifold", [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0.5, -1, 0], [0.7, -0.5, 0.3]],
     [[0, 1, 2], [0, 3, 1], [0, 4, 1]], "not a manifold"),
    ("nan", [[0, 0, 0], [1, 0, np.nan], [0, 1, 0]], [[0, 1, 2]], "non-finite"),
    ("bad index", [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 3]], "vertex indices"),
])
def test_malformed_surfaces_raise_input_errors(case, vertices, triangles, words):
    with pytest.raises(InputError, match=words):
        TriangulatedSurface(np.array(vertices, dtype=float), np.array(triangles))


# -- readers -------------------------------------------------------------------

@pytest.mark.parametrize("suffix", ["stl", "obj", "vtu", "ply"])
def test_meshio_round_trip_gives_the_same_projection(tmp_path, wavy_surface, rng, suffix):
    path = tmp_path / f"seabed.{suffix}"
    meshio.write(path, meshio.Mesh(wavy_surface.vertices, [("triangle", wavy_surface.triangles)]))
    surface = meshio_surface.read(path)
    assert len(surface.vertices) == len(wavy_surface.vertices)  # STL's repeated corners merged
    assert len(surface.triangles) == len(wavy_surface.triangles)
    points = np.column_stack([rng.uniform(-45, 45, (200, 2)), rng.uniform(-53, -47, 200)])
    tolerance = 1e-5 if suffix == "stl" else 1e-12  # binary STL stores float32
    assert np.abs(surface.project(points).gap - wavy_surface.project(points).gap).max() < tolerance


def test_meshio_reader_splits_quads(tmp_path):
    vertices, _ = grid_mesh(wavy, n=5)
    quads = np.array([[j * 5 + i, j * 5 + i + 1, j * 5 + i + 6, j * 5 + i + 5]
                      for j in range(4) for i in range(4)])
    meshio.write(tmp_path / "quads.vtu", meshio.Mesh(vertices, [("quad", quads)]))
    assert len(meshio_surface.read(tmp_path / "quads.vtu").triangles) == 32


def test_xyz_round_trip_with_commas_and_comments(tmp_path, rng):
    xy = rng.uniform(-50, 50, (60, 2))
    points = np.column_stack([xy, wavy(xy)])
    rows = [[repr(float(v)) for v in point] for point in points]  # repr: exact round trip
    lines = ["# x y z soundings", ""] + [", ".join(row) + f"  # ping {k}" if k % 2 else " ".join(row)
                                           for k, row in enumerate(rows)]
    (tmp_path / "s.xyz").write_text("\n".join(lines) + "\n")
    surface = xyz.read(tmp_path / "s.xyz")
    assert np.array_equal(surface.vertices, points)
    reference = TriangulatedSurface(points, Delaunay(xy).simplices)
    probe = np.column_stack([rng.uniform(-30, 30, (100, 2)), rng.uniform(-53, -47, 100)])
    assert np.abs(surface.project(probe).gap - reference.project(probe).gap).max() < 1e-12


def _one_line_naming(error, path):
    message = str(error.value)
    assert "\n" not in message and str(path) in message
    return message


MESHIO_DEFECTS = {
    "degenerate": ([[0, 0, -1], [1, 0, -1], [2, 0, -1], [0, 1, -1]], [[0, 1, 2], [0, 1, 3]], "zero area"),
    "repeated corner": ([[0, 0, -1], [1, 0, -1], [0, 1, -1]], [[0, 1, 1]], "degenerate"),
    "non-manifold": ([[0, 0, -1], [1, 0, -1], [0, 1, -1], [0.5, -1, -1], [0.7, -0.5, -0.7]],
                     [[0, 1, 2], [0, 3, 1], [0, 4, 1]], "not a manifold"),
    "folded": ([[0, 0, -1], [1, 0, -1], [0, 1, -1], [0.5, 0.6, -0.9]], [[0, 1, 2], [0, 1, 3]], "folds over"),
    "nan": ([[0, 0, -1], [1, 0, np.nan], [0, 1, -1]], [[0, 1, 2]], "non-finite"),
    "doubled": ([[0, 0, -1], [1, 0, -1], [0, 1, -1]], [[0, 1, 2], [0, 2, 1]], "repeats"),
}


@pytest.mark.parametrize("case", sorted(MESHIO_DEFECTS))
def test_malformed_mesh_files_raise_one_line_naming_the_file(tmp_path, case):
    vertices, triangles, words = MESHIO_DEFECTS[case]
    path = tmp_path / f"{case.replace(' ', '_')}.vtu"
    meshio.write(path, meshio.Mesh(np.array(vertices, dtype=float), [("triangle", np.array(triangles))]))
    with pytest.raises(InputError) as error:
        meshio_surface.read(path)
    assert words in _one_line_naming(error, path)


def test_unreadable_missing_and_triangle_free_mesh_files_raise(tmp_path):
    garbage = tmp_path / "garbage.vtu"
    garbage.write_text("this is not a mesh\n")
    lines = tmp_path / "lines.vtu"
    meshio.write(lines, meshio.Mesh(np.eye(3), [("line", np.array([[0, 1], [1, 2]]))]))
    for path, words in ((garbage, "cannot read"), (tmp_path / "missing.stl", "no such file"),
                        (lines, "no triangles")):
        with pytest.raises(InputError) as error:
            meshio_surface.read(path)
        assert words in _one_line_naming(error, path)


@pytest.mark.parametrize("text, words", [
    ("0 0 -1\n1 0 -1\n", "at least 3 points"),
    ("0 0 -1\n1 0 -1\n0 1 -1\n1 0 -2\n", "lines 2 and 4 give the same (x, y)"),
    ("0 0 -1\n1 1 -1\n2 2 -3\n", "on one line"),
    ("0 0 -1\n1 0 -1\n0 1 abc\n", "line 3"),
    ("0 0 -1\n1 0\n0 1 -1\n", "line 2"),
    ("0 0 -1\n1 0 nan\n0 1 -1\n", "line 2"),
], ids=["too few", "duplicate xy", "collinear", "not a number", "two fields", "nan"])
def test_malformed_soundings_raise_one_line_naming_file_and_row(tmp_path, text, words):
    path = tmp_path / "bad.xyz"
    path.write_text(text)
    with pytest.raises(InputError) as error:
        xyz.read(path)
    assert words in _one_line_naming(error, path)


def test_registry_reads_meshes_and_soundings(tmp_path, wavy_surface):
    from cablefem.geometry.readers import read_seabed

    meshio.write(tmp_path / "s.obj", meshio.Mesh(wavy_surface.vertices, [("triangle", wavy_surface.triangles)]))
    np.savetxt(tmp_path / "s.xyz", wavy_surface.vertices)
    for name, kind in (("s.obj", "mesh"), ("s.xyz", "points")):
        seabed = read_seabed(tmp_path / name, kind)
        assert isinstance(seabed, TriangulatedSurface) and len(seabed.vertices) == 441
