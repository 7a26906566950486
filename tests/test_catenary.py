"""Closed-form static lines (cablefem.statics.catenary): MoorPy agreement, seabed slopes,
internal consistency, the Batista & Perkovic case of desire2023 Table 4, bad input."""

import math

import numpy as np
import pytest

from cablefem import ConvergenceError, InputError
from cablefem.statics import _catenary_core as core
from cablefem.statics.catenary import elastic_catenary, inclined_catenary, inclined_catenary_from_force

moorpy_catenary = pytest.importorskip("moorpy.Catenary").catenary


def moorpy_forces(X, Z, L, EA, W, CB=0.0, alpha_deg=0.0, plots=0):
    """MoorPy's (HF, VF, HA, VA) in our sign convention, plus its info dict."""
    fAH, fAV, fBH, fBV, info = moorpy_catenary(X, Z, L, EA, W, CB=CB, alpha=alpha_deg, plots=plots)
    return np.array([-fBH, -fBV, fAH, fAV]), info


def forces(solution):
    return np.array([solution.fairlead_horizontal, solution.fairlead_vertical,
                     solution.anchor_horizontal, solution.anchor_vertical])


# central differences on L/4000 steps are O(ds^2 / R^2) off on a line bending with radius R
# (down to H/w ~ 3 m here); a wrong law (touchdown angle, lying tension) shows as O(1e-2) or more
FINITE_DIFFERENCE_TOLERANCE = 1e-4


def equilibrium_error(solution, n=4001):
    """Largest relative violation of the line's balance laws, from finite differences of the profile.

    Stretch |dr/ds| = 1 + T/EA; frictionless tangential balance dT/ds = w t_z (on the
    hanging part and along a frictionless plane alike); H = T t_x on the hanging part.
    Slack stretches (T = 0) carry nothing and are skipped.
    """
    s = np.linspace(0.0, solution.length, n)
    x, z = solution.profile(s)
    T = solution.tension(s)
    ds = s[1] - s[0]
    dx, dz, dT = np.gradient(x, ds), np.gradient(z, ds), np.gradient(T, ds)
    stretch = np.hypot(dx, dz)
    with np.errstate(invalid="ignore", divide="ignore"):
        tx, tz = dx / stretch, dz / stretch
    inner = (np.arange(n) > 1) & (np.arange(n) < n - 2) & (T > 1e-9 * solution.weight * solution.length)
    # keep away from kinks where central differences straddle two laws: touchdown, the ends of
    # slack stretches and piles, and the fold of a vertical line hanging below both ends
    kinks = [solution.touchdown_s, solution.length - solution.fairlead_vertical / solution.weight]
    if solution.lying is not None:
        kinks += [solution.lying.slack, solution.lying.length]
    for kink in kinks:
        if kink is not None:
            inner &= np.abs(s - kink) > 3 * ds
    scale = max(solution.fairlead_tension, solution.weight * solution.length)
    if not inner.any():
        return 0.0  # nothing tensioned: nothing to balance
    errors = [np.abs(stretch - 1.0 - T / solution.EA)[inner].max(),
              np.abs(dT - solution.weight * tz)[inner].max() * solution.length / scale]
    hanging = inner & (s > (solution.touchdown_s or 0.0) + 3 * ds)
    if hanging.any():
        errors.append(np.abs(T * tx - solution.fairlead_horizontal)[hanging].max() / scale)
    return max(errors)


# ---- flat seabed against MoorPy ---------------------------------------------------------------

