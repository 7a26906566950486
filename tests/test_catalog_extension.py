"""A newcomer's loads (``tests/toy_loads.py``), added as docs/architecture.md says: one module and one
catalog line each. They run in the compiled path and the numpy path alike, read their scene table,
and one of them keeps history per point (issue 15). The kernels are compiled for one catalog, so the
toy loads are registered in a fresh process with its own numba cache (~2-4 min of compilation on one
core): ``tests/conftest.py`` starts it when these tests are collected and runs them last, so that it
compiles beside the other tests."""

import numpy as np
import pytest


@pytest.fixture(scope="module")
def measured(toy_catalog):
    return toy_catalog.measured()


def test_a_uniform_force_from_its_scene_table_is_extra_weight_in_statics(measured):
    # the catenary of w + 500 N/m: P2 x 30 of a suspended line, measured 2e-8
    assert "UniformForce" in measured["uniform_in_catalog_loads"]
    assert measured["uniform_static_error"] < 1e-6


def test_a_registered_conservative_load_s_energy_reaches_statics_line_search(measured):
    # LineSystem.energy sums the catalog loads' energies, the toy's -f . r with them: the slope of
    # the line search's merit along a direction is the residual's G . d, and what the toy adds to
    # the one is what it adds to the other (central differences, h = 1e-4 m; round-off of the
    # ~1e9 J energy over h ~ 1e-8 of what the toy adds; without its energy the error would be 1)
    assert measured["uniform_energy_slope_error"] < 1e-6
    assert measured["uniform_energy_added_slope_error"] < 1e-5


def test_a_registered_load_runs_in_the_compiled_path_equal_to_its_numpy_face(measured):
    assert measured["uniform_compiled_steps"]
    assert measured["uniform_faces_difference"] < 1e-12
    assert measured["uniform_held_still_change"] < 1e-9  # a line at rest stays at rest


def test_plastic_work_per_cycle_is_the_hysteresis_loops_closed_form(measured):
    # each point moves s/L of the fairlead's 1 m: the loop of a point moving a beyond F_y / k
    # dissipates 4 F_y (a - F_y / k) per unit length (the extremes are step times)
    closed = measured["plastic_closed_form"]
    for label in ("plain", "halved", "python"):
        assert measured[f"plastic_{label}_work"] == pytest.approx(closed, rel=1e-3)


def test_history_survives_halved_and_rejected_steps(measured):
    # two full Newton iterations at most: steps fail and are halved, their trial history thrown away;
    # the committed history is that of the run without (to the Newton tolerance) and the same in
    # the compiled and the Python path (round-off)
    assert measured["plastic_halved_rejected"] > 0 and measured["plastic_plain_rejected"] == 0
    halved, python, plain = (np.array(measured[f"plastic_{label}_rest"]) for label in ("halved", "python", "plain"))
    np.testing.assert_allclose(halved, plain, rtol=0, atol=1e-6)
    np.testing.assert_allclose(halved, python, rtol=0, atol=1e-9)


def test_history_a_load_asks_for_is_in_the_frames(measured):
    assert measured["plastic_run_completed"]
    assert "plastic_rest" in measured["plastic_frames_fields"]
