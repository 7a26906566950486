"""Free rods and rods on free bodies in time (``cablefem.loads.rod_body``, issue 36): a floating rod's
heave against its closed form, its energy conserved where nothing dissipates and lost where its end
drags, a spinning rod's own inertial terms, a free body's rows with a rod the sum of the body's and
the rod's, and a run of MoorDyn's RodHanging.txt from its statics at rest."""

import math
import os
from dataclasses import replace

import numpy as np

from cablefem.dynamics.registry import INTEGRATORS
from cablefem.dynamics.rigid_body import RigidBody
from cablefem.io import load_scene
from cablefem.loads.body import BodyLoads
from cablefem.loads.rod import mass_matrix
from cablefem.loads.rod_body import Loads, RodPart, body_loads
from cablefem.model.network import Body, rotation
from cablefem.model.rod import Rod, RodType, rod_body
from cablefem.model.scene import Environment
from cablefem.statics.rods import carried_terms

RHO, G = 1025.0, 9.81
WATER = Environment(water_density=RHO, gravity=G)
HERE = os.path.dirname(__file__)


def free_rod(rod, pose, integrator, velocity=None, **options):
    """A ``RigidBody`` of free ``rod`` (no lines) at ``pose`` (6,) stepped by ``integrator``."""
    stepper = INTEGRATORS[integrator]
    parameters = np.zeros(1, stepper.scheme.parameters)
    if integrator == "generalized-alpha":
        r = options["rho_inf"]
        alpha_m, alpha_f = (2 * r - 1) / (r + 1), r / (r + 1)
        parameters[0] = (alpha_m, alpha_f, 0.5 - alpha_m + alpha_f, 0.25 * (1 - alpha_m + alpha_f) ** 2)
    body = RigidBody(rod.name, body_loads(rod_body(rod, Body), WATER), pose, stepper.scheme, parameters, [],
                     velocity=velocity)
    body.A = body.initial_acceleration(np.zeros(6))
    return body


def step(body, h, tolerance=1e-10):
    """One step of ``body`` alone: Newton on its rows to ``tolerance`` of its weight (the body group's
    condensation with no strings; the rows' round-off is ~3e-12 of it)."""
    body.begin(h)
    body.X1 = body.guess.copy()
    for _ in range(20):
        body.evaluate(True)
        if np.max(np.abs(body.rows)) < tolerance * body.loads.weight:
            break
        body.X1 = body.X1 + np.linalg.solve(body.tangent, -body.rows).reshape(2, 3)
    else:
        raise AssertionError("Newton did not converge")
    body.accept(h)


#: a rod floating upright, 0.6 of water's density: 6 m of its 10 m under the surface at rest
SPAR = RodType("spar", 0.5, 0.6 * RHO * math.pi / 4 * 0.25, 0.0, 1.0, 0.0, 1.0)


def heave(rod_type, integrator, periods, steps_per_period, depth=0.1, **options):
    """A rod of ``rod_type`` released upright ``depth`` [m] below its floating draft: its heave z of
    end A over time (n,) [s], its energy (n,) [J], its period's closed form [s] and draft [m]."""
    L, area = 10.0, math.pi / 4 * rod_type.diameter ** 2
    draft = rod_type.mass_per_length * L / (RHO * area)
    rod = Rod("rod1", rod_type, [0.0, 0.0, -draft - depth], [0.0, 0.0, L - draft - depth])
    added = RHO * rod_type.CaEnd * 2.0 / 3.0 * math.pi * (rod_type.diameter / 2) ** 3  # the submerged end's
    period = 2 * math.pi * math.sqrt((rod.mass + added) / (RHO * G * area))
    h = period / steps_per_period
    body = free_rod(rod, np.concatenate([rod.end_a, np.zeros(3)]), integrator, **options)
    z, energy = [body.X[0, 2]], [body.loads.energy(body.X, body.V)]
    for _ in range(int(periods * steps_per_period)):
        step(body, h)
        z.append(body.X[0, 2])
        energy.append(body.loads.energy(body.X, body.V))
    return h * np.arange(len(z)), np.array(z), np.array(energy), period, draft


