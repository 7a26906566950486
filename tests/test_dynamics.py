"""Time integration: temporal order, natural frequencies against closed forms, friction
stick and slip on slopes, and run outputs that survive an early stop."""

import json
import os
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg

from cablefem import Line, LineType, Segment
from cablefem.dynamics.bdf2 import BDF2
from cablefem.dynamics.generalized_alpha import GeneralizedAlpha
from cablefem.geometry import Horizontal, Plane
from cablefem.loads.added_mass import AddedMass
from cablefem.loads.drag import Drag
from cablefem.model.motion import fairlead_motion
from cablefem.model.scene import Contact, Environment, Friction, Motion
from cablefem.statics.solve import solve_static
from cablefem.fem.system import LineSystem

ROPE = LineType("rope", diameter=0.05, mass=10.0, EA=1e5, damping=0.01,
                Cd_normal=1.2, Cd_tangential=0.2, Ca_normal=1.0, Ca_tangential=0.5)


def rope_system(order=2, elements=8):
    """A 105 m rope hanging freely between two points 100 m apart, with drag and added mass."""
    line = Line("rope", [-80.0, 0.0, -60.0], [0.0, 0.0, 0.0], [Segment(ROPE, 105.0, elements)], order)
    env = Environment()
    system = LineSystem(line, Horizontal(1000.0), Contact(), env)
    system.loads += [Drag([0.05] * elements, [1.2] * elements, [0.2] * elements, 1025.0, (0.3, 0.0, 0.0)),
                     AddedMass([0.05] * elements, [1.0] * elements, [0.5] * elements, 1025.0)]
    return system


def integrate(cls, system, X0, dt, duration, **options):
    motion = Motion(kind="harmonic", amplitude=(1.0, 0.0, 0.5), period=4.0, ramp=2.0)
    fairlead = system.line.fairlead

    def boundary(t):
        d, v, a = fairlead_motion(motion, t)
        return fairlead + d, v, a

    integ = cls(system, X0, boundary, dt=dt, tolerance=1e-12, **options)
    for _ in range(int(round(duration / dt))):
        integ.step(dt)
    return integ


@pytest.mark.parametrize("cls, options", [(BDF2, {}), (GeneralizedAlpha, {"rho_inf": 0.8})])
def test_integrators_converge_at_second_order_in_time(cls, options):
    system = rope_system()
    X0 = solve_static(system, tolerance=1e-12).X
    steps = [0.08, 0.04, 0.02]
    reference = integrate(cls, system, X0, 0.005, 3.0, **options)
    errors = [np.abs(integrate(cls, system, X0, dt, 3.0, **options).X - reference.X).max() for dt in steps]
    orders = np.log2(np.array(errors[:-1]) / errors[1:])
    # a smooth problem (no contact, resolved axial modes): both schemes are second order;
    # 1.8 leaves room for the reference's own error and the pre-asymptotic first step
    assert np.all(orders > 1.8), (errors, orders)


def taut_line(order, elements, water_density=0.0):
    """A weightless line of 100 m stretched 1 % between fixed ends (no gravity, no seabed)."""
    line_type = LineType("taut", diameter=0.1, mass=50.0, EA=2e6, Ca_normal=1.0, Ca_tangential=0.5)
    line = Line("taut", [0.0, 0.0, 0.0], [101.0, 0.0, 0.0], [Segment(line_type, 100.0, elements)], order)
    env = Environment(water_density=water_density, gravity=0.0)
    system = LineSystem(line, Horizontal(1e4), Contact(), env)
    if water_density:
        system.loads.append(AddedMass([0.1] * elements, [1.0] * elements, [0.5] * elements, water_density))
    X = system.fem.interpolate(lambda s: np.column_stack([1.01 * s, 0 * s, 0 * s]))
    return system, X, line_type


def modal_frequencies(system, X, count):
    """Lowest angular frequencies [rad/s] of the linearised line about X: K phi = w^2 M phi."""
    _, blocks = system.evaluate(system.state(X, np.zeros_like(X), np.zeros_like(X)),
                                acceleration_factor=0.0)
    K = system.matrix(blocks).toarray()
    M = system.fem.vector_mass(system.props["mass"]).toarray()
    _, added = system.evaluate(system.state(X, np.zeros_like(X), np.zeros_like(X)),
                               acceleration_factor=1.0)
    M += system.matrix(added).toarray() - K  # the added-mass blocks alone
    values = scipy.linalg.eigh(K, M, eigvals_only=True)
    return np.sqrt(np.sort(values)[:count])


