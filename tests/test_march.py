"""Compiled BDF2 steps (cablefem.compiled.steps) against the per-step Python path, and their pieces."""

import numpy as np
import pytest
from scipy.linalg import solve_banded

from cablefem.dynamics import policy
from cablefem.dynamics.bdf2 import BDF2
from cablefem.dynamics.integrator import Integrator
from cablefem.geometry import DepthGrid
from cablefem.compiled.banded import lu_factor, lu_solve
from cablefem.compiled.problem import Packer
from cablefem.model.motion import fairlead_motion
from cablefem.runs.run import step_times
from cablefem.model.network import boundary_path
from cablefem.fem.system import build_system
from cablefem.statics.scene import start_states
from cablefem.model.scene import Motion
from cablefem.model.builtin import flume_scene


def integrator(scene, dt, compiled_steps, tolerance=1e-6, newton="auto", max_iterations=12):
    line = scene.lines[0]
    system = build_system(scene, line)
    (X0,), _ = start_states(scene, systems=[system])
    integ = BDF2(system, X0, boundary_path(scene, line), dt=dt, tolerance=tolerance, newton=newton,
                 max_iterations=max_iterations)
    if not compiled_steps:
        integ.stepper().packer = None  # the fused kernel per evaluation, Newton in Python
    return integ


@pytest.mark.parametrize("newton", ["full", "modified", "auto"])
@pytest.mark.parametrize("order, elements, dt, motion, iterations", [
    (1, 20, 0.04, "dynamic", 3),     # snap, 3 Newton iterations at most: steps fail and are halved
    (2, 10, 0.1, "quasi-static", 12),
    (3, 8, 0.02, "dynamic", 12),
])
def test_compiled_steps_equal_the_python_steps(order, elements, dt, motion, iterations, newton):
    scene = flume_scene("flat", motion, elements, order, 8.0, dt)
    times = step_times(0.0, 8.0, dt)
    runs = []
    for compiled_steps in (True, False):
        integ = integrator(scene, dt, compiled_steps, newton=newton, max_iterations=iterations)
        assert (integ.stepper().packer is not None) == compiled_steps
        forces = integ.march(times)
        runs.append((forces, integ.X, integ.V, integ.statistics()))
    (f1, X1, V1, s1), (f2, X2, V2, s2) = runs
    if iterations < 12 and newton != "full":
        # snap loads at 3 iterations: the paths agree bitwise for 3.2 s, then round-off in a step's
        # size (0.004375000000000018 s against 0.004374999999999782) decides modified Newton's
        # exact test of whether the kept factors belong to the step (the same v_x): one
        # factorisation more or less moves the answer within Newton's tolerance (1e-6)
        assert np.max(np.abs(f1 - f2)) <= 1e-8 * np.max(np.abs(f2))
        assert abs(s1.pop("njev") - s2.pop("njev")) <= 1 and abs(s1.pop("nlu") - s2.pop("nlu")) <= 1
    else:  # the same arithmetic in another order: round-off apart, the same iterations and halvings
        assert np.max(np.abs(f1 - f2)) <= 1e-9 * np.max(np.abs(f2))
        assert np.max(np.abs(X1 - X2)) <= 1e-9
        assert np.max(np.abs(V1 - V2)) <= 1e-7
    assert s1 == s2
    if iterations < 12:
        assert s1["rejected"] > 0  # the halving path was exercised ...
        if newton != "modified":  # modified Newton solves again on new branches only with new factors,
            assert s1["corrections"] > 0  # ... and the Newton steps solved again on new branches


def test_one_compiled_attempt_takes_the_python_attempts_iterations_to_its_state():
    """One attempt on its own (``Packer.attempt``: the policy's attempt by address from ``_entry``)
    and on the Python ops: the same iterations, the same state to round-off, snap loads on a flat
    flume floor."""
    scene = flume_scene("flat", "dynamic", 20, 1, 1.0, 0.05)
    runs = []
    for compiled_steps in (True, False):
        integ = integrator(scene, 0.05, compiled_steps)
        assert (integ.stepper().packer is not None) == compiled_steps
        for _ in range(2):
            integ.targets = integ.ends_at(integ.t + 0.05)  # as the policy's place_ends before an attempt
            assert integ.attempt(0.05)
        runs.append((integ.X.copy(), integ.V.copy(), integ.t, integ.statistics()))
    (X1, V1, t1, s1), (X2, V2, t2, s2) = runs
    assert t1 == t2 == pytest.approx(0.1) and s1 == s2 and s1["newton_iterations"] >= 2
    assert np.max(np.abs(X1 - X2)) <= 1e-9 and np.max(np.abs(V1 - V2)) <= 1e-7


