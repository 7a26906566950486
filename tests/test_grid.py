"""DepthGrid projection, the bathymetry readers, read_seabed, simplify and seabed.vtu."""

import numpy as np
import pytest

from cablefem.errors import InputError
from cablefem.geometry import (DepthGrid, Horizontal, Plane, TriangulatedSurface, read_seabed,
                               simplify, write_seabed_vtu)
from cablefem.geometry.readers import FORMATS, guess_kind, moordyn_c, moordyn_f, sniff_grid


def curved_grid():
    """A 5 x 4 grid with uneven spacing and a different twist in every cell."""
    x = np.array([-100.0, -40.0, 0.0, 35.0, 120.0])
    y = np.array([-60.0, -10.0, 30.0, 90.0])
    gx, gy = np.meshgrid(x, y)
    z = -80.0 + 0.05 * gx - 0.03 * gy + 4.0 * np.sin(gx / 30.0) * np.cos(gy / 25.0)
    return DepthGrid(x, y, z)


def cell_interior_points(grid, rng, count=40):
    """Points (count, 3) strictly inside cells (away from grid lines) and near the seabed."""
    i = rng.integers(0, len(grid.x) - 1, count)
    j = rng.integers(0, len(grid.y) - 1, count)
    u, v = rng.uniform(0.1, 0.9, (2, count))
    x = grid.x[i] + u * (grid.x[i + 1] - grid.x[i])
    y = grid.y[j] + v * (grid.y[j + 1] - grid.y[j])
    z = grid.elevation(np.column_stack([x, y])) + rng.uniform(-3.0, 3.0, count)
    return np.column_stack([x, y, z])


# -- projection ---------------------------------------------------------------

@pytest.mark.parametrize("angle, azimuth", [(0.0, 0.0), (0.2, 0.0), (0.3, 2.0), (0.5, -2.6)])
def test_planar_grid_projection_equals_the_plane_exactly(angle, azimuth):
    # A bilinear patch of a plane is the plane, so every output must agree with
    # the closed-form point-to-plane projection to rounding (1e-12 relative).
    plane = Plane.from_slope([3.0, -2.0, -90.0], angle, azimuth)
    x, y = np.linspace(-200, 300, 6), np.linspace(-150, 100, 4)
    gx, gy = np.meshgrid(x, y)
    grid = DepthGrid(x, y, plane.elevation(np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape))
    rng = np.random.default_rng(7)
    points = np.column_stack([rng.uniform(-199, 299, 50), rng.uniform(-149, 99, 50),
                              rng.uniform(-150, -20, 50)])
    got, want = grid.project(points), plane.project(points)
    assert np.allclose(got.gap, want.gap, rtol=0, atol=1e-12 * 300)
    assert np.allclose(got.direction, want.direction, rtol=0, atol=1e-12)
    assert np.allclose(got.closest, want.closest, rtol=0, atol=1e-12 * 300)
    assert np.allclose(got.gap_gradient, want.gap_gradient, rtol=0, atol=1e-12)
    assert np.allclose(got.direction_gradient, 0.0, rtol=0, atol=1e-12)
    assert np.allclose(grid.gap_only(points), want.gap, rtol=0, atol=1e-12 * 300)
    assert np.allclose(plane.gap_only(got.closest), 0.0, atol=1e-10)


def test_gap_is_moordyn_vertical_height_times_n_z():
    grid = curved_grid()
    points = cell_interior_points(grid, np.random.default_rng(1))
    projection = grid.project(points)
    height = points[:, 2] - grid.elevation(points[:, :2])
    assert np.allclose(projection.gap, height * projection.direction[:, 2], rtol=1e-14, atol=0)
    assert np.allclose(np.linalg.norm(projection.direction, axis=1), 1.0, rtol=0, atol=1e-14)
    assert np.allclose(projection.closest, points - projection.gap[:, None] * projection.direction)


def central_differences(function, points, step=1e-5):
    """d function / d points by central differences: (n, ..., 3)."""
    columns = []
    for b in range(3):
        shift = np.zeros(3)
        shift[b] = step
        columns.append((function(points + shift) - function(points - shift)) / (2 * step))
    return np.stack(columns, axis=-1)