def test_a_floating_rod_heaves_at_the_period_of_its_waterplane_spring_and_mass():
    """An upright rod released 0.1 m below its draft (no drag) heaves about -draft at 2 pi sqrt((m +
    rho CaEnd V_end) / (rho g A)): its period from the upward zero crossings within 1e-3 (the
    trapezoidal rule's period error at 100 steps a period is (omega h)^2 / 12 = 3e-4) and its
    amplitude 0.1 m within 1e-3 m; generalised-alpha with rho_inf = 1 conserves its energy to 1e-9
    of the spring's (the heave is linear while the surface stays on the rod)."""
    t, z, energy, period, draft = heave(SPAR, "generalized-alpha", 3, 100, rho_inf=1.0)
    x = z + draft
    up = [t[k] - x[k] * (t[k + 1] - t[k]) / (x[k + 1] - x[k]) for k in range(len(x) - 1) if x[k] < 0 <= x[k + 1]]
    measured = np.mean(np.diff(up))
    assert abs(measured / period - 1.0) < 1e-3, (measured, period)
    assert abs(np.max(np.abs(x)) - 0.1) < 1e-3
    spring = 0.5 * RHO * G * math.pi / 4 * SPAR.diameter ** 2 * 0.1 ** 2
    assert np.max(np.abs(energy - energy[0])) < 1e-9 * spring


def test_a_rod_dragging_at_its_end_settles_at_its_draft_and_bdf2_only_dissipates():
    """With drag at its ends (CdEnd 1.0) a released rod settles where its weight and buoyancy
    balance: after 40 periods under BDF2 at 8 steps a period (its own damping on top of the drag's,
    which alone decays a quadratic-drag oscillation only as 1/t) its end A is within 1e-3 of the
    0.1 m start offset of -draft (the closed form; network statics' balance of a free rod is the
    same ``static_loads``; 4e-6 measured), and its energy never rises (1e-9 of the spring's energy:
    the round-off of the energies' 7e4 J) and ends with all of the spring's energy gone."""
    dragging = replace(SPAR, CdEnd=1.0)
    _, z, energy, _, draft = heave(dragging, "bdf2", 40, 8)
    assert abs(z[-1] + draft) < 1e-3 * 0.1
    spring = 0.5 * RHO * G * math.pi / 4 * SPAR.diameter ** 2 * 0.1 ** 2
    assert np.max(np.diff(energy)) < 1e-9 * spring
    assert energy[0] - energy[-1] > 0.99 * spring


def test_a_spinning_rod_keeps_its_spin_and_its_energy():
    """A submerged rod as dense as the water, spinning end over end about its middle at 0.5 rad/s (no
    drag): its weight and buoyancy cancel at its middle and the added mass across it sees only the
    centripetal acceleration along it, so it spins on at 0.5 rad/s and its middle stays put. Its own
    centripetal and gyroscopic terms (``RodPart``) hold that: after a turn of 180 deg (generalised-
    alpha, rho_inf = 1, 200 steps) its roll rate is 0.5 rad/s within 1e-4, its middle within 1e-3 m
    of where it started (1.3e-4 m measured: end A's circle of 4 m stepped at omega h = 0.016) and its
    energy within 1e-6 of its kinetic energy. Without the centripetal terms (``turning``) the
    middle drifts by 0.4 m."""
    neutral = RodType("neutral", 0.4, RHO * math.pi / 4 * 0.16, 0.0, 1.0, 0.0, 1.0)
    L, spin = 8.0, 0.5
    rod = Rod("rod1", neutral, [0.0, 0.0, -24.0], [0.0, 0.0, -16.0])
    velocity = np.array([[0.0, spin * L / 2, 0.0], [spin, 0.0, 0.0]])  # end A circles the middle
    body = free_rod(rod, np.concatenate([rod.end_a, np.zeros(3)]), "generalized-alpha", velocity=velocity,
                    rho_inf=1.0)
    energy0 = body.loads.energy(body.X, body.V)
    kinetic = energy0 - body.loads.energy(body.X, 0 * body.V)
    h = math.pi / spin / 200
    for _ in range(200):
        step(body, h)
    middle = body.X[0] + body.rotation(body.X[1]) @ [0.0, 0.0, L / 2]
    assert abs(body.V[1, 0] - spin) < 1e-4 * spin
    np.testing.assert_allclose(middle, [0.0, 0.0, -20.0], atol=1e-3)
    assert abs(body.loads.energy(body.X, body.V) - energy0) < 1e-6 * kinetic