def test_a_settings_field_of_another_type_fills_the_call_table_again():
    """A Packer's ``calls`` hold the addresses of code compiled for its Problems' type: a settings field
    that becomes an int between runs (where it was a float) fills them again (``problem.type_key``),
    and the steps take the numbers they take with the float; strided times step as their copy."""
    scene = flume_scene("flat", "dynamic", 20, 1, 2.0, 0.04)
    times = step_times(0.0, 2.0, 0.04)
    runs = []
    for value in (1.0, 1):
        integ = integrator(scene, 0.04, True)
        integ.march(times[:10])
        packer = integ.stepper().packer
        packer.settings = packer.settings._replace(min_damping=value)
        runs.append(integ.march(times[11::2]))  # every other time: a strided array
    assert np.array_equal(runs[0], runs[1]) and np.all(np.isfinite(runs[0]))
    again = integrator(scene, 0.04, True)
    again.march(times[:10])
    again.stepper().packer.settings = again.stepper().packer.settings._replace(min_damping=1.0)
    assert np.array_equal(again.march(times[11::2].copy()), runs[0])


def test_branch_corrections_save_evaluations_and_keep_the_solution():
    """Snap loads, P1 x 14 at dt 0.16 s: solving a rejected Newton step again on the friction and
    tension branches its trial reached (``Integrator.MAX_CORRECTIONS``) leaves no failed attempt
    and saves residual evaluations (measured: 327 -> 274, 1 failed attempt -> 0), and the
    fairlead tension is the same to the Newton tolerance where the steps are the same (measured
    0.25 % RMS over 12 s; the run without halves one step, which moves the later steps)."""
    scene = flume_scene("flat", "dynamic", 14, 1, 12.0, 0.16)
    times = step_times(0.0, 12.0, 0.16)
    runs = {}
    for corrections in (0, 2):
        integ = integrator(scene, 0.16, True, tolerance=1e-4)
        integ.MAX_CORRECTIONS = corrections
        integ.stepper().packer = Packer.for_group(integ.stepper())  # settings read at construction
        tension = np.linalg.norm(integ.march(times)[:, 0], axis=1)
        runs[corrections] = (tension, integ.statistics())
    (plain, without), (tension, stats) = runs[0], runs[2]
    assert stats["corrections"] > 0 and without["corrections"] == 0
    assert stats["rejected"] < without["rejected"]
    assert stats["nfev"] <= 0.9 * without["nfev"]
    assert np.sqrt(np.mean((tension - plain) ** 2)) <= 0.01 * np.mean(plain)


@pytest.mark.parametrize("order, elements, dt, motion", [(2, 10, 0.1, "quasi-static"), (1, 20, 0.04, "dynamic")])
def test_auto_newton_saves_factorisations_of_full_and_iterations_of_modified(order, elements, dt, motion):
    """"auto" (compiled kernel): modified Newton until its kept factors must be rebuilt or a
    step fails, then full Newton for a while: fewer LU factorisations than full Newton and
    fewer iterations than modified on a quasi-static and a snap-load run (measured: LU 107 and
    269 against 125 and 330; iterations 169 and 447 against 272 and 750), and the state of full
    Newton to its tolerance (1.8e-7 m and 1.7e-7 m apart at tolerance 1e-6)."""
    scene = flume_scene("flat", motion, elements, order, 8.0, dt)
    times = step_times(0.0, 8.0, dt)
    runs = {}
    for newton in ("full", "modified", "auto"):
        integ = integrator(scene, dt, True, newton=newton)
        integ.march(times)
        runs[newton] = (integ.X, integ.statistics())
    (X_full, full), (_, modified), (X_auto, auto) = runs["full"], runs["modified"], runs["auto"]
    assert auto["nlu"] < full["nlu"]
    assert auto["newton_iterations"] < modified["newton_iterations"]
    assert np.max(np.abs(X_auto - X_full)) <= 1e-5


def undulating_grid():
    """A depth grid under the flat flume line that no plane fits: 100 m deep at the fairlead,
    rising 4 m towards the anchor with a 1 m swell."""
    x, y = np.linspace(-700.0, 100.0, 33), np.linspace(-200.0, 200.0, 9)
    X, Y = np.meshgrid(x, y)
    return DepthGrid(x, y, -100.0 - 0.005 * X + np.sin(X / 60.0) + 0.002 * Y)