def test_gradients_match_central_differences_on_a_curved_grid():
    # Central differences with h = 1e-5 m have truncation ~h^2 * third derivative
    # and rounding ~1e-16 * 100 / h ~ 1e-9: 1e-7 separates them from any
    # missing term (the n(x, y) dependence is ~1e-3 here).
    grid = curved_grid()
    points = cell_interior_points(grid, np.random.default_rng(2))
    projection = grid.project(points)
    assert np.abs(projection.direction_gradient).max() > 1e-4  # the test has teeth
    gap_fd = central_differences(lambda p: grid.project(p).gap, points)
    direction_fd = central_differences(lambda p: grid.project(p).direction, points)
    assert np.allclose(projection.gap_gradient, gap_fd, rtol=0, atol=1e-7)
    assert np.allclose(projection.direction_gradient, direction_fd, rtol=0, atol=1e-7)


def test_outside_the_grid_the_seabed_is_clamped_to_the_edge():
    grid = curved_grid()
    edge = grid.elevation([[120.0, 0.0], [-100.0, 90.0], [0.0, -60.0]])
    beyond = grid.elevation([[500.0, 0.0], [-400.0, 300.0], [0.0, -999.0]])
    assert np.array_equal(edge, beyond)
    # Beyond x_max the surface does not vary with x: no x-slope, and the
    # derivatives still match finite differences there.
    points = np.array([[300.0, 10.0, -70.0], [-500.0, -80.0, -75.0], [50.0, 400.0, -60.0]])
    projection = grid.project(points)
    assert projection.direction[0, 0] == 0.0 and projection.direction[1, :2].tolist() == [0.0, 0.0]
    assert projection.direction[2, 1] == 0.0
    gap_fd = central_differences(lambda p: grid.project(p).gap, points)
    assert np.allclose(projection.gap_gradient, gap_fd, rtol=0, atol=1e-7)


@pytest.mark.parametrize("x, y, z, key, words", [
    ([0, 10, 10, 20], [0, 1], np.zeros((2, 4)), "x", "x[2] = 10"),
    ([0, 10], [5, 1, 7], np.zeros((3, 2)), "y", "y[1] = 1"),
    ([0, 10], [0, 1], [[0, 0], [0, np.nan]], "z", "x = 10, y = 1"),
    ([0, 10], [0, 1], np.zeros((2, 3)), "z", "(2, 2)"),
    ([0], [0, 1], np.zeros((2, 1)), "x", "at least 2"),
])
def test_bad_grid_is_refused_naming_the_axis_or_node(x, y, z, key, words):
    with pytest.raises(InputError) as error:
        DepthGrid(x, y, z)
    assert error.value.key == key and words in str(error.value)


def test_surface_is_the_grid_and_its_clamped_extension():
    grid = curved_grid()
    points, triangles = grid.surface()
    assert points.shape == (20, 3) and triangles.shape == (2 * 4 * 3, 3)
    assert np.array_equal(points, grid.vertices)
    points, triangles = grid.surface(((-300.0, 50.0), (-60.0, 200.0)))
    assert set(np.unique(points[:, 0])) == {-300.0, -100.0, -40.0, 0.0, 35.0, 50.0}
    assert np.allclose(points[:, 2], grid.elevation(points[:, :2]))
    assert "grid 5 x 4" in grid.describe()


# -- readers ------------------------------------------------------------------

WRITERS = {"moordyn-c": moordyn_c.write, "moordyn-f": moordyn_f.write}


@pytest.mark.parametrize("fmt", sorted(WRITERS))
def test_reader_round_trip_gives_the_same_grid(tmp_path, fmt):
    grid = curved_grid()
    path = tmp_path / "bathymetry.txt"
    WRITERS[fmt](path, grid)
    assert sniff_grid(path) == fmt and guess_kind(path) == "grid"
    for kind in (None, "grid", fmt):
        back = read_seabed(path, kind)
        assert isinstance(back, DepthGrid)
        assert np.array_equal(back.x, grid.x) and np.array_equal(back.y, grid.y)
        assert np.array_equal(back.z, grid.z)