def test_a_pinned_rod_swings_about_its_pin_at_the_period_of_its_closed_form():
    """A buoyant rod (half the water's density) pinned at its lower end A under water, tilted 0.01 rad
    from upright (no drag): it swings about A at 2 pi sqrt(I_A / ((B - W) L / 2)), I_A = (m + rho Ca
    A) L^3 / 3 + m L r^2 / 4 (its line of mass and added mass across it, and its section's inertia
    across), B and W its buoyancy and weight: the period from the upward zero crossings of its tilt
    within 1e-3 (the trapezoidal rule's error at 100 steps a period, 3e-4, and the amplitude's,
    theta^2 / 16), and its pin gives by less than 2e-6 of its length (``PIN_GIVE`` under a force of
    its weight; Newton's tolerance 1e-8 here, the pin spring's round-off being 1e-9 of the weight)."""
    d, L = 0.4, 6.0
    area = math.pi / 4 * d * d
    light = RodType("light", d, 0.5 * RHO * area, 0.0, 1.0, 0.0, 1.0)
    tilt = 0.01
    a = np.array([0.0, 0.0, -20.0])
    rod = Rod("rod1", light, a, a + L * np.array([math.sin(tilt), 0.0, math.cos(tilt)]), pinned=True)
    m = rod.mass / L
    inertia = (m + RHO * area) * L ** 3 / 3 + m * L * (d / 2) ** 2 / 4
    period = 2 * math.pi * math.sqrt(inertia / ((RHO * area - m) * G * L * L / 2))
    h = period / 100
    body = free_rod(rod, np.concatenate([a, rod_body(rod, Body).rotation]), "generalized-alpha", rho_inf=1.0)
    t, angle, pin = [0.0], [tilt], 0.0
    for k in range(300):
        step(body, h, tolerance=1e-8)
        axis = body.rotation(body.X[1]) @ [0.0, 0.0, 1.0]
        t.append(body.t)
        angle.append(math.atan2(axis[0], axis[2]))
        pin = max(pin, float(np.max(np.abs(body.X[0] - a))))
    t, angle = np.array(t), np.array(angle)
    up = [t[k] - angle[k] * h / (angle[k + 1] - angle[k]) for k in range(len(t) - 1) if angle[k] < 0 <= angle[k + 1]]
    assert abs(np.mean(np.diff(up)) / period - 1.0) < 1e-3, (np.mean(np.diff(up)), period)
    assert pin < 2e-6 * L