@pytest.mark.parametrize("water_density", [0.0, 1025.0])
def test_taut_line_modes_match_closed_forms(water_density):
    system, X, lt = taut_line(order=3, elements=12, water_density=water_density)
    L, e = 100.0, 0.01
    T = lt.EA * e
    area = np.pi * lt.diameter**2 / 4
    # inertia per unstretched length: the line, plus added mass per stretched length x (1 + e)
    m_lateral = lt.mass + water_density * area * lt.Ca_normal * (1 + e)
    m_axial = lt.mass + water_density * area * lt.Ca_tangential * (1 + e)
    n = np.arange(1, 4)
    lateral = n * np.pi / L * np.sqrt(T / ((1 + e) * m_lateral))  # string: tension / stretch
    axial = n * np.pi / L * np.sqrt(lt.EA / m_axial)
    expected = np.sort(np.concatenate([lateral, lateral, axial]))[:6]
    computed = modal_frequencies(system, X, 6)
    # P3 x 12 elements: the eigenvalue error grows like (n h / L)^(2p), ~1e-6 at n = 3
    np.testing.assert_allclose(computed, expected, rtol=1e-5)


@pytest.mark.parametrize("cls", [BDF2, GeneralizedAlpha])
def test_free_lateral_vibration_has_the_string_period(cls):
    system, X0, lt = taut_line(order=2, elements=10)
    L, e = 100.0, 0.01
    omega = np.pi / L * np.sqrt(lt.EA * e / ((1 + e) * lt.mass))
    period = 2 * np.pi / omega
    fem = system.fem
    amplitude = 0.01  # m: small against the length, so the motion is linear
    X = X0 + fem.interpolate(lambda s: np.column_stack([0 * s, amplitude * np.sin(np.pi * s / L), 0 * s]))
    options = {"rho_inf": 1.0} if cls is GeneralizedAlpha else {}
    integ = cls(system, X, lambda t: (np.array([101.0, 0, 0]), np.zeros(3), np.zeros(3)),
                dt=period / 200, tolerance=1e-12, **options)
    middle = int(np.argmin(np.abs(fem.mesh.p[0] - L / 2)))
    times, values = [integ.t], [integ.X[middle, 1]]
    while integ.t < 2.2 * period:
        integ.step()
        times.append(integ.t)
        values.append(integ.X[middle, 1])
    times, values = np.array(times), np.array(values)
    crossing = np.flatnonzero((values[:-1] > 0) & (values[1:] <= 0))
    t_cross = times[crossing] + (times[crossing + 1] - times[crossing]) * values[crossing] / (
        values[crossing] - values[crossing + 1])
    measured = t_cross[1] - t_cross[0]
    # 200 steps per period: the period error of both schemes is O((w dt)^2) ~ 1e-3
    assert measured == pytest.approx(period, rel=3e-3)


def lying_line(direction, slope_deg, friction, slack=0.05, elements=10):
    """A slack chain lying on a plane rising at ``slope_deg`` towards +x, laid along
    ``direction`` (a unit vector in the plane), both ends fixed."""
    chain = LineType("chain", diameter=0.1, mass=200.0, EA=1e8, damping=0.0,
                     Cd_normal=0.0, Cd_tangential=0.0, Ca_normal=0.0, Ca_tangential=0.0)
    plane = Plane.from_slope([0.0, 0.0, -50.0], np.radians(slope_deg))
    chord = 20.0
    start = np.array([0.0, 0.0, -50.0])
    end = start + chord * np.asarray(direction)
    line = Line("lying", start, end, [Segment(chain, chord * (1 + slack), elements)], 1)
    contact = Contact(stiffness=1e7, damping_ratio=1.0)
    system = LineSystem(line, plane, contact, Environment(), friction=friction)
    sink = chain.submerged_weight(1025.0, 9.81) * plane.normal[2] / (1e7 * 0.1)
    X = system.fem.interpolate(lambda s: start + np.outer(s / (chord * (1 + slack)), end - start)
                               - sink * plane.normal)
    return system, X


def slide(system, X, duration=2.0, dt=0.01):
    integ = BDF2(system, X, lambda t: (system.line.fairlead, np.zeros(3), np.zeros(3)), dt=dt,
                 tolerance=1e-10)
    middle = system.fem.n_vertices // 2
    while integ.t < duration - 1e-9:
        integ.step(dt)
    return integ.X[middle] - X[middle], integ.V[middle]