def test_both_layouts_of_one_bathymetry_give_the_same_grid(tmp_path):
    # Hand-written, rows of the C layout shuffled: MoorDyn-C takes any order.
    (tmp_path / "c.txt").write_text("3 2\n0 50 100\n-10 10\n100 10 -95\n0 -10 -80.5\n"
                                    "50 -10 -82\n0 10 -81\n100 -10 -90\n\n50 10 -88.25\n")
    (tmp_path / "f.txt").write_text("--- MoorDyn Bathymetry Input File ---\nnGridX 3\nnGridY 2\n"
                                    "      0   50    100\n-10 80.5 82 90\n10  81 88.25  95\n")
    c, f = read_seabed(tmp_path / "c.txt"), read_seabed(tmp_path / "f.txt")
    assert np.array_equal(c.z, f.z) and np.array_equal(c.x, f.x) and np.array_equal(c.y, f.y)
    assert c.z[1, 2] == -95.0 and c.z[0, 0] == -80.5  # elevation, negative below water


def test_moorpy_reads_our_moordyn_f_file_as_we_do(tmp_path):
    helpers = pytest.importorskip("moorpy.helpers")
    grid = curved_grid()
    moordyn_f.write(tmp_path / "bath.txt", grid)
    xs, ys, depths = helpers.readBathymetryFile(str(tmp_path / "bath.txt"))
    assert np.array_equal(xs, grid.x) and np.array_equal(ys, grid.y)
    assert np.array_equal(-np.asarray(depths), grid.z)  # MoorPy: depth positive down


def test_moordyn_c_reads_our_file_and_interpolates_as_we_do(tmp_path):
    moordyn = pytest.importorskip("moordyn")
    # Values exact in float32 (MoorDyn parses with stof), so any difference is
    # the interpolation, not the parsing: 1e-9 m.
    x, y = np.array([-100.0, 0.0, 50.0, 150.0]), np.array([-50.0, 25.0, 60.0])
    z = -80.0 + 0.25 * np.arange(12.0).reshape(3, 4) ** 1.0 * np.array([1, -1, 1, -1])
    grid = DepthGrid(x, y, z)
    moordyn_c.write(tmp_path / "sea.txt", grid)
    (tmp_path / "lines.txt").write_text(f"""--- MoorDyn Input File ---
cablefem seafloor check
---------------------- LINE TYPES -----------------------------------
TypeName Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx
(name) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)
chain 0.1 100.0 1e8 -1.0 0 1.2 1.0 0.2 0.0
---------------------- POINTS ---------------------------------------
ID Attachment X Y Z Mass Volume CdA Ca
(#) (-) (m) (m) (m) (kg) (m^3) (m^2) (-)
1 Fixed -50.0 0.0 -60.0 0 0 0 0
2 Fixed 50.0 0.0 -10.0 0 0 0 0
---------------------- LINES ----------------------------------------
ID LineType AttachA AttachB UnstrLen NumSegs LineOutputs
(#) (name) (#) (#) (m) (-) (-)
1 chain 1 2 120.0 10 -
---------------------- OPTIONS --------------------------------------
0.001 dtM
100.0 WtrDpth
{tmp_path / 'sea.txt'} SeafloorFile
--------------------- need this line -------------------------------
""")
    system = moordyn.Create(str(tmp_path / "lines.txt"))
    try:
        seafloor = moordyn.GetSeafloor(system)
        xy = np.array([[-100, -50], [12.5, -7.75], [49.5, 59.0], [140, -20], [300, 100], [-300, -300]])
        theirs = [moordyn.GetDepthAt(seafloor, float(a), float(b)) for a, b in xy]
    finally:
        moordyn.Close(system)
    assert np.allclose(theirs, grid.elevation(xy), rtol=0, atol=1e-9)


def malformed(fmt, case):
    """Text of a malformed file of format fmt and the line number its error must name."""
    if fmt == "moordyn-c":
        good = ["3 2", "0 50 100", "-10 10", "0 -10 -80", "50 -10 -82", "100 -10 -90",
                "0 10 -81", "50 10 -88", "100 10 -95"]
        edits = {"off-grid row": (5, "50.5 -10 -82", "50.5"),
                 "hole": (9, None, "x = 100, y = 10"),
                 "duplicate": (9, "50 10 -88", "lines 8 and 9"),
                 "non-monotone axis": (2, "0 100 50", "x[2] = 50"),
                 "wrong counts": (2, "0 50", "nx = 3"),
                 "non-numeric": (7, "0 10 deep", "'deep'")}
    else:
        good = ["--- bathymetry ---", "nGridX 3", "nGridY 2", "0 50 100",
                "-10 80 82 90", "10 81 88 95"]
        edits = {"off-grid row": (6, "10 81 88 95 97", "4 depths, but nGridX = 3"),
                 "hole": (6, "10 81 88", "x = 100, y = 10"),
                 "duplicate": (6, "-10 81 88 95", "lines 5 and 6"),
                 "non-monotone axis": (4, "0 100 50", "x[2] = 50"),
                 "wrong counts": (4, "0 50 100 150", "nGridX = 3 x values, got 4"),
                 "non-numeric": (5, "-10 80 eighty 90", "'eighty'")}
    line, replacement, words = edits[case]
    lines = list(good)
    if replacement is None:
        del lines[line - 1]
    else:
        lines[line - 1] = replacement
    key = "rows" if (fmt, case) == ("moordyn-c", "hole") else f"line {line}"
    return "\n".join(lines) + "\n", key, words


