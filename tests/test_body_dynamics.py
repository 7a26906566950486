"""Free rigid bodies in time (``cablefem.dynamics.body_group``, ``cablefem.loads.body``): energy
conserved where nothing dissipates, the statics reached again by a damped run, the body's own
rows' tangent, and ``cablefem run`` on a scene with a free body."""

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cablefem.dynamics.body_group import body_groups
from cablefem.dynamics.energy import stored_energy
from cablefem.dynamics.registry import INTEGRATORS, integrator_options
from cablefem.io import load_scene
from cablefem.loads.body import BodyLoads
from cablefem.model.network import Body, anchor_path, boundary_path
from cablefem.model.scene import Environment
from cablefem.statics.scene import network_start

BUOY = Path(__file__).parent / "data" / "free_buoy.toml"


def start(scene, integrator, dt, **solver):
    """The integrators of ``scene``'s lines from its statics and the body group that steps them."""
    scene = replace(scene, solver=replace(scene.solver, integrator=integrator, **solver))
    systems, states, _, network = network_start(scene)
    integrators = [INTEGRATORS[integrator](system, X, boundary_path(scene, line), dt=dt, anchor=anchor_path(scene, line),
                                           **integrator_options(scene.solver))
                   for system, line, X in zip(systems, scene.lines, states)]
    group, = body_groups(scene, integrators, network.poses)
    return integrators, group, network


def total_energy(integrators, body):
    """The body's kinetic and potential energy and each line's kinetic, strain and gravity energy [J]."""
    return body.loads.energy(body.X, body.V) + sum(
        sum(stored_energy(m.system, m.X, m.V, m.M).values()) for m in integrators)


def energy_history(integrator, dt, duration, velocity):
    scene = load_scene(BUOY)
    integrators, group, _ = start(scene, integrator, dt, rho_inf=1.0)
    body = group.bodies[0]
    group.set_velocity(body, velocity)
    energy = [total_energy(integrators, body)]
    for _ in range(int(round(duration / dt))):
        group.step(dt)
        energy.append(total_energy(integrators, body))
    kinetic = body.loads.energy(body.X, body.V) - body.loads.energy(body.X, 0.0 * body.V)
    return np.array(energy), kinetic


#: a start with every one of the six rates, small enough that no element of the lines goes slack (a
#: slack element's kink in the tension law is where the trapezoidal rule stops conserving energy)
RATES = [[0.05, 0.03, 0.1], [0.01, 0.01, 0.005]]


def test_generalised_alpha_with_rho_one_conserves_a_free_body_s_energy():
    """Generalised-alpha with rho_inf = 1 is the trapezoidal rule: on a body on elastic lines without
    drag, damping or seabed, the total energy stays within 1e-3 of the kinetic energy it starts with
    over 40 steps (3e-4 measured: the rule conserves a quadratic energy exactly, the lines' and the
    rotations' nonlinearity leaves an O(h^2) oscillation; a lever arm or a gyroscopic term left out
    of the body's rows loses or makes percents of it)."""
    energy, _ = energy_history("generalized-alpha", 0.05, 2.0, RATES)
    start_kinetic = 0.5 * 40000.0 * (0.05 ** 2 + 0.03 ** 2 + 0.1 ** 2)  # the body's translation alone
    assert np.max(np.abs(energy - energy[0])) < 1e-3 * start_kinetic


def test_bdf2_only_dissipates_a_free_body_s_energy():
    """BDF2 damps where generalised-alpha at rho_inf = 1 conserves: from the same start its total
    energy never rises by more than the latter's error bound (1e-3 of the start's kinetic energy)
    and it ends below its start by more than a tenth of that kinetic energy (the lines' unresolved
    modes, which the start's velocity jump at the fairleads excites, are damped at any step)."""
    energy, _ = energy_history("bdf2", 0.05, 2.0, [[0.0, 0.0, 0.3], [0.0, 0.0, 0.0]])
    start_kinetic = 0.5 * 40000.0 * 0.3 ** 2
    assert np.max(energy - energy[0]) < 1e-3 * start_kinetic
    assert energy[0] - energy[-1] > 0.1 * start_kinetic


def test_a_damped_run_from_a_perturbed_start_ends_at_the_statics():
    """A body with drag pushed from its equilibrium (BDF2 with 2 s steps damps it too) comes back to
    the pose network statics found: after 120 s its distance from it is below 2 % of its largest
    excursion (0.4 % measured; the surge and yaw of a buoy on three lines are slow and lightly damped),
    and the statics' pose is where it settles, not a pose of its own (the pose's error falls)."""
    scene = load_scene(BUOY)
    body = replace(scene.bodies["buoy"], CdA=np.full(6, 2000.0), Ca=np.full(6, 0.5))
    scene = replace(scene, bodies={**scene.bodies, "buoy": body})
    integrators, group, network = start(scene, "bdf2", 2.0)
    group.set_velocity(group.bodies[0], [[0.1, -0.1, 0.4], [0.02, 0.02, 0.05]])
    expected = network.poses["buoy"]
    distance = []
    for _ in range(60):
        group.step(2.0)
        error = group.bodies[0].absolute(group.bodies[0].X) - expected
        distance.append(max(np.max(np.abs(error[:3])), np.max(np.abs(error[3:])) * group.bodies[0].length))
    assert distance[-1] < 0.02 * max(distance)
    assert max(distance[-10:]) < 0.1 * max(distance[:10])