@pytest.mark.parametrize("seabed", ["steep", "grid"])  # the walk on a triangulated step; bilinear
def test_compiled_steps_project_curved_seabeds_as_the_python_steps(seabed):
    scene = flume_scene("flat" if seabed == "grid" else seabed, "dynamic", 12, 2, 6.0, 0.02)
    if seabed == "grid":
        scene.seabed = undulating_grid()
    times = step_times(0.0, 6.0, 0.02)
    runs = []
    for compiled_steps in (True, False):
        integ = integrator(scene, 0.02, compiled_steps)
        assert (integ.stepper().packer is not None) == compiled_steps
        runs.append((integ.march(times), integ.X, integ.statistics()))
    (f1, X1, s1), (f2, X2, s2) = runs
    assert np.max(np.abs(f1 - f2)) <= 1e-9 * np.max(np.abs(f2))
    assert np.max(np.abs(X1 - X2)) <= 1e-9
    assert s1 == s2
    assert np.all(integ.system.seabed.project(X2[1:]).gap > -0.5)  # resting on it (the anchor is buried)


@pytest.mark.parametrize("iterations, smallest, python_steps", [
    (3, 0.04 / 4, False),  # failed steps halved twice, all inside the compiled loop
    (2, 0.04 / 16, True),  # halved four times: deeper than the loop's DEPTH, step() goes on
])
def test_compiled_steps_halve_and_grow_back_as_step_does(iterations, smallest, python_steps):
    """A step whose Newton fails is halved in the compiled loop, up to DEPTH times, and the steps
    after it grow back by at most 2x, as ``Integrator.step`` does (the same attempts: the same
    statistics and states as the Python path); a deeper halving goes on in ``Integrator.step``."""
    scene = flume_scene("flat", "dynamic", 20, 1, 8.0, 0.04)
    times = step_times(0.0, 8.0, 0.04)
    runs = []
    for compiled_steps in (True, False):
        integ = integrator(scene, 0.04, compiled_steps, max_iterations=iterations)
        group = integ.stepper()
        sizes, calls = [], []
        attempt, step = group.attempt, group.step

        def recording(h, attempt=attempt, sizes=sizes):
            outcome = attempt(h)
            sizes.append((h, outcome == policy.CONVERGED))
            return outcome

        def counting(*args, step=step, calls=calls, **kwargs):
            calls.append(args)
            return step(*args, **kwargs)

        group.attempt, group.step = recording, counting
        forces = integ.march(times)
        runs.append((forces, integ.X, integ.statistics(), sizes, calls))
        assert integ.t == pytest.approx(8.0, abs=1e-12)
    (f1, X1, s1, _, calls), (f2, X2, s2, sizes, _) = runs
    assert s1 == s2 and s1["rejected"] > 0
    assert np.max(np.abs(f1 - f2)) <= 1e-9 * np.max(np.abs(f2))
    assert np.max(np.abs(X1 - X2)) <= 1e-9
    taken = np.array([h for h, ok in sizes if ok])
    assert taken.min() == pytest.approx(smallest)  # the deepest halving of the run
    assert np.all(taken[1:] <= 2.0 * (1 + BDF2.STRETCH) * taken[:-1])  # grown back by doubling
    assert bool(calls) == python_steps


def test_banded_lu_with_pivoting_solves_like_scipy():
    rng = np.random.default_rng(3)
    n, kl, ku = 40, 5, 5
    dense = np.zeros((n, n))
    for i in range(n):
        for j in range(max(0, i - kl), min(n, i + ku + 1)):
            dense[i, j] = rng.standard_normal()
    dense[np.arange(n), np.arange(n)] = 0.0  # no diagonal: every column needs a row swap
    b = rng.standard_normal(n)
    band = np.zeros((n, 2 * kl + ku + 1)).T  # column-major, LAPACK's layout
    for j in range(n):
        for i in range(max(0, j - ku), min(n, j + kl + 1)):
            band[kl + ku + i - j, j] = dense[i, j]
    expected = solve_banded((kl, ku), band[kl:], b)
    x, pivots, scratch = b.copy(), np.zeros(n, dtype=np.int64), np.zeros(kl + 1)
    flat = band.T.ravel()  # columns one after the other
    assert lu_factor(flat, n, kl, ku, pivots, scratch)
    lu_solve(flat, n, kl, ku, pivots, x)
    assert np.max(np.abs(dense @ x - b)) <= 1e-10 * np.max(np.abs(b))
    assert np.allclose(x, expected, rtol=1e-9, atol=1e-12)
    singular = np.zeros(n * (2 * kl + ku + 1))
    assert not lu_factor(singular, n, kl, ku, pivots, scratch)