CASES = ["off-grid row", "hole", "duplicate", "non-monotone axis", "wrong counts", "non-numeric"]


@pytest.mark.parametrize("fmt", sorted(WRITERS))
@pytest.mark.parametrize("case", CASES)
def test_malformed_grid_file_names_file_and_line_in_one_line(tmp_path, fmt, case):
    text, key, words = malformed(fmt, case)
    path = tmp_path / f"{case.replace(' ', '_')}.txt"
    path.write_text(text)
    with pytest.raises(InputError) as error:
        read_seabed(path, "grid")
    message = str(error.value)
    assert "\n" not in message
    assert message.startswith(f"{path}: {key}: "), message
    assert words in message, message


def test_moordyn_c_rows_with_more_nodes_than_the_grid_are_duplicates(tmp_path):
    path = tmp_path / "c.txt"
    path.write_text("2 2\n0 1\n0 1\n0 0 -5\n1 0 -5\n0 1 -5\n1 1 -5\n1 1 -6\n")
    with pytest.raises(InputError, match="lines 7 and 8"):
        read_seabed(path)


def test_moordyn_f_missing_and_extra_rows_are_refused(tmp_path):
    base = "title\nnGridX 2\nnGridY 2\n0 1\n0 5 5\n"
    (tmp_path / "short.txt").write_text(base)
    (tmp_path / "long.txt").write_text(base + "1 5 5\n2 5 5\n")
    with pytest.raises(InputError, match="1 rows of depths, but nGridY = 2"):
        read_seabed(tmp_path / "short.txt")
    with pytest.raises(InputError, match="line 7: row 3 of depths"):
        read_seabed(tmp_path / "long.txt")


def test_read_seabed_refuses_unknown_kind_missing_file_and_unknown_layout(tmp_path):
    with pytest.raises(InputError, match="kind: unknown seabed kind 'terrain'"):
        read_seabed(tmp_path / "a.txt", "terrain")
    with pytest.raises(InputError, match="no such file"):
        read_seabed(tmp_path / "missing.txt")
    (tmp_path / "notes.txt").write_text("hello world\nthis is not a seabed\n")
    with pytest.raises(InputError, match="not a bathymetry grid"):
        read_seabed(tmp_path / "notes.txt", "grid")
    with pytest.raises(InputError, match="cannot tell which kind"):
        read_seabed(tmp_path / "notes.txt")


def test_kinds_are_guessed_from_content_and_suffix(tmp_path):
    (tmp_path / "soundings.txt").write_text("0 0 -10\n1 0 -11\n0 1 -12\n")
    (tmp_path / "seabed.stl").write_text("solid s\nendsolid s\n")
    assert guess_kind(tmp_path / "soundings.txt") == "points"
    assert guess_kind(tmp_path / "seabed.stl") == "mesh"


def test_a_missing_reader_module_is_an_input_error(tmp_path, monkeypatch):
    monkeypatch.setitem(FORMATS, "points", ("points", "cablefem.geometry.readers.not_there", ""))
    (tmp_path / "s.xyz").write_text("0 0 -10\n")
    with pytest.raises(InputError, match="no reader for 'points' files"):
        read_seabed(tmp_path / "s.xyz", "points")


# -- simplify -----------------------------------------------------------------