def test_the_body_rows_tangent_is_their_derivative():
    """``RigidBody``'s tangent of a body with drag, added mass and an offset centre of gravity equals
    the rows' central differences in the trial pose to 1e-6 relative."""
    scene = load_scene(BUOY)
    integrators, group, _ = start(scene, "generalized-alpha", 0.05, rho_inf=0.7)
    body = group.bodies[0]
    body.loads = BodyLoads(replace(scene.bodies["buoy"], CdA=np.full(6, 30.0), Ca=np.full(6, 0.8)),
                           scene.environment)
    group.set_velocity(body, [[0.2, -0.1, 0.3], [0.1, 0.2, -0.1]])
    body.begin(0.05)
    X1 = body.guess + np.array([[0.01, -0.02, 0.03], [0.05, -0.04, 0.03]])
    _, tangent = body.rows_and_tangent(X1, True)
    numeric = np.empty((6, 6))
    for j in range(6):
        plus, minus = X1.copy(), X1.copy()
        plus.flat[j] += 1e-5
        minus.flat[j] -= 1e-5
        numeric[:, j] = (body.rows_and_tangent(plus, False)[0] - body.rows_and_tangent(minus, False)[0]) / 2e-5
    assert np.max(np.abs(tangent - numeric)) < 1e-6 * np.max(np.abs(numeric))


def test_drag_and_added_mass_are_moordyn_c_s():
    """At rest the rows are weight and buoyancy; a body moving at u through still water feels
    0.5 rho CdA |u| u against it, accelerating at a needs (m + rho V Ca) a (MoorDyn-C's Body.cpp)."""
    environment = Environment(water_density=1025.0, gravity=9.81)
    body = Body("b", "free", [0.0, 0.0, -10.0], mass=2000.0, inertia=[100.0, 100.0, 100.0], volume=3.0,
                CdA=[2.0, 3.0, 4.0, 0.0, 0.0, 0.0], Ca=[0.5, 0.5, 1.0, 0.0, 0.0, 0.0])
    loads = BodyLoads(body, environment)
    X = np.array([[0.0, 0.0, -10.0], [0.0, 0.0, 0.0]])
    V = np.array([[1.0, -2.0, 0.5], [0.0, 0.0, 0.0]])
    A = np.array([[0.1, 0.2, -0.3], [0.0, 0.0, 0.0]])
    rows = loads.residual(X, V, A)
    speed = np.linalg.norm(V[0])
    expected = (np.array([2000 + 1025 * 3 * 0.5, 2000 + 1025 * 3 * 0.5, 2000 + 1025 * 3 * 1.0]) * A[0]
                + 0.5 * 1025 * np.array([2.0, 3.0, 4.0]) * speed * V[0] + [0.0, 0.0, (2000 - 1025 * 3) * 9.81])
    assert np.allclose(rows[:3], expected, rtol=1e-13, atol=1e-9)
    assert np.allclose(rows[3:], 0.0, atol=1e-9)


def test_cablefem_run_steps_a_free_body(tmp_path):
    """``cablefem run`` on a scene with a free body runs (no refusal), starting from its statics: at
    rest nothing moves, the body's pose columns stay at the statics' pose (1e-6 m) and the lines'
    fairlead forces at their static values."""
    from cablefem.runs.run import run_scene

    scene = load_scene(BUOY)
    scene = replace(scene, solver=replace(scene.solver, duration=0.5, dt=0.1))
    summary = run_scene(scene, out_dir=tmp_path)
    assert summary["completed"]
    table = np.genfromtxt(tmp_path / "tensions.csv", delimiter=",", names=True)
    _, _, _, network = network_start(scene)
    for k, axis in enumerate("xyz"):
        assert np.allclose(table[f"bodybuoy{axis}"], network.poses["buoy"][k], atol=1e-6)
    json.loads((tmp_path / "summary.json").read_text())


def test_body_drag_runs_at_pitch_minus_90_deg_and_its_statics_is_where_moordyn_c_settles(tmp_path):
    """MoorDyn's body_tests/bodyDrag.txt: its free body hangs below its anchor at pitch -90 deg, where
    roll, pitch and yaw are singular; its angles are stepped from its start orientation, so a run from
    the statics goes and stays there (1e-6 m). MoorDyn-C (TmaxIC 0: no initial-condition solve, its
    first tensions those of the file's pose, the body 5 m above the anchor on a 4.5 m spring: the
    corpus's 232 %) lets the body fall and settles after 60 s where cablefem's statics has it (1e-4 m)."""
    from cablefem.runs.run import run_scene

    path = Path(__file__).parent / "data" / "moordyn" / "laws" / "bodyDrag.txt"
    scene = load_scene(path)
    summary = run_scene(scene, tmp_path, duration=0.5, dt=0.05)
    assert summary["completed"]
    table = np.genfromtxt(tmp_path / "tensions.csv", delimiter=",", names=True)
    _, _, _, network = network_start(scene)
    pose = network.poses["body1"]
    assert abs(np.degrees(pose[4]) + 90.0) < 1e-6
    np.testing.assert_allclose(table["bodybody1z"], pose[2], atol=1e-6)
    moordyn = pytest.importorskip("moordyn")
    from validation.moordyn.peer import silenced_stdout

    with silenced_stdout():
        system = moordyn.Create(str(path))
        moordyn.Init(system, [], [])
        body = moordyn.GetBody(system, 1)
        for k in range(120):
            moordyn.Step(system, [], [], 0.5 * k, 0.5)
        settled = np.array(moordyn.GetBodyState(body)[0])
        moordyn.Close(system)
    assert abs(settled[2] - pose[2]) < 1e-4
