"""Statics and dynamics of lines longer than they need, lines whose two ends meet, buoyant lines and
lazy waves (issue 14): the starting shapes of ``cablefem.statics.start_shape``, the partially submerged
cross-section of ``cablefem.loads.gravity`` and the scale-free convergence test of statics."""

import numpy as np
import pytest
from moorpy.Catenary import catenary

from cablefem import ConvergenceError, Line, LineType, Segment
from cablefem.statics.catenary import elastic_catenary
from cablefem.dynamics.bdf2 import BDF2
from cablefem.compiled.evaluator import FusedEvaluator
from cablefem.geometry import Horizontal
from cablefem.loads import State
from cablefem.loads.gravity import Weight, submerged_fraction, submerged_integral
from cablefem.runs.results import end_forces, report
from cablefem.fem.system import build_system
from cablefem.statics.scene import start_states
from cablefem.model.scene import Contact, Environment, Motion, Scene, Solver
from cablefem.statics.start_shape import float_level, initial_shape
from cablefem.statics.touchdown import solve_line
from cablefem.statics.solve import solve_static
from cablefem.fem.system import LineSystem

ENV = Environment()
CHAIN = LineType("chain", diameter=0.3539, mass=835.4, EA=3.15e9, damping=0.001, Cd_normal=2.5,
                 Cd_tangential=0.5, Ca_normal=3.8)
FLOAT = LineType("float", diameter=0.5, mass=50.0, EA=1e8, Cd_normal=1.2, Ca_normal=1.0)
ANCHOR, FAIRLEAD, DEPTH = (-595.0, 0.0, -100.0), (0.0, 0.0, 0.0), 100.0
W = CHAIN.submerged_weight(ENV.water_density, ENV.gravity)
#: from taut through the touchdown regime to slack and 20 times the 595 m span
LENGTHS = [605.0, 620.0, 635.0, 700.0, 800.0, 1200.0, 3000.0, 11900.0]


def chain_line(length, order, elements=40, anchor=ANCHOR, fairlead=FAIRLEAD):
    return Line("l", anchor, fairlead, [Segment(CHAIN, length, elements)], order)


@pytest.mark.parametrize("order", [1, 2, 3])
@pytest.mark.parametrize("length", LENGTHS)
def test_start_shape_of_any_length_has_no_two_vertices_at_one_point(order, length):
    system = LineSystem(chain_line(length, order), Horizontal(DEPTH), Contact(), ENV)
    X, slack = initial_shape(system)
    vertices = X[: system.fem.n_vertices]
    gaps = np.linalg.norm(np.diff(vertices[np.argsort(system.fem.mesh.p[0])], axis=0), axis=1)
    assert gaps.min() > 1e-3 * length / 40  # a folded or piled start divided by zero (issue 14)
    assert slack == (length >= 700.0)  # the slack layout exactly when the line is longer than it needs


@pytest.mark.parametrize("order", [1, 2, 3])
@pytest.mark.parametrize("length", LENGTHS)
def test_fairlead_tension_matches_moorpy_from_taut_to_20_times_the_span(order, length):
    # a stiff seabed (3e8 N/m^3: 0.07 mm of penetration) so that MoorPy's rigid one is the same
    # physics; MoorPy's depth is the resting level. Measured: slack (>= 700 m) <= 1.1e-9 at every
    # order; touchdown P2/P3 <= 9e-7, P1 x 40 2.7e-3 (its kink at the touchdown)
    stiffness = 3e8
    system, result = solve_line(chain_line(length, order), Horizontal(DEPTH), Contact(stiffness=stiffness), ENV)
    sink = W / (stiffness * CHAIN.diameter)
    fAH, fAV, fBH, fBV, info = catenary(595.0, DEPTH + sink, length, CHAIN.EA, W, CB=0)
    expected = np.hypot(fBH, fBV)
    tolerance = 1e-8 if length >= 700.0 else (5e-3 if order == 1 else 1e-5)
    assert report(system, result.X).fairlead_tension == pytest.approx(expected, rel=tolerance)
    assert (info["ProfileType"] == 4) == (length >= 700.0)  # MoorPy's "slack": H = 0