FLAT_CASES = {  # X, Z, L, EA, W, friction
    "suspended": (450.0, 200.0, 500.0, 1e8, 700.0, 0.0),
    "suspended_nearly_taut": (470.0, 170.0, 500.0, 1e9, 700.0, 0.0),
    "suspended_stretched": (500.3, 30.0, 500.0, 1e9, 700.0, 0.0),
    "touchdown": (480.0, 100.0, 500.0, 1e9, 700.0, 0.0),
    "touchdown_friction": (480.0, 100.0, 500.0, 1e9, 700.0, 0.5),
    "friction_zero_tension_before_anchor": (495.0, 10.0, 500.0, 1e9, 700.0, 0.3),
    "friction_zero_tension_stiff_pull": (499.0, 30.0, 500.0, 1e8, 1000.0, 2.0),
    "chain_table5": (600.0, 100.0, 635.0, 3.15e9, 7206.0, 0.3),
    "slack_pile_up": (300.0, 200.0, 500.0, 3e8, 700.0, 0.0),
    "lying_friction_anchor_loaded": (520.0, 0.0, 500.0, 1e7, 700.0, 0.5),
    "lying_friction_anchor_slack": (510.0, 0.0, 500.0, 1e7, 700.0, 1.0),
}


@pytest.mark.parametrize("case", FLAT_CASES.values(), ids=FLAT_CASES.keys())
def test_flat_seabed_end_forces_match_moorpy_to_1e6(case):
    # MoorPy stops once the fairlead misses by less than Tol = 1e-6 m; at these stiffnesses
    # (<= EA/L = 2e6 N/m) that is <= 2 N on forces of 1e5-3e6 N, i.e. ~1e-6 relative.
    X, Z, L, EA, W, mu = case
    ours = elastic_catenary(X, Z, L, EA, W, friction=mu)
    theirs, info = moorpy_forces(X, Z, L, EA, W, CB=mu)
    assert np.abs(forces(ours) - theirs).max() <= 1e-6 * np.abs(theirs).max()
    assert ours.lying_length == pytest.approx(info["LBot"], rel=1e-6, abs=1e-6 * L)


def test_friction_leaves_a_slack_straight_stretch_at_the_anchor():
    X, Z, L, EA, W, mu = FLAT_CASES["friction_zero_tension_before_anchor"]
    line = elastic_catenary(X, Z, L, EA, W, friction=mu)
    slack_end = line.lying_length - line.fairlead_horizontal / (mu * W)  # tension falls by mu*w per metre
    assert line.anchor_tension == 0.0
    assert line.lying.slack == pytest.approx(slack_end, rel=1e-12)
    s = np.linspace(0.0, 0.99 * slack_end, 50)
    x, z = line.profile(s)
    np.testing.assert_allclose(line.tension(s), 0.0, atol=0.0)
    np.testing.assert_allclose(x, s, rtol=1e-14)  # unstretched and straight, held by friction
    np.testing.assert_allclose(z, 0.0, atol=0.0)


# ---- sloped seabed: MoorPy's regime test and where it is right ---------------------------------

def test_moorpy_buries_a_line_on_a_slope_where_ours_touches_down():
    # MoorPy calls a sloped line suspended when V_A > tan(alpha), a force against a pure
    # number; here the free catenary leaves the anchor at 8.3 deg, below the 15 deg seabed.
    X, Z, L, EA, W, alpha = 95.0, 30.0, 100.0, 1e9, 1000.0, 15.0
    _, info = moorpy_forces(X, Z, L, EA, W, alpha_deg=alpha, plots=1)
    a = math.radians(alpha)
    moorpy_height = info["Z"] * math.cos(a) - info["X"] * math.sin(a)
    assert info["ProfileType"] == 1 and moorpy_height.min() < -2.0  # 2 m into the seabed

    ours = inclined_catenary(X, Z, L, W, a, EA)
    x, z = ours.profile(np.linspace(0.0, L, 2001))
    assert ours.regime == "touchdown" and ours.lying_length > 0.0
    assert (z * math.cos(a) - x * math.sin(a)).min() >= -1e-9
    assert equilibrium_error(ours) < FINITE_DIFFERENCE_TOLERANCE
    touchdown_angle = math.atan2(float(ours.fairlead_vertical - W * (L - ours.lying_length)),
                                 ours.fairlead_horizontal)
    assert touchdown_angle == pytest.approx(a, abs=1e-12)  # leaves the seabed tangentially


