"""Seabed generators: slopes, the desire2023 flume steps, diamond-square."""

import numpy as np
import pytest

from cablefem.errors import InputError
from cablefem.geometry import DepthGrid, Horizontal, Plane, simplify
from cablefem.geometry.generators import (FLUME_WIDTH, diamond_square, flume_step,
                                          fractal_heights, slope, step)


@pytest.mark.parametrize("angle, azimuth", [(np.arctan(0.125), 0.0), (np.arctan(0.125), np.pi),
                                            (np.arctan(0.125), np.pi / 2), (0.3, 1.2)])
def test_slope_rises_at_its_angle_towards_its_azimuth(angle, azimuth):
    # housner2022's up-, down- and side-slopes are the 12.5 % grade at three azimuths.
    grid = slope(angle, azimuth, depth=850.0, nodes=4)
    plane = Plane.from_slope([0.0, 0.0, -850.0], angle, azimuth)
    chosen = simplify(grid)
    assert type(chosen) is Plane
    assert np.allclose(chosen.normal, plane.normal, rtol=0, atol=1e-12)
    ahead = np.array([[np.cos(azimuth), np.sin(azimuth)]]) * 100.0
    assert grid.elevation(ahead)[0] - grid.elevation([[0.0, 0.0]])[0] == pytest.approx(
        100.0 * np.tan(angle), rel=1e-12)


def profile_slopes(grid):
    """Slope angles [deg] of the pieces of a step profile (along x, at y = 0)."""
    z = grid.z[0]
    return np.degrees(np.arctan(np.diff(z) / np.diff(grid.x)))


@pytest.mark.parametrize("kind, angle", [("gentle", 4.0), ("steep", 19.0)])
def test_flume_steps_have_the_paper_angles_and_are_flat_slope_flat(kind, angle):
    grid = flume_step(kind)
    slopes = profile_slopes(grid)
    assert np.allclose(slopes, [0.0, angle, 0.0], rtol=0, atol=1e-12)
    # The slope angle seen by the projection: the normal's tilt on the slope.
    foot, top = grid.x[1], grid.x[2]
    on_slope = grid.project(np.array([[0.5 * (foot + top), 0.0, -90.0]]))
    assert np.degrees(np.arccos(on_slope.direction[0, 2])) == pytest.approx(angle, abs=1e-10)
    # Uniform across the 150 m (2 m model) flume, rising towards the fairlead.
    assert np.array_equal(grid.z[0], grid.z[1]) and grid.y[1] - grid.y[0] == FLUME_WIDTH
    assert grid.z[0, 0] == -100.0 and grid.z[0, -1] > grid.z[0, 0]


@pytest.mark.parametrize("kind", ["gentle", "steep"])
def test_flume_steps_are_continuous_across_their_corners(kind):
    grid = flume_step(kind)
    for corner in grid.x[1:3]:
        for eps in (1e-3, 1e-6):
            left, right = grid.elevation([[corner - eps, 10.0], [corner + eps, 10.0]])
            assert abs(right - left) <= 2 * eps * np.tan(np.radians(19.0)) + 1e-12


def test_flume_corners_are_where_the_line_meets_them():
    # gentle: the concave foot lies anchor-side of the flat-floor touchdown
    # (x ~ -150 to -270 m), the top fairlead-side; steep: the convex top sits
    # at it. A change here changes the validation cases: see docs/seabeds.md.
    gentle, steep = flume_step("gentle"), flume_step("steep")
    assert gentle.x[1] == -260.0 and -100.0 < gentle.x[2] < -80.0
    assert steep.x[2] == -200.0 and -240.0 < steep.x[1] < -230.0
    assert gentle.z[0, -1] == steep.z[0, -1] == -88.0


def test_flat_flume_is_a_horizontal_seabed_100_m_deep():
    chosen = simplify(flume_step("flat"))
    assert isinstance(chosen, Horizontal) and chosen.depth == 100.0


@pytest.mark.parametrize("call, key", [
    (lambda: flume_step("medium"), "kind"),
    (lambda: flume_step("gentle", rise=150.0), "rise"),
    (lambda: step(0.1, -2000.0, 5.0), "x_range"),
    (lambda: slope(2.0), "angle"),
    (lambda: slope(0.1, nodes=1), "nodes"),
    (lambda: diamond_square(0), "n"),
    (lambda: diamond_square(3, smoothness=1.5), "smoothness"),
    (lambda: diamond_square(3, tilt=(0.1,)), "tilt"),
    (lambda: diamond_square(3, mean_depth=-5.0), "mean_depth"),
])
def test_generator_inputs_are_checked(call, key):
    with pytest.raises(InputError) as error:
        call()
    assert error.value.key == key


def test_diamond_square_is_reproducible_from_its_seed():
    a = diamond_square(5, seed=11)
    b = diamond_square(5, seed=11)
    c = diamond_square(5, seed=12)
    assert np.array_equal(a.z, b.z)
    assert not np.allclose(a.z, c.z)
    assert a.z.shape == (33, 33) and isinstance(a, DepthGrid)


@pytest.mark.parametrize("mean_depth, tilt", [(93.5, (0.0, 0.0)), (93.5, (0.03, -0.01)),
                                              (400.0, (-0.1, 0.05))])
def test_diamond_square_has_the_requested_mean_depth_and_tilt(mean_depth, tilt):
    grid = diamond_square(6, amplitude=12.0, seed=3, mean_depth=mean_depth, tilt=tilt)
    assert grid.z.mean() == pytest.approx(-mean_depth, abs=1e-9)
    assert grid.mean_depth_horizontal().depth == pytest.approx(mean_depth, abs=1e-9)
    normal = grid.least_squares_plane().normal
    assert np.allclose(-normal[:2] / normal[2], tilt, rtol=0, atol=1e-12)
    # Irregular in x and in y (desire2023 Fig. 18), not a plane.
    residual = grid.z - grid.least_squares_plane().elevation(grid.vertices[:, :2]).reshape(grid.z.shape)
    assert residual.std(axis=0).mean() > 0.5 and residual.std(axis=1).mean() > 0.5
    assert simplify(grid) is grid


def test_diamond_square_smoothness_near_zero_is_smoother():
    # desire2023 Sec. 5: "the closer it is to 0, the smoother is the surface".
    # Roughness measured as the mean squared second difference relative to
    # the variance; the same seed draws the same random numbers.
    def roughness(smoothness):
        h = fractal_heights(7, smoothness, 1.0, np.random.default_rng(5))
        return np.mean(np.diff(h, 2, axis=0) ** 2) / h.var()
    values = [roughness(s) for s in (0.0, 0.3, 0.7, 1.0)]
    assert all(a < b for a, b in zip(values, values[1:])), values


def test_diamond_square_without_amplitude_is_its_plane():
    grid = diamond_square(3, amplitude=0.0, tilt=(0.02, 0.0))
    chosen = simplify(grid)
    assert type(chosen) is Plane and chosen.slope_angle() == pytest.approx(np.arctan(0.02), rel=1e-12)