@pytest.mark.parametrize("order", [1, 2, 3])
@pytest.mark.parametrize("length", [800.0, 3000.0, 11900.0])
def test_excess_length_lies_on_the_seabed_with_zero_tension(order, length):
    system, result = solve_line(chain_line(length, order), Horizontal(DEPTH), Contact(), ENV)
    hang = DEPTH  # the vertical part from the fairlead down to the seabed, ~100 m of line
    nodes = system.fem.mesh.p[0]
    lying = nodes[nodes < length - hang - 1.0]
    middle = 0.5 * (lying[1:] + lying[:-1])
    # slack: no tension at all, but for micro-newtons where the anchor, at the seabed's surface,
    # holds up the first element above the line's resting level (measured 2e-6 N, P3 x 40)
    assert np.all(system.tension_at(result.X, middle) <= 1e-9 * W * length)
    assert np.all(system.gap_at(result.X, lying[1:]) < 0.0)  # every lying vertex rests in the seabed
    fairlead, anchor = end_forces(system, result.X)
    assert abs(fairlead[0]) < 1e-6 * abs(fairlead[2])  # H = 0: nothing pulls the fairlead sideways
    assert abs(anchor[0]) < 1e-6 * abs(fairlead[2]) and abs(anchor[1]) < 1e-6 * abs(fairlead[2])


@pytest.mark.parametrize("order", [1, 2, 3])
def test_line_whose_ends_meet_in_mid_water_hangs_both_halves_to_the_seabed(order):
    # anchor and fairlead at one point 50 m above the seabed: each end carries one vertical hang
    # down to the line's resting level, of unstretched length l with l + w l^2 / (2 EA) = height,
    # and the rest lies slack
    point = (0.0, 0.0, -50.0)
    system, result = solve_line(chain_line(800.0, order, anchor=point, fairlead=point), Horizontal(DEPTH),
                                Contact(), ENV)
    height = 50.0 + W / (Contact().stiffness * CHAIN.diameter)
    hang = 2.0 * height / (1.0 + np.sqrt(1.0 + 2.0 * W * height / CHAIN.EA))
    fairlead, anchor = end_forces(system, result.X)
    for force in (fairlead, anchor):
        assert -force[2] == pytest.approx(W * hang, rel=1e-8)  # measured <= 1.3e-9


def test_line_whose_ends_meet_on_the_seabed_solves_with_no_tension():
    point = (0.0, 0.0, -DEPTH)
    system, result = solve_line(chain_line(800.0, 1, anchor=point, fairlead=point), Horizontal(DEPTH),
                                Contact(), ENV)
    nodes = system.fem.mesh.p[0]
    assert np.all(system.tension_at(result.X, 0.5 * (nodes[1:] + nodes[:-1])) == 0.0)


@pytest.mark.parametrize("order, elements, tolerance", [(1, 80, 3e-4), (2, 40, 1e-6), (3, 20, 1e-6)])
def test_buoyant_segment_is_the_inverted_catenary(order, elements, tolerance):
    # 330 m of a float line (w = -1484 N/m) from the seabed to 20 m below the surface: the catenary
    # of weight |w| upside down. Measured: P1 x 80 1.4e-4, P2 x 40 and P3 x 20 < 1e-7
    anchor, fairlead, length = (-300.0, 0.0, -100.0), (0.0, 0.0, -20.0), 330.0
    line = Line("float", anchor, fairlead, [Segment(FLOAT, length, elements)], order)
    system, result = solve_line(line, Horizontal(DEPTH), Contact(), ENV)
    lift = -FLOAT.submerged_weight(ENV.water_density, ENV.gravity)
    closed = elastic_catenary(300.0, -80.0, length, FLOAT.EA, lift, seabed=False)
    fairlead_force, anchor_force = end_forces(system, result.X)
    # mirrored in z: the line pulls the fairlead up by V_F and the anchor up by -V_A of the
    # hanging catenary, each with horizontal H
    assert fairlead_force[2] == pytest.approx(closed.fairlead_vertical, rel=tolerance)
    assert -fairlead_force[0] == pytest.approx(closed.fairlead_horizontal, rel=tolerance)
    assert anchor_force[2] == pytest.approx(-closed.anchor_vertical, rel=tolerance)
    assert np.max(result.X[: system.fem.n_vertices, 2]) < -0.5  # it never reaches the surface