SLOPE_CASES = [(80.0, 50.0, 5.0), (97.0, 20.0, 5.0), (90.0, 30.0, 5.0), (80.0, 50.0, 15.0),
               (95.0, 30.0, -15.0), (60.0, 60.0, -15.0), (70.0, 30.0, -15.0), (50.0, 70.0, -30.0)]


@pytest.mark.parametrize("X, Z, alpha", SLOPE_CASES)
def test_slope_end_forces_match_moorpy_where_its_line_is_consistent(X, Z, alpha):
    # cases where MoorPy's line neither buries itself nor needs a negative anchor tension
    theirs, _ = moorpy_forces(X, Z, 100.0, 1e9, 1000.0, alpha_deg=alpha)
    ours = inclined_catenary(X, Z, 100.0, 1000.0, math.radians(alpha), 1e9)
    assert np.abs(forces(ours) - theirs).max() <= 1e-6 * np.abs(theirs).max()


@pytest.mark.parametrize("X, Z, alpha", [(80.0, 50.0, -15.0), (97.0, 20.0, -15.0), (85.0, 45.0, -30.0)])
def test_downslope_hanging_line_pulls_the_anchor_along_itself_not_along_the_seabed(X, Z, alpha):
    # MoorPy agrees on the fairlead but reports these suspended lines' anchor force along the
    # seabed (its sloped branch); the line leaves the anchor above the seabed, so its force does too
    theirs, _ = moorpy_forces(X, Z, 100.0, 1e9, 1000.0, alpha_deg=alpha)
    ours = inclined_catenary(X, Z, 100.0, 1000.0, math.radians(alpha), 1e9)
    assert ours.regime == "suspended"
    assert np.abs(forces(ours)[:2] - theirs[:2]).max() <= 1e-6 * np.abs(theirs).max()
    x, z = ours.profile([0.0, 1e-6])
    leaving = math.atan2(z[1] - z[0], x[1] - x[0])
    assert math.atan2(ours.anchor_vertical, ours.anchor_horizontal) == pytest.approx(leaving, abs=1e-6)
    assert leaving > math.radians(alpha) + 0.05


SLOPE_GRID = [(X, Z, alpha) for alpha in (-40.0, -15.0, 15.0, 40.0)
              for X, Z in ((60.0, 70.0), (85.0, 40.0), (30.0, 90.0), (20.0, 40.0))
              if Z > X * math.tan(math.radians(alpha))]  # fairlead above the seabed


@pytest.mark.parametrize("X, Z, alpha", SLOPE_GRID)
def test_inextensible_slope_keeps_T_minus_wz_constant_and_stays_above_the_seabed(X, Z, alpha):
    # frictionless and inextensible: T - w z is the same wherever the line is tensioned
    a = math.radians(alpha)
    line = inclined_catenary(X, Z, 100.0, 500.0, a)
    s = np.linspace(0.0, 100.0, 1001)
    x, z = line.profile(s)
    T = line.tension(s)
    tensioned = T > 0.0
    invariant = T[tensioned] - 500.0 * z[tensioned]
    assert np.ptp(invariant) <= 1e-9 * line.fairlead_tension
    assert (z * math.cos(a) - x * math.sin(a)).min() >= -1e-9
    assert equilibrium_error(line) < FINITE_DIFFERENCE_TOLERANCE


def test_frictionless_upslope_piles_surplus_chain_at_the_anchor():
    line = inclined_catenary(70.0, 30.0, 100.0, 1000.0, math.radians(15.0))  # MoorPy: H = 0, slides
    g = 1000.0 * math.sin(math.radians(15.0))
    assert line.anchor_tension == 0.0 and line.lying.slack > 0.0 and not line.lying.held
    x, z = line.profile(np.linspace(0.0, line.lying.slack, 20))
    np.testing.assert_allclose(np.hypot(x, z), 0.0, atol=1e-12)
    tensioned = line.lying_length - line.lying.slack
    assert tensioned * g == pytest.approx(line.fairlead_horizontal / math.cos(math.radians(15.0)), rel=1e-12)