@pytest.mark.parametrize("angle, azimuth", [(0.05, 0.0), (0.3, np.pi / 2), (0.2, 2.5), (1e-3, -1.0)])
def test_simplify_finds_the_plane_of_a_planar_grid_in_any_direction(angle, azimuth):
    plane = Plane.from_slope([0.0, 0.0, -120.0], angle, azimuth)
    x, y = np.linspace(-500, 500, 7), np.linspace(-300, 200, 5)
    gx, gy = np.meshgrid(x, y)
    grid = DepthGrid(x, y, plane.elevation(np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape))
    notes = []
    chosen = simplify(grid, notes=notes)
    assert type(chosen) is Plane
    assert np.allclose(chosen.normal, plane.normal, rtol=0, atol=1e-12)
    assert abs(chosen.gap_only(np.array([[10.0, 20.0, -100.0]]))[0]
               - plane.gap_only(np.array([[10.0, 20.0, -100.0]]))[0]) < 1e-9
    assert len(notes) == 1 and "planar within" in notes[0]


def test_simplify_turns_a_level_grid_into_a_horizontal():
    grid = DepthGrid([0.0, 5.0, 9.0], [0.0, 1.0], np.full((2, 3), -42.0))
    notes = []
    chosen = simplify(grid, notes=notes)
    assert isinstance(chosen, Horizontal) and chosen.depth == 42.0
    assert "horizontal within 0 m" in notes[0]


def test_simplify_keeps_a_curved_grid_and_says_how_far_from_flat():
    grid = curved_grid()
    notes = []
    assert simplify(grid, notes=notes) is grid
    assert notes[0].startswith("seabed: kept grid") and "least-squares plane" in notes[0]
    # 3.6 m from its plane, 10.2 m from level, over a 267 m extent: a looser
    # tolerance takes the plane, a looser one still the horizontal first.
    assert simplify(grid, tolerance=0.01) is grid
    assert type(simplify(grid, tolerance=0.03)) is Plane
    assert type(simplify(grid, tolerance=0.1)) is Horizontal


def test_simplify_works_on_a_triangulated_surface_by_its_vertices():
    plane = Plane.from_slope([0.0, 0.0, -50.0], 0.1, 1.0)
    x, y = np.linspace(-100, 100, 5), np.linspace(-100, 100, 4)
    gx, gy = np.meshgrid(x, y)
    grid = DepthGrid(x, y, plane.elevation(np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape))
    surface = TriangulatedSurface(*grid.surface())
    assert np.allclose(simplify(surface).normal, plane.normal, atol=1e-12)
    bumpy = TriangulatedSurface(*curved_grid().surface())
    assert simplify(bumpy) is bumpy


def test_least_squares_and_mean_depth_stand_ins():
    grid = curved_grid()
    horizontal = grid.mean_depth_horizontal()
    assert horizontal.depth == pytest.approx(-grid.z.mean(), rel=1e-14)
    fitted = grid.least_squares_plane()
    # The fitted plane's vertical residuals sum to zero and are orthogonal to x and y.
    residual = grid.z.ravel() - fitted.elevation(grid.vertices[:, :2])
    assert abs(residual.sum()) < 1e-9
    assert np.abs(residual @ grid.vertices[:, :2]).max() < 1e-6
    with pytest.raises(InputError, match="not below the water surface"):
        DepthGrid([0, 1], [0, 1], np.ones((2, 2))).mean_depth_horizontal()


# -- seabed.vtu ---------------------------------------------------------------

@pytest.mark.parametrize("make", [curved_grid, lambda: Plane.from_slope([0, 0, -80.0], 0.1, 0.4),
                                  lambda: Horizontal(60.0)])
def test_seabed_vtu_reads_back_with_pyvista(tmp_path, make):
    pyvista = pytest.importorskip("pyvista")
    seabed = make()
    bounds = ((-150.0, 130.0), (-70.0, 95.0))
    path = write_seabed_vtu(seabed, tmp_path / "seabed.vtu", bounds)
    mesh = pyvista.read(path)
    points, triangles = seabed.surface(bounds)
    assert np.allclose(mesh.points, points, rtol=0, atol=1e-12)
    assert mesh.n_cells == len(triangles)
    assert np.allclose(mesh.point_data["elevation"], points[:, 2])
    assert np.allclose(mesh.point_data["normal"], seabed.project(points).direction)
    assert np.all(mesh.point_data["normal"][:, 2] > 0)
    assert not list(tmp_path.glob(".*partial"))


def test_seabed_vtu_refuses_another_suffix(tmp_path):
    with pytest.raises(InputError, match="expected a .vtu file"):
        write_seabed_vtu(Horizontal(10.0), tmp_path / "seabed.vtk")