def test_a_free_body_s_rows_with_a_rod_are_the_sum_of_the_body_s_and_the_rod_s():
    """A free body (turned, offset centre of gravity, added mass) carrying a rod that pierces the
    surface: at rest its rows are ``BodyLoads``' less network statics' weight and buoyancy of the rod
    (``cablefem.statics.rods.carried_terms``, a path of its own); its mass matrix is the body's plus
    the rod's 6 x 6 mass matrix about end A (``cablefem.loads.rod.mass_matrix``) moved to the body's
    reference point, [I 0; [p_A]x I] M [I -[p_A]x R_0; 0 R_0] at zero angles. 1e-10 relative."""
    rod = Rod("rod1", RodType("can", 0.8, 300.0, 1.0, 1.0, 0.5, 0.5), [0.5, 0.2, -1.0], [1.0, -0.3, 4.0])
    body = Body("buoy", "free", [2.0, 1.0, -2.0], [0.1, -0.2, 0.3], mass=5000.0, inertia=[4e3, 5e3, 6e3],
                volume=4.0, cg=[0.1, 0.0, -0.3], CdA=np.full(6, 3.0), Ca=np.full(6, 0.5), rods=(rod,))
    loads = body_loads(body, WATER)
    assert isinstance(loads, Loads)
    alone = BodyLoads(replace(body, rods=()), WATER)
    R0 = rotation(body.rotation)
    loads.frame = alone.frame = R0
    X = np.array([body.position, np.zeros(3)])
    zero = np.zeros((2, 3))
    statics, _ = carried_terms(body, np.concatenate([body.position, body.rotation]), RHO, G)
    expected = alone.residual(X, zero, zero) - statics
    np.testing.assert_allclose(loads.residual(X, zero, zero), expected, rtol=1e-10, atol=1e-10 * np.abs(expected).max())

    def skew(v):
        return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])

    arm = R0 @ rod.end_a
    a, b = body.position + arm, body.position + R0 @ rod.end_b
    left = np.block([[np.eye(3), np.zeros((3, 3))], [skew(arm), np.eye(3)]])
    right = np.block([[np.eye(3), -skew(arm) @ R0], [np.zeros((3, 3)), R0]])
    expected = alone.mass_matrix(X) + left @ mass_matrix(a, b, rod, RHO) @ right
    np.testing.assert_allclose(loads.mass_matrix(X), expected, rtol=1e-10, atol=1e-10 * np.abs(expected).max())


def test_a_free_rod_s_rows_are_its_rod_part_s():
    """A free rod's own loads in a run are one ``RodPart`` on its own frame (end A at the reference
    point, end B at (0, 0, L)): at rest, the weight and buoyancy of ``cablefem.loads.rod``."""
    from cablefem.loads.rod import static_loads

    rod = Rod("rod1", SPAR, [1.0, 2.0, -6.0], [4.0, 2.0, 2.0])
    loads = body_loads(rod_body(rod, Body), WATER)
    assert [type(part) for part in loads.parts] == [RodPart]
    loads.frame = rotation(rod_body(rod, Body).rotation)
    rows = loads.residual(np.array([rod.end_a, np.zeros(3)]), np.zeros((2, 3)), np.zeros((2, 3)))
    force, moment = static_loads(rod.end_a, rod.end_b, rod, RHO, G)
    np.testing.assert_allclose(rows, -np.concatenate([force, moment]), rtol=1e-12, atol=1e-9)


def test_moordyns_rod_hanging_holds_still_in_a_run_from_its_statics(tmp_path):
    """MoorDyn's RodHanging.txt (a free rod on two 450 m ropes) run for 2 s from its statics: the
    statics' equilibrium is the run's rest, the rod's end A moves by less than 1e-6 m (tensions.csv's
    10 digits of the 86 m depth) and its pitch by less than 1e-6 deg."""
    from cablefem.runs.run import run_scene

    scene = load_scene(os.path.join(HERE, "data", "moordyn", "RodHanging.txt"))
    summary = run_scene(scene, tmp_path, duration=2.0, dt=0.05)
    assert summary["completed"]
    table = np.genfromtxt(tmp_path / "tensions.csv", delimiter=",", names=True)
    for axis in "xyz":
        column = table[f"bodyrod1{axis}"]
        assert np.ptp(column) < 1e-6, (axis, np.ptp(column))
    assert np.ptp(table["bodyrod1pitch_deg"]) < 1e-6