# ---- internal consistency ----------------------------------------------------------------------

REGIME_CASES = {
    "suspended": lambda: elastic_catenary(450.0, 200.0, 500.0, 1e8, 700.0),
    "touchdown_friction": lambda: elastic_catenary(499.0, 30.0, 500.0, 1e8, 1000.0, friction=2.0),
    "taut": lambda: elastic_catenary(520.0, 80.0, 500.0, 1e8, 700.0),
    "free_sag_below_anchor": lambda: elastic_catenary(300.0, -50.0, 500.0, 1e9, 700.0, seabed=False),
    "slack": lambda: elastic_catenary(300.0, 200.0, 500.0, 3e8, 700.0),
    "vertical_taut": lambda: elastic_catenary(0.0, 501.5, 500.0, 1e8, 700.0),
    "vertical_pile_at_anchor": lambda: elastic_catenary(0.0, 500.2, 500.0, 1e8, 700.0),
    "vertical_folded": lambda: elastic_catenary(0.0, 100.0, 500.0, 1e8, 700.0, seabed=False),
    "downslope_slack": lambda: inclined_catenary(40.0, 60.0, 100.0, 500.0, -0.4, 1e6),
    "upslope_pile": lambda: inclined_catenary(70.0, 30.0, 100.0, 1000.0, 0.26, 1e7),
    "lying_downslope": lambda: inclined_catenary(90.0, -90.0 * math.tan(0.3), 100.0, 500.0, -0.3, 1e5),
}


@pytest.mark.parametrize("make", REGIME_CASES.values(), ids=REGIME_CASES.keys())
def test_profile_ends_at_the_fairlead_to_1e9(make):
    line = make()
    x, z = line.profile([0.0, line.length])
    assert (x[0], z[0]) == (0.0, 0.0)
    miss = math.hypot(x[1] - line.horizontal_span, z[1] - line.vertical_span)
    assert miss <= 1e-9 * line.length
    assert line.tension([line.length])[0] == pytest.approx(line.fairlead_tension, rel=1e-12)
    assert line.tension([0.0])[0] == pytest.approx(line.anchor_tension, rel=1e-12, abs=1e-9)


FRICTIONLESS_CASES = {k: v for k, v in REGIME_CASES.items() if "friction" not in k}


@pytest.mark.parametrize("make", FRICTIONLESS_CASES.values(), ids=FRICTIONLESS_CASES.keys())
def test_shape_satisfies_stretch_and_tangential_balance(make):
    line = make()
    assert equilibrium_error(line) < FINITE_DIFFERENCE_TOLERANCE


def test_hanging_tension_is_the_hypotenuse_of_H_and_V():
    line = elastic_catenary(480.0, 100.0, 500.0, 1e9, 700.0)
    s = np.linspace(line.touchdown_s, line.length, 101)
    V = line.fairlead_vertical - 700.0 * (line.length - s)
    np.testing.assert_allclose(line.tension(s), np.hypot(line.fairlead_horizontal, V), rtol=1e-14)


def test_elastic_line_tends_to_the_inextensible_one_as_EA_grows():
    rigid = forces(elastic_catenary(480.0, 100.0, 500.0, np.inf, 700.0))
    gaps = [np.abs(forces(elastic_catenary(480.0, 100.0, 500.0, EA, 700.0)) - rigid).max() / rigid.max()
            for EA in (1e9, 1e11, 1e14)]
    assert gaps[0] > 1e-3 and gaps[2] < 1e-6
    assert gaps[1] / gaps[0] == pytest.approx(1e-2, rel=0.05)  # first order in 1/EA


