"""Currents that vary with depth (issue 18): a line hanging in a sheared current against an independent
integration of the cable's equilibrium, the uniform case bitwise unchanged, and the profile's readers."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from cablefem.dynamics.bdf2 import BDF2
from cablefem.errors import InputError
from cablefem.geometry import Horizontal
from cablefem.io.currents import current_profile_setting, read_current_profile
from cablefem.model.line import Joint, Line, LineType, Segment
from cablefem.loads.current import MAX_HEIGHTS, CurrentProfile
from cablefem.model.scene import Contact, Environment
from cablefem.statics.solve import solve_static
from cablefem.fem.system import LineSystem

RHO, G = 1025.0, 9.81
ROPE = LineType("rope", diameter=0.05, mass=3.0, EA=2.0e5, damping=0.05, Cd_normal=1.2, Cd_tangential=0.3,
                Ca_normal=1.0)
CLUMP = Joint("clump", mass=40.0, volume=0.01, CdA=0.3, Ca=1.0)
#: sheared along x, turning towards y near the surface; bends at -30 and -10 m, constant below -50 m
PROFILE = CurrentProfile.from_arrays([-50.0, -30.0, -10.0, 0.0],
                                     [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.3, 0.0], [1.2, 0.3, 0.0]], "test")
TOP = np.array([0.0, 0.0, -2.0])
LENGTH = 40.0
STEP, STEPS = 5.0, 200


def hanging_line(elements, order):
    """The rope hanging from TOP (its fairlead end, prescribed), the clump on its free lower end."""
    return Line("hang", TOP - [0.0, 0.0, LENGTH], TOP, (Segment(ROPE, LENGTH, elements),), order,
                joints=((0, CLUMP),), prescribed=(False, True))


def settled_in_current(line, profile):
    """The line at rest in the current: BDF2 with large steps from the still-water statics until the
    velocities vanish (the static equilibrium with drag at zero velocity). The state X (N, 3), the
    line's FEM and the force on the top [N]."""
    env = Environment(RHO, G, current_profile=profile)
    static = LineSystem(line, Horizontal(500.0), Contact(), env)
    X0 = solve_static(static).X
    system = LineSystem(line, Horizontal(500.0), Contact(), env, dynamic=True, fem=static.fem)

    def top(t):
        return TOP.copy(), np.zeros(3), np.zeros(3)

    integ = BDF2(system, X0, top, dt=STEP)  # steps of 5 s damp the ~12 s pendulum in a few periods
    integ.march(np.arange(1, STEPS + 1) * STEP)
    assert np.abs(integ.V).max() < 1e-9  # at rest
    zero = np.zeros_like(integ.X)  # drag needs the (zero) velocities
    return integ.X, system.fem, -system.residual(integ.X, zero, zero)[system.fem.fairlead_dof]


def equilibrium_by_integration(profile):
    """The same rope's equilibrium integrated along its unstretched length from the free end up
    (independent of the FEM): the internal force N(s) = EA e t with dN/ds = -f(r, N) (weight in water
    and Morison drag in the current at the local height, per unstretched length, the stretch 1 + e
    times the drag per stretched length), N(0) = -(the clump's weight in water and drag), dr/ds =
    (1 + e) t; the bottom's position is shot until the top lands on TOP. Returns r(s) (callable)
    and N(L)."""
    area = np.pi * ROPE.diameter ** 2 / 4
    weight = np.array([0.0, 0.0, -(ROPE.mass - RHO * area) * G])
    half_rho_d = 0.5 * RHO * ROPE.diameter

    def current(z):
        U, _ = profile.at(np.array([z]))
        return U[:, 0]

    def rhs(s, y):
        N, r = y[:3], y[3:]
        tension = np.linalg.norm(N)
        t, stretch = N / tension, 1.0 + tension / ROPE.EA
        u = current(r[2])
        along = u @ t
        normal = u - along * t
        drag = half_rho_d * (ROPE.Cd_normal * np.linalg.norm(normal) * normal
                             + ROPE.Cd_tangential * abs(along) * along * t)
        return np.concatenate([-(weight + stretch * drag), stretch * t])

    def shoot(bottom):
        U = current(bottom[2])
        clump = (np.array([0.0, 0.0, (RHO * CLUMP.volume - CLUMP.mass) * G])
                 + 0.5 * RHO * CLUMP.CdA * np.linalg.norm(U) * U)
        return solve_ivp(rhs, (0.0, LENGTH), np.concatenate([-clump, bottom]), method="DOP853", rtol=1e-12,
                         atol=1e-12, dense_output=True, max_step=0.25)

    bottom = TOP - [0.0, 0.0, LENGTH]
    for _ in range(60):  # the top depends on the bottom's position only through U(z): a contraction
        solution = shoot(bottom)
        miss = TOP - solution.y[3:, -1]
        bottom = bottom + miss
        if np.abs(miss).max() < 1e-11:
            break
    assert np.abs(miss).max() < 1e-11
    return (lambda s: solution.sol(s)[3:].T), solution.y[:3, -1]