@pytest.mark.parametrize("dt, stop", [(0.04, 1.0), (0.03, 1.0), (0.17, 0.5), (0.1, 0.1000001)])
def test_fixed_step_times_land_on_the_stop_without_slivers(dt, stop):
    scene = flume_scene("flat", "dynamic", 4, 1, 1.0, dt)
    times = step_times(0.0, stop, dt)
    steps = np.diff(np.concatenate([[0.0], times]))
    assert times[-1] == stop
    assert np.all(steps <= dt * (1 + 1e-3) + 1e-15)
    assert np.all(steps >= 0.5 * min(dt, stop) - 1e-15)  # never a sliver before the stop


@pytest.mark.parametrize("motion", [
    Motion(kind="harmonic", amplitude=(5.0, 1.0, -2.0), period=6.0, offset=(1.0, 0.0, 0.5), ramp=6.0),
    Motion(kind="circular", radius=2.0, period=4.0, plane="xz", offset=(0.0, 1.0, 0.0), ramp=3.0),
    Motion(kind="table", times=(0.0, 1.0, 4.0), positions=((0, 0, 0), (1, 2, 3), (-1, 0, 2)), ramp=0.5),
    Motion(kind="fixed"),
])
def test_vectorised_motion_equals_the_scalar_one(motion):
    times = np.linspace(-1.0, 8.0, 181)
    together = fairlead_motion(motion, times)
    one_by_one = [np.array([fairlead_motion(motion, t)[k] for t in times]) for k in range(3)]
    for a, b in zip(together, one_by_one):
        assert a.shape == (181, 3)
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12)


def test_table_motion_holds_its_ends_and_interpolates():
    motion = Motion(kind="table", times=(0.0, 2.0), positions=((0, 0, 0), (2, 4, 6)))
    d, v, a = fairlead_motion(motion, np.array([-1.0, 0.5, 3.0]))
    np.testing.assert_allclose(d, [[0, 0, 0], [0.5, 1, 1.5], [2, 4, 6]])
    np.testing.assert_allclose(v, [[0, 0, 0], [1, 2, 3], [0, 0, 0]])
    assert not a.any()


def test_compiled_steps_need_the_compiled_kernel():
    assert integrator(flume_scene("flat", "dynamic", 6, 2, 1.0, 0.05), 0.05, True).stepper().packer is not None
    reference = flume_scene("flat", "dynamic", 6, 2, 1.0, 0.05)
    line = reference.lines[0]
    system = build_system(reference, line)
    X0 = start_states(reference, systems=[system])[0][0]
    assert BDF2(system, X0, boundary_path(reference, line), dt=0.05, compiled=False).stepper().packer is None


def test_residual_line_search_stops_newton_cycling_in_snap_loads():
    """Undamped Newton cycles between two friction/contact states in the snap-load case and the
    step is halved; the Armijo line search converges instead (Integrator.newton)."""
    scene = flume_scene("flat", "dynamic", 20, 2, 10.0, 0.04)
    times = step_times(0.0, 10.0, 0.04)
    rejected = {}
    for damping in (Integrator.MIN_DAMPING, 1.0):  # 1.0: no line search
        integ = integrator(scene, 0.04, True)
        integ.stepper().packer.settings = integ.stepper().packer.settings._replace(min_damping=damping)
        integ.march(times)
        rejected[damping] = integ.rejected
    assert rejected[1.0] >= 3
    assert rejected[Integrator.MIN_DAMPING] == 0


def test_compiled_adaptive_steps_hold_the_tolerance_as_the_python_steps():
    """Error-controlled steps (``policy.attempt``'s INACCURATE, the tension error of
    ``Integrator.tension_error`` and ``line_ops._tension_error``) on the flume's snap: the compiled
    steps end on 1/64 splits of an output interval (``problem.ADAPTIVE_PARTS``) where the Python
    ops do not, so their steps differ (measured 1253 against 1051, 71 and 125 rejected); at the same
    tolerance both rejected steps and their forces agree within 1 % of the peak (measured 0.29 %)."""
    scene = flume_scene("flat", "dynamic", 20, 2, 8.0, 0.2)
    times = step_times(0.0, 8.0, 0.2)
    runs = []
    for compiled_steps in (True, False):
        line = scene.lines[0]
        system = build_system(scene, line)
        (X0,), _ = start_states(scene, systems=[system])
        integ = BDF2(system, X0, boundary_path(scene, line), dt=0.2, tolerance=1e-8, adaptive=True,
                     error_tolerance=1e-4)
        if not compiled_steps:
            integ.stepper().packer = None
        runs.append((integ.march(times), integ.statistics()))
    (f1, s1), (f2, s2) = runs
    assert s1["rejected"] > 0 and s2["rejected"] > 0
    assert 0.8 < s1["steps"] / s2["steps"] < 1.25
    assert np.max(np.abs(f1 - f2)) <= 1e-2 * np.max(np.abs(f2))