def test_buoyant_line_longer_than_its_span_floats_at_its_waterline():
    # the refused line: a float line (0.5 m, 50 kg/m) from the seabed to a fairlead at the
    # surface. Its surplus floats where the submerged part of the section carries its weight
    line = Line("float", ANCHOR, FAIRLEAD, [Segment(FLOAT, 700.0, 70)], 1)
    system, result = solve_line(line, Horizontal(DEPTH), Contact(), ENV)
    level = float_level(system.weight)
    fraction, _ = submerged_fraction(level, FLOAT.diameter)
    assert fraction == pytest.approx(FLOAT.mass / (ENV.water_density * FLOAT.area), rel=1e-12)
    z = result.X[: system.fem.n_vertices, 2]
    floating = np.abs(z - level) < 1e-3
    assert floating.sum() > 20  # a long stretch lies at the waterline, slack
    nodes = system.fem.mesh.p[0]
    afloat = nodes[floating]
    inner = afloat[(afloat > afloat.min() + 20.0) & (afloat < afloat.max() - 20.0)]
    assert np.all(system.tension_at(result.X, inner) == 0.0)


def lazy_wave(order=1):
    return Line("lazy", ANCHOR, FAIRLEAD, [Segment(CHAIN, 400.0, 20), Segment(FLOAT, 150.0, 15),
                                           Segment(CHAIN, 200.0, 20)], order)


def test_lazy_wave_statics_lifts_its_float_section_into_an_arch():
    # a start with the float section lying slack on the seabed cannot be finished by Newton (the
    # section must rise through a snap); the line settles in water and Newton finishes there
    system = LineSystem(lazy_wave(), Horizontal(DEPTH), Contact(), ENV)
    result = solve_static(system)
    assert result.residual <= 1e-8
    s = np.linspace(400.0, 550.0, 31)
    heights = system.fem.evaluate(result.X, s)[:, 2] + DEPTH
    assert heights.max() > 30.0  # the arch; the chain on either side rests on the seabed
    assert system.gap_at(result.X, np.array([100.0, 300.0]))[0] < 0.0


def test_lazy_wave_held_still_stays_at_its_static_equilibrium():
    # dynamics starts from the statics; with the fairlead fixed nothing may move: the tension after
    # 20 s equals the static one (measured 1e-9 relative)
    scene = Scene("lazy", [lazy_wave()], Horizontal(DEPTH), solver=Solver(dt=0.05, tolerance=1e-10),
                  motion=Motion())
    system = build_system(scene, scene.lines[0])
    X0 = start_states(scene, systems=[system])[0][0]
    line = scene.lines[0]
    integ = BDF2(system, X0, lambda t: (np.asarray(line.fairlead, float), np.zeros(3), np.zeros(3)), dt=0.05,
                 tolerance=1e-10)
    static = np.linalg.norm(integ.reactions()[0])
    forces = integ.march(np.arange(1, 401) * 0.05)
    assert np.linalg.norm(forces[-1, 0]) == pytest.approx(static, rel=1e-6)
    assert np.max(np.abs(integ.V)) < 1e-4


def test_submerged_fraction_is_the_circular_segment_area_and_its_derivatives_agree():
    d = 0.5
    z = np.linspace(-0.3, 0.3, 60)  # not on the band's edges, where dphi/dz ~ sqrt(h) -> 0
    fraction, slope = submerged_fraction(z, d)
    # area of the circle below z = 0, by quadrature across the section
    y = np.linspace(-d / 2, d / 2, 200001)
    chord = 2.0 * np.sqrt(np.maximum((d / 2) ** 2 - y**2, 0.0))
    below = np.array([np.trapezoid(chord * (zc + y <= 0.0), y) for zc in z]) / (np.pi * d**2 / 4)
    np.testing.assert_allclose(fraction, below, atol=1e-5)
    assert fraction[0] == 1.0 and fraction[-1] == 0.0
    h = 1e-8
    numeric = (submerged_fraction(z + h, d)[0] - submerged_fraction(z - h, d)[0]) / (2 * h)
    np.testing.assert_allclose(slope, numeric, atol=1e-5)
    integral = (submerged_integral(z + h, d) - submerged_integral(z - h, d)) / (2 * h)
    np.testing.assert_allclose(integral, fraction, atol=1e-6)  # the energy's derivative is the force