def test_a_line_hanging_in_a_sheared_current_takes_the_integrated_shape():
    """P2 FEM at rest in the sheared current against the ODE: the line within 1e-5 m of the integrated
    curve (the rope drifts ~17 m; the discretisation error of 80 P2 elements is 2e-6 m, of 40 9e-5 m,
    measured: the profile's kinks limit the order) and the force on the top, -N(L), within 1e-6."""
    line = hanging_line(80, 2)
    X, fem, top_force = settled_in_current(line, PROFILE)
    curve, N_top = equilibrium_by_integration(PROFILE)
    s = np.linspace(0.0, LENGTH, 161)  # the free end first
    shape = fem.evaluate(X, s)
    assert np.linalg.norm(shape[0] - (TOP - [0.0, 0.0, LENGTH])) > 5.0  # the current really moved it
    np.testing.assert_allclose(shape, curve(s), rtol=0, atol=1e-5)
    np.testing.assert_allclose(top_force, -N_top, rtol=0, atol=1e-6 * np.linalg.norm(N_top))


def test_a_profile_of_one_height_drags_as_the_uniform_current_does(rng):
    """A profile that is the same at every height gives the uniform current's residual and tangent,
    on the numpy face and on the compiled one (to round-off: the same sums)."""
    from cablefem.compiled.evaluator import FusedEvaluator

    line = hanging_line(10, 2)
    results, draws = [], rng.standard_normal((2, 21, 3))
    for env in (Environment(RHO, G, current=(0.6, 0.2, 0.0)),
                Environment(RHO, G, current_profile=CurrentProfile.from_arrays([-20.0], [[0.6, 0.2, 0.0]], "k"))):
        system = LineSystem(line, Horizontal(500.0), Contact(), env, dynamic=True)
        X = system.fem.interpolate(lambda s: np.column_stack([0.3 * np.sin(s / 7), 0 * s, s - 42.0]))
        V, A = draws
        rows, band = FusedEvaluator.for_system(system, system.props["mass"]).evaluate(X, V, A, 150.0, 2.2e4)
        results.append((system.residual(X, V, A), rows, band))
    for uniform, profile in zip(*results):
        np.testing.assert_allclose(profile, uniform, rtol=0, atol=1e-13 * np.abs(uniform).max())


def test_profile_is_linear_between_heights_and_constant_beyond_as_moordyn_interpolates():
    U, slope = PROFILE.at(np.array([-80.0, -50.0, -40.0, -30.0, -20.0, -5.0, 3.0]))
    np.testing.assert_allclose(U[0], [0.0, 0.0, 0.25, 0.5, 0.75, 1.1, 1.2], rtol=0, atol=1e-15)
    np.testing.assert_allclose(slope[0], [0.0, 0.0, 0.025, 0.025, 0.025, 0.02, 0.0], rtol=0, atol=1e-15)


def test_straight_runs_of_a_profile_are_dropped_and_a_long_bent_one_is_refused():
    z = np.linspace(-100.0, 0.0, 200)
    straight = CurrentProfile.from_arrays(z, np.column_stack([0.01 * z + 1.0, 0 * z, 0 * z]), "k")
    assert straight.z == (-100.0, 0.0)
    with pytest.raises(InputError, match=f"keeps at most {MAX_HEIGHTS}"):
        CurrentProfile.from_arrays(z, np.column_stack([np.sin(z), 0 * z, 0 * z]), "k")


def test_current_profile_files_and_tables_are_read_and_checked(tmp_path):
    path = tmp_path / "current_profile.txt"
    path.write_text("--- MoorDyn steady currents File ---\nTabulated file\nz (m), ux (m/s), uy (m/s), uz (m/s)\n"
                    "-50 0.0\n-10 1.0 0.5\n0 1.0 0.5 0.1\n")
    profile = read_current_profile(str(path), "k")
    assert profile.z == (-50.0, -10.0, 0.0)
    assert profile.velocity == ((0.0, 0.0, 0.0), (1.0, 0.5, 0.0), (1.0, 0.5, 0.1))
    inline = current_profile_setting({"z": [-50, -10, 0], "velocity": [[0, 0, 0], [1, 0.5, 0], [1, 0.5, 0.1]]},
                                     "environment.current_profile", str(tmp_path))
    assert inline.z == profile.z and inline.velocity == profile.velocity
    path.write_text("-50 0.0\n-10 1.0\n0 1.0\n1 1.0\n")
    with pytest.raises(InputError, match="line 1: holds numbers, but the first 3 lines are a header"):
        read_current_profile(str(path), "k")
    path.write_text("h\nh\nh\n-10 1.0\n-50 0.0\n")
    with pytest.raises(InputError, match="heights must strictly increase"):
        read_current_profile(str(path), "k")
    with pytest.raises(InputError, match="environment.current_profile.velocity"):
        current_profile_setting({"z": [-50, 0], "velocity": [[0, 0, 0]]}, "environment.current_profile", ".")