@pytest.mark.parametrize("X, Z", [(480.0, 100.0), (300.0, 200.0), (450.0, 200.0), (510.0, 0.0)])
def test_inclined_with_zero_slope_is_the_frictionless_flat_catenary(X, Z):
    flat = elastic_catenary(X, Z, 500.0, 1e8, 700.0)
    inclined = inclined_catenary(X, Z, 500.0, 700.0, 0.0, 1e8)
    assert inclined.regime == flat.regime
    np.testing.assert_array_equal(forces(inclined), forces(flat))


@pytest.mark.parametrize("X, Z", [(300.0, 100.0), (400.0, -150.0), (480.0, 20.0), (200.0, 0.0)])
def test_free_line_solved_from_either_end_gives_the_same_forces(X, Z):
    ab = elastic_catenary(X, Z, 500.0, 1e8, 700.0, seabed=False)
    ba = elastic_catenary(X, -Z, 500.0, 1e8, 700.0, seabed=False)
    swapped = [ba.anchor_horizontal, -ba.anchor_vertical, ba.fairlead_horizontal, -ba.fairlead_vertical]
    np.testing.assert_allclose(forces(ab), swapped, rtol=1e-10, atol=1e-10 * ab.fairlead_tension)


def test_touchdown_regime_is_continuous_into_the_suspended_one():
    # the fairlead moves out along z = 150 m: the lying length shrinks to zero, forces stay smooth
    spans = np.linspace(468.5, 470.0, 31)
    lines = [elastic_catenary(X, 150.0, 500.0, 1e9, 700.0) for X in spans]
    regimes = [line.regime for line in lines]
    assert "touchdown" in regimes and "suspended" in regimes
    steps = np.diff([line.fairlead_horizontal for line in lines])
    assert np.all(steps > 0.0)
    assert np.abs(np.diff(steps)).max() < 0.01 * steps.max()  # H and dH/dX without a jump at the switch


def test_vertical_line_is_the_limit_of_a_nearly_vertical_one():
    exact = elastic_catenary(0.0, 200.0, 500.0, 1e9, 700.0, seabed=False)
    near = elastic_catenary(1e-6, 200.0, 500.0, 1e9, 700.0, seabed=False)
    assert exact.regime == "vertical"
    assert near.fairlead_vertical == pytest.approx(exact.fairlead_vertical, rel=1e-6)
    assert near.fairlead_horizontal < 1e-3 * exact.fairlead_vertical


def test_slack_pile_up_hangs_vertically_with_the_surplus_on_the_seabed():
    line = elastic_catenary(300.0, 200.0, 500.0, np.inf, 700.0)
    assert line.regime == "slack" and line.fairlead_horizontal == 0.0
    assert line.fairlead_vertical == pytest.approx(700.0 * 200.0, rel=1e-14)
    assert line.lying_length == pytest.approx(300.0, rel=1e-14)


def test_bracketed_fallback_agrees_with_newton():
    for X, Z, alpha, mu in [(480.0, 100.0, 0.0, 0.3), (95.0, 30.0, 0.26, 0.0), (80.0, 50.0, -0.26, 0.0)]:
        L = 500.0 if alpha == 0.0 else 100.0
        setting = core.Setting(700.0, L, 1e9, alpha, mu, True)
        newton = core.solve(X, Z, setting)
        fallback = core.bracketed(X, Z, setting)
        np.testing.assert_allclose(fallback, newton, rtol=1e-9)


def test_a_solver_that_misses_the_fairlead_raises_convergence_error(monkeypatch):
    monkeypatch.setattr(core, "newton", lambda *args, **kwargs: None)
    monkeypatch.setattr(core, "bracketed", lambda X, Z, setting: (1e3, 1e5))
    with pytest.raises(ConvergenceError) as caught:
        elastic_catenary(480.0, 100.0, 500.0, 1e9, 700.0)
    assert caught.value.residual > 1.0