def test_isotropic_friction_sticks_below_the_friction_angle_and_slides_above():
    mu = 0.4  # friction angle 21.8 deg
    along_contour = np.array([0.0, 1.0, 0.0])
    friction = Friction(model="isotropic", mu=mu, v_threshold=0.01)
    slow, _ = slide(*lying_line(along_contour, 15.0, friction))
    fast, v = slide(*lying_line(along_contour, 30.0, friction))
    # below: the saturated-damping law creeps at v_c tan(a)/mu at most
    assert np.linalg.norm(slow) < 2.0 * 0.01 * np.tan(np.radians(15.0)) / mu * 1.05
    # above: the middle slides down the fall line (-x) with g (sin a - mu cos a) per unit
    # submerged weight over mass (no drag, no added mass; the slack lets it move freely); measured
    # 5.1 % further than that (4.9 % with the seabed damper switching on in full at the surface):
    # the 5 % left is not yet explained
    a = np.radians(30.0)
    w_over_m = (200.0 - 1025.0 * np.pi * 0.1**2 / 4) / 200.0
    expected = 0.5 * 9.81 * w_over_m * (np.sin(a) - mu * np.cos(a)) * 2.0**2
    downhill = -fast @ np.array([np.cos(a), 0.0, np.sin(a)])
    assert downhill == pytest.approx(expected, rel=0.06)


def test_anisotropic_friction_acts_axially_and_transversally_with_its_own_coefficient():
    # on a 20 deg slope: transverse friction angle 5.7 deg (slides), axial 38.7 deg (sticks)
    friction = Friction(model="anisotropic", mu_axial=0.8, mu_transverse=0.1, v_threshold=0.01)
    a = np.radians(20.0)
    fall_line = np.array([np.cos(a), 0.0, np.sin(a)])
    across, _ = slide(*lying_line(np.array([0.0, 1.0, 0.0]), 20.0, friction))
    along, _ = slide(*lying_line(fall_line, 20.0, friction))
    assert -across @ fall_line > 1.0  # slides down across the line, metres in 2 s
    assert np.linalg.norm(along) < 2.0 * 0.01 * np.tan(a) / 0.8 * 1.05  # creeps at most


