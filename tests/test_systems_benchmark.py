"""benchmarks/systems.py's error and its scenes: the error is zero for equal series and the closed
form for a shifted sine; the best row changes only what it says it changes (an element count per
segment, or each segment's count times a factor, rounded up)."""

import math

import numpy as np
import pytest

from benchmarks.systems import SYSTEMS, error, largest_step, scene_of

PERIOD, MEAN, AMPLITUDE = 10.0, 1.0e6, 2.0e5


def sine(t, shift=0.0):
    return MEAN + AMPLITUDE * np.sin(2 * np.pi * (t - shift) / PERIOD)


def test_error_of_equal_series_is_zero():
    t = np.linspace(0.0, 100.0, 10001)
    series = np.column_stack([sine(t), sine(t, 1.0)])
    assert error(t, series, t, series, 80.0) == 0.0


@pytest.mark.parametrize("shift", [0.05, 0.5, 2.5])
def test_error_of_shifted_sine_is_the_closed_form(shift):
    """RMS of A sin(w (t - s)) - A sin(w t) over whole periods is sqrt(2) A |sin(w s / 2)|; the run
    on a coarser grid than the reference's, so the reference is interpolated to the run's times."""
    t_ref = np.arange(0.0, 100.0 + 1e-9, 0.001)
    t_run = np.arange(0.0, 100.0, 0.1) + 0.1  # the run's steps, not the reference's grid
    expected = np.sqrt(2) * AMPLITUDE * abs(np.sin(np.pi * shift / PERIOD)) / MEAN
    got = error(t_run, sine(t_run, shift)[:, None], t_ref, sine(t_ref)[:, None], 80.0 + 0.05)
    assert got == pytest.approx(expected, rel=2e-3)


def test_error_is_the_largest_over_the_lines():
    t = np.linspace(0.0, 100.0, 10001)
    reference = np.column_stack([sine(t), sine(t), sine(t)])
    run = np.column_stack([sine(t, 0.1), sine(t, 1.0), sine(t)])
    alone = error(t, run[:, 1:2], t, reference[:, 1:2], 80.0)
    assert error(t, run, t, reference, 80.0) == alone > error(t, run[:, :1], t, reference[:, :1], 80.0)


def test_error_window_ignores_what_comes_before_it():
    t = np.linspace(0.0, 100.0, 10001)
    run = sine(t)[:, None].copy()
    run[t < 80.0] *= 3.0
    assert error(t, run, t, sine(t)[:, None], 80.0) == 0.0


@pytest.mark.parametrize("system", [name for name, spec in SYSTEMS.items() if "module" not in spec])
def test_best_scene_changes_only_order_elements_step_and_tolerance(system):
    best = SYSTEMS[system]["best"]
    default, tuned = scene_of(system), scene_of(system, **best)
    assert [line.order for line in tuned.lines] == [best["order"]] * len(default.lines)
    counts = [s.elements for line in default.lines for s in line.segments]
    expected = [best["elements"]] * len(counts) if "elements" in best else \
        [max(1, math.ceil(best["factor"] * n)) for n in counts]
    assert [s.elements for line in tuned.lines for s in line.segments] == expected
    assert (tuned.solver.dt, tuned.solver.tolerance) == (best["dt"], best["tolerance"])
    assert [s.length for line in tuned.lines for s in line.segments] == \
        [s.length for line in default.lines for s in line.segments]
    assert tuned.motion == default.motion and tuned.solver.duration == default.solver.duration


def test_lazy_wave_rows_are_the_files_mesh_at_the_defaults_steps_and_half_of_it(tmp_path):
    """The lazy wave's cablefem rows: the MoorDyn file's 52 segments read as 52 Hermite elements (26 for
    the best row), the steps a fortieth of the shortest forcing period (the 10 s ramp) as a scene that
    gives only the motion gets them, one welded line clamped vertical at its top."""
    from benchmarks import systems_lazy_wave as lazy

    made, best = lazy.scene(lazy.MOORDYN_LENGTH, tmp_path), lazy.scene(lazy.BEST_LENGTH, tmp_path)
    for scene, count in ((made, 52), (best, 26)):
        (line,) = scene.lines
        assert line.element == "hermite" and sum(s.elements for s in line.segments) == count
        np.testing.assert_array_equal(line.tangents[1], [0.0, 0.0, 1.0])
        assert scene.solver.dt == pytest.approx(10.0 / 40) and not scene.solver.adaptive
        assert scene.solver.duration == lazy.DURATION


def test_error_at_frames_counts_only_the_times_on_them():
    """``every``: the error at the run's times that are multiples of it, where an adaptive run has its
    rows: a run wrong only between whole seconds has none there, and all of its error at every row."""
    t = np.arange(0.0, 100.0 + 1e-9, 0.25)
    run = sine(t)[:, None].copy()
    run[np.abs(t - np.round(t)) > 1e-9] += 1e5
    assert error(t, run, t, sine(t)[:, None], 80.0, every=1.0) == 0.0
    assert error(t, run, t, sine(t)[:, None], 80.0) > 0.05


@pytest.mark.parametrize("system", [name for name, spec in SYSTEMS.items() if "module" not in spec])
def test_adaptive_rows_change_only_the_step_control(system):
    """An adaptive row: the scene at its defaults with error control at the tolerance given, its
    largest step a twentieth of the period and its frames at least that far apart."""
    default, adaptive = scene_of(system), scene_of(system, error_tolerance=1e-2, integrator="generalized-alpha")
    assert adaptive.solver.adaptive and adaptive.solver.error_tolerance == 1e-2
    assert adaptive.solver.integrator == "generalized-alpha"
    assert adaptive.solver.dt == pytest.approx(SYSTEMS[system]["period"] / 20) == largest_step(system)
    assert adaptive.output.every == max(default.output.every, adaptive.solver.dt)
    assert [(line.name, line.order) for line in adaptive.lines] == [(line.name, line.order) for line in default.lines]
    assert [s.elements for line in adaptive.lines for s in line.segments] == \
        [s.elements for line in default.lines for s in line.segments]
    assert adaptive.motion == default.motion and adaptive.solver.duration == default.solver.duration