# ---- Batista & Perkovic, desire2023 Sec. 3 -------------------------------------------------------

SUBMERGED_WEIGHT = (835.4 - 1025.0 * math.pi * 0.3539**2 / 4.0) * 9.8  # Table 2, g = 9.8 (Sec. 2.2)
TABLE4_H = [3.5e6, 3.7e6, 4.0e6, 4.3e6, 4.5e6]
TABLE4_TA = [5373e3, 5188e3, 4912e3, 4637e3, 4454e3]


def test_table4_fairlead_tensions_follow_with_the_H_column_reversed():
    # fairlead 83.766 m above an anchor on a 15 deg slope falling towards the fairlead
    for H, T in zip(TABLE4_H, TABLE4_TA[::-1]):
        line = inclined_catenary_from_force(H, 83.766, 635.0, SUBMERGED_WEIGHT, math.radians(-15.0))
        assert line.fairlead_horizontal == pytest.approx(H, rel=1e-12)
        assert line.regime == "touchdown"
        assert abs(line.fairlead_tension - T) < 0.5e3  # to the printed kN


@pytest.mark.parametrize("height", [20.0, 80.0, 200.0, 400.0])
def test_table4_as_printed_is_out_of_reach_for_any_height(height):
    # T_A = 4454 kN at H = 4.5 MN cannot be: the fairlead tension is at least H
    line = inclined_catenary_from_force(4.5e6, height, 635.0, SUBMERGED_WEIGHT, math.radians(-15.0))
    assert line.fairlead_tension > 4.5e6 > TABLE4_TA[-1]


# ---- bad input -------------------------------------------------------------------------------------

@pytest.mark.parametrize("kwargs, key", [
    (dict(length=0.0), "length"), (dict(length=-5.0), "length"), (dict(weight=0.0), "weight"),
    (dict(EA=-1.0), "EA"), (dict(EA=0.0), "EA"), (dict(horizontal_span=float("nan")), "horizontal_span"),
    (dict(vertical_span=float("inf")), "vertical_span"), (dict(friction=-0.1), "friction"),
    (dict(horizontal_span=-1.0), "horizontal_span"), (dict(weight=True), "weight"),
    (dict(vertical_span=-10.0), "vertical_span"),  # fairlead below the seabed
    (dict(horizontal_span=700.0), "length"),  # needs 40 % strain
    (dict(horizontal_span=505.0, EA=np.inf), "length"),  # inextensible, chord > L
    (dict(seabed="yes"), "seabed"),
])
def test_bad_input_raises_input_error_naming_the_key(kwargs, key):
    args = dict(horizontal_span=400.0, vertical_span=100.0, length=500.0, EA=1e9, weight=700.0)
    args.update(kwargs)
    with pytest.raises(InputError) as caught:
        elastic_catenary(**args)
    assert caught.value.key == key


@pytest.mark.parametrize("kwargs, key", [
    (dict(slope=math.pi / 2), "slope"), (dict(slope=float("nan")), "slope"),
    (dict(vertical_span=10.0, slope=0.5), "vertical_span"),  # 10 m up at 80 m is under a 27 deg seabed
    (dict(weight=-1.0), "weight"),
])
def test_bad_inclined_input_raises_input_error_naming_the_key(kwargs, key):
    args = dict(horizontal_span=80.0, vertical_span=50.0, length=100.0, weight=1000.0, slope=0.2)
    args.update(kwargs)
    with pytest.raises(InputError) as caught:
        inclined_catenary(**args)
    assert caught.value.key == key


def test_a_force_the_line_cannot_carry_names_horizontal_force():
    with pytest.raises(InputError) as caught:
        inclined_catenary_from_force(1e15, 83.766, 635.0, SUBMERGED_WEIGHT, math.radians(-15.0))
    assert caught.value.key == "horizontal_force"