def test_run_stopped_early_leaves_valid_outputs(tmp_path, monkeypatch):
    pyvista = pytest.importorskip("pyvista")
    from cablefem.dynamics.group import Group
    from cablefem.io.vtk import read_collection
    from cablefem.runs.run import run_scene
    from cablefem.model.builtin import default_scene

    scene = default_scene()
    calls = {"n": 0}
    original = Group.march

    def interrupted(self, times):  # run_scene marches from one output time (every 0.1 s) to the next
        calls["n"] += 1
        if calls["n"] > 3:
            raise KeyboardInterrupt
        return original(self, times)

    monkeypatch.setattr(Group, "march", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_scene(scene, str(tmp_path), duration=10.0, dt=0.01)
    times, frames = read_collection(tmp_path / f"{scene.name}.pvd")
    assert len(frames) == 4  # t = 0, 0.1, 0.2, 0.3 s: every 0.1 s up to the interruption
    np.testing.assert_allclose(times, [0.0, 0.1, 0.2, 0.3], atol=1e-9)
    mesh = pyvista.read(frames[-1])
    assert mesh.n_points == scene.lines[0].segments[0].elements + 1
    assert np.all(np.isfinite(mesh["tension"])) and mesh["tension"].min() > 0
    rows = np.loadtxt(tmp_path / "tensions.csv", delimiter=",", skiprows=1)
    assert len(rows) == 31 and np.allclose(np.diff(rows[:, 0]), 0.01)
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["completed"] is False and summary["status"] == "interrupted"
    assert summary["steps"] == 30
    assert os.path.isfile(tmp_path / "seabed.vtu")


@pytest.mark.parametrize("integrator", ["bdf2", "generalized-alpha"])
def test_adaptive_steps_follow_their_tolerance(tmp_path, integrator):
    """Error-controlled steps of either scheme (its own local error: Milne's device for BDF2, the
    Newmark family's for generalised-alpha) follow the tolerance."""
    from dataclasses import replace

    from cablefem.post import read_tensions
    from cablefem.runs.run import run_scene
    from cablefem.model.builtin import flume_scene

    def fairlead_tension(out, **solver):
        scene = flume_scene("flat", "quasi-static", elements=20, duration=4.0)
        scene.solver = replace(scene.solver, tolerance=1e-9, **solver)
        scene.output = replace(scene.output, every=0.5)
        summary = run_scene(scene, str(tmp_path / out), progress=False)
        data = read_tensions(str(tmp_path / out))
        frames = np.isin(np.round(data["t"], 9), np.arange(0.0, 4.01, 0.5))
        return data["fairlead_tension"][frames], summary

    reference, _ = fairlead_tension("ref", dt=0.002)
    loose, s_loose = fairlead_tension("loose", adaptive=True, dt=0.2, error_tolerance=1e-3, integrator=integrator)
    tight, s_tight = fairlead_tension("tight", adaptive=True, dt=0.2, error_tolerance=1e-5, integrator=integrator)
    e_loose = np.abs(loose - reference).max() / reference.max()
    e_tight = np.abs(tight - reference).max() / reference.max()
    # a hundred times tighter: more (smaller) steps and a smaller error (second order: ~ tol^(2/3))
    assert s_tight["steps"] > 2 * s_loose["steps"]
    assert e_tight < e_loose / 3, (e_loose, e_tight)


def test_collection_lists_every_frame_after_each_frame(tmp_path):
    """The .pvd is rewritten after every frame (so a run killed outright lists every complete
    frame); past ``every_frame`` frames at most every ``refresh`` seconds, and in full by
    ``close``. What it lists is always a valid collection of files that exist."""
    from cablefem.io.vtk import TimeSeriesWriter, polyline_mesh, read_collection

    writer = TimeSeriesWriter(str(tmp_path), "run", refresh=3600.0, every_frame=3)
    line = {"points": np.array([[0.0, 0, 0], [1.0, 0, 0]]), "tension": np.array([1.0, 2.0])}
    listed = []
    for k in range(5):
        writer.write(0.1 * k, polyline_mesh([line]))
        listed.append(len(read_collection(tmp_path / "run.pvd")[0]))
    assert listed == [1, 2, 3, 3, 3]  # after the third frame, not due again for an hour
    writer.close()
    times, files = read_collection(tmp_path / "run.pvd")
    np.testing.assert_allclose(times, [0.0, 0.1, 0.2, 0.3, 0.4])
    assert all(os.path.isfile(f) for f in files)
    assert sorted(os.listdir(tmp_path)) == ["run.pvd"] + [f"run_{k:05d}.vtu" for k in range(5)]  # no temporaries


def test_compiled_adaptive_steps_grow_as_the_python_ones(tmp_path, monkeypatch):
    """The compiled steps end on splits of the output interval, so an adaptive step is cut back to
    the split before it; a cut step still proposes a longer next one where its error allows. (When
    a cut step proposed nothing, the compiled steps never grew: 765 steps where the Python ops took
    498 on this run, and OC4's chains failed to converge at t = 14.5 s.) Both faces: the same steps
    to 10 % and the same tensions to the tolerance's order."""
    from dataclasses import replace

    from cablefem.dynamics import group
    from cablefem.io import load_scene
    from cablefem.post import read_tensions
    from cablefem.runs.run import run_scene

    scene = load_scene(Path(__file__).resolve().parents[1] / "examples" / "flume_flat.toml")
    scene.solver = replace(scene.solver, adaptive=True, dt=0.05)
    compiled = run_scene(scene, str(tmp_path / "compiled"), duration=4.0, progress=False)
    original = group.Group.__init__

    def python_only(self, *args, **kwargs):
        original(self, *args, **kwargs)
        self.packer = None

    monkeypatch.setattr(group.Group, "__init__", python_only)
    python = run_scene(scene, str(tmp_path / "python"), duration=4.0, progress=False)
    assert abs(compiled["steps"] - python["steps"]) <= 0.1 * python["steps"], (compiled["steps"], python["steps"])
    a, b = (read_tensions(str(tmp_path / name))["fairlead_tension"] for name in ("compiled", "python"))
    assert np.abs(a - b).max() <= 10 * scene.solver.error_tolerance * b.max()


def test_adaptive_steps_that_cannot_meet_their_error_stop_with_the_solvers_message(tmp_path):
    """A light chain whose fairlead heaves 1.5 m every 3 s without a ramp: adaptive BDF2 cannot keep its
    steps' error and Newton's residual within their tolerances. The run stops with a ConvergenceError
    that says where and what to try (a step whose error never fell used to shrink without a floor
    until the compiled step divided by zero)."""
    from cablefem.errors import ConvergenceError
    from cablefem.runs.run import run_scene
    from test_failures import HEAVE, hang_scene

    scene = hang_scene(tmp_path, HEAVE, duration=4.0, solver="adaptive = true\n", name="heave.toml")
    with pytest.raises(ConvergenceError, match=r"at t = [0-9.]+ s .*dt = .*try "):
        run_scene(scene, str(tmp_path / "out"), progress=False)


@pytest.mark.parametrize("order", [1, 2])
def test_the_step_error_is_the_tension_the_difference_makes(order):
    """``Integrator.tension_error``: the difference dX between a step's positions and a solution of
    lower order, as a tension, EA t . d(dX)/ds over the line's largest tension. A transverse
    difference that is linear along the line (a rotation of the taut line, to first order) makes
    no tension: no error; a uniform axial stretch of it, EA times the strain it adds; the sum,
    the axial one's (the full vector |d(dX)/ds| counted a seabed strike's sideways difference as
    tension: the error control rejected OC4's steps down to 1 ms, tests/test_defaults.py)."""
    system, X, line_type = taut_line(order, 8)
    integ = BDF2(system, X, lambda t: (system.line.fairlead, np.zeros(3), np.zeros(3)), dt=0.01)
    s = X[:, 0] / 101.0
    sideways = np.column_stack([0 * s, 1e-3 * s, -2e-3 * s])
    along = np.column_stack([1e-4 * X[:, 0], 0 * s, 0 * s])
    tension = line_type.EA * 0.01
    assert integ.tension_error(X - sideways, X) < 1e-12
    assert integ.tension_error(X - along, X) == pytest.approx(line_type.EA * 1.01e-4 / tension, rel=1e-9)
    assert integ.tension_error(X - along - sideways, X) == pytest.approx(line_type.EA * 1.01e-4 / tension,
                                                                            rel=1e-5)


def test_generalised_alpha_end_force_is_its_balance_not_the_states_strain(tmp_path):
    """On the lazy wave of validation/cables (a clamped cable whose hang-off moves 6 m in 12 s, EA / T
    ~ 3e4), generalised-alpha's hang-off force at 80 steps a period is as close to BDF2's at dt 0.01 s
    as BDF2's own at that step: the force is the rows where the scheme balances them (t_{n+1-alpha_f}).
    The loads at the state X_{n+1} put a strain EA alpha_f dtheta^2 / 2 too large into it where the
    cable turns by dtheta in a step: 94 % RMS error here (GeneralizedAlpha's docstring)."""
    from cablefem.fem.system import build_system
    from cablefem.model.network import boundary_path
    from validation.cables import case

    scene = case.cablefem_scene(case.segments_for(20.0), tmp_path)  # 13 Hermite elements
    line = scene.lines[0]
    static = build_system(scene, line, dynamic=False)
    X0 = solve_static(static).X
    times = 0.3 * np.arange(1, 74)  # the 10 s ramp and one period
    after = times >= 10.0

    def tension(cls, dt):
        integ = cls(build_system(scene, line, dynamic=True, fem=static.fem), X0, boundary_path(scene, line), dt=dt)
        forces = []
        for t in times:
            integ.march(np.linspace(integ.t, t, int(round((t - integ.t) / dt)) + 1)[1:])
            forces.append(integ.reactions()[0])
        return np.linalg.norm(forces, axis=1)[after]

    reference = tension(BDF2, 0.01)
    rms = {cls: np.sqrt(np.mean((tension(cls, 0.15) - reference) ** 2)) / reference.mean()
           for cls in (BDF2, GeneralizedAlpha)}
    # measured: BDF2 0.49 %, generalised-alpha 0.76 % (its balance carried on to t_{n+1}; as it is,
    # lagging alpha_f h = 0.05 s, 0.81 %), the loads at the state 94 %; the bounds leave twice the
    # measured errors
    assert rms[BDF2] < 0.01 and rms[GeneralizedAlpha] < 0.015, rms


def test_the_step_error_is_relative_to_the_starting_tension_where_the_line_is_slacker():
    """The error control's tension scale does not fall below the line's largest tension at the start
    (``clock["tension_scale"]``): a line gone slack is held to the error its pretension allows, not to
    a fraction of its near-zero tension (OC4's line 2, slack for 4 s of each 10 s period, took 100-146
    steps a second there at 3e-4 against 20 elsewhere; generalised-alpha failed at t = 24.5 s)."""
    system, X, line_type = taut_line(2, 8)
    integ = BDF2(system, X, lambda t: (system.line.fairlead, np.zeros(3), np.zeros(3)), dt=0.01)
    assert integ.clock["tension_scale"][0] == pytest.approx(line_type.EA * 0.01, rel=1e-12)
    slack = X / 1.01  # unstretched: no tension
    along = np.column_stack([1e-4 * slack[:, 0], 0 * slack[:, 0], 0 * slack[:, 0]])
    assert integ.tension_error(slack - along, slack) == pytest.approx(1e-4 / 0.01, rel=1e-9)
    # taut beyond the start, the line's own largest tension is the scale
    tauter = X * 1.02 / 1.01
    assert integ.tension_error(tauter - along, tauter) == pytest.approx(1e-4 / 0.02, rel=1e-9)