def test_weight_jacobian_at_the_waterline_matches_finite_differences():
    weight = Weight(np.array([50.0]), np.array([FLOAT.area]), ENV.water_density, ENV.gravity)
    r = np.array([0.0, 0.0, 0.07]).reshape(3, 1, 1)
    terms = weight.evaluate(State(r, r), jacobian=True)
    h = 1e-6
    up, down = r.copy(), r.copy()
    up[2] += h
    down[2] -= h
    numeric = (weight.evaluate(State(up, up)).force - weight.evaluate(State(down, down)).force) / (2 * h)
    np.testing.assert_allclose(terms.force_r[:, 2], numeric, rtol=1e-6)


@pytest.mark.parametrize("order", [1, 2, 3])
def test_compiled_weight_at_the_waterline_equals_the_reference(order):
    # a float line lying along the surface: its points sit in the band where the section is
    # partly wet, where the compiled kernel and the numpy load must agree
    line = Line("float", (-30.0, 0.0, -0.05), (0.0, 0.0, 0.2), [Segment(FLOAT, 31.0, 6)], order)
    system = LineSystem(line, Horizontal(DEPTH), Contact(), ENV)
    rng = np.random.default_rng(order)
    X = system.fem.interpolate(lambda s: np.column_stack([s - 30.0, 0 * s, 0.1 * np.sin(s)]))
    X += 0.01 * rng.standard_normal(X.shape)
    zero = np.zeros_like(X)
    fused = FusedEvaluator.for_system(system, system.props["mass"])
    rows, band = fused.evaluate(X, zero, zero, 0.0, 0.0)
    rows_ref, blocks = system.evaluate(system.state(X), True)
    K_ref = system.matrix(blocks).toarray()
    np.testing.assert_allclose(rows, rows_ref, rtol=0, atol=1e-12 * np.abs(rows_ref).max())
    np.testing.assert_allclose(fused.dense(band), K_ref, rtol=0, atol=1e-12 * np.abs(K_ref).max())


def test_statics_converges_on_a_stiff_case_by_the_scale_free_residual():
    # EA 5e11 over a 3e14 N/m^3 seabed: positions known to round-off leave forces of 1e-4 of the
    # weight, so the force residual cannot reach 1e-8; the Newton step K^-1 G, free of the
    # stiffnesses' scale, does (measured 4e-5 and < 1e-13)
    stiff = LineType("stiff", diameter=0.3539, mass=835.4, EA=5e11)
    line = Line("l", ANCHOR, FAIRLEAD, [Segment(stiff, 635.0, 40)], 1)
    _, result = solve_line(line, Horizontal(DEPTH), Contact(stiffness=3e14), ENV)
    assert result.increment <= 1e-8
    assert result.residual > 1e-8


def test_a_dynamic_step_that_fails_says_its_residual():
    scene = Scene("snap", [chain_line(635.0, 1, elements=10)], Horizontal(DEPTH),
                  motion=Motion(kind="harmonic", amplitude=(40.0, 0.0, 0.0), period=2.0))
    system = build_system(scene, scene.lines[0])
    X0 = start_states(scene, systems=[system])[0][0]
    from cablefem.model.network import boundary_path

    integ = BDF2(system, X0, boundary_path(scene, scene.lines[0]), dt=0.5, tolerance=1e-12, min_dt=0.25,
                 max_iterations=2)
    with pytest.raises(ConvergenceError, match=r"relative residual \d") as error:
        integ.march(np.arange(1, 21) * 0.5)
    assert error.value.residual > 1e-12
