"""The axial laws of ``cablefem.loads.rope`` (issue 36, item 3): tangents over a step, the statics'
energy, the laws' limits (relaxed, frozen, pushing), the history they commit, and the closed forms
of verification/axial_laws. The two faces are held equal in tests/test_catalog.py."""

import numpy as np
import pytest

from cablefem.compiled.evaluator import FusedEvaluator
from cablefem.loads.rope import Rope
from rope_cases import INITIAL, LAWS, rope_state, rope_system

KINDS = list(LAWS)


@pytest.mark.parametrize("slack", [False, True], ids=["no-slack-force", "moordyn-slack"])
@pytest.mark.parametrize("kind", KINDS)
def test_the_tangent_over_a_step_matches_finite_differences(kind, slack, rng):
    # the step's equation for the slow strain is solved to round-off at each evaluation (the
    # implicit function theorem gives its derivatives): central differences of h 1e-7 m and m/s
    # agree to their own truncation, ~1e-6 of the largest entry (SYROPE's 5e-5 in V: BA / h ~ 1e12)
    system = rope_system(kind, 2, slack)
    X, V, A = rope_state(system, rng)
    inv_h = 20.0
    state = lambda X, V: system.state(X, V, A, inv_h=inv_h)  # noqa: E731
    residual = lambda X, V: system.evaluate(state(X, V), False)[0].ravel()  # noqa: E731
    K = {cv: system.matrix(system.evaluate(state(X, V), True, cv, 0.0)[1], free_only=False).toarray()
         for cv in (0.0, 1.0, 150.0)}
    for matrix, dX, dV, tolerance in ((K[0.0], 1.0, 0.0, 1e-5), (K[1.0] - K[0.0], 0.0, 1.0, 2e-4),
                                      (K[150.0], 1.0, 150.0, 1e-5)):
        for _ in range(2):
            d = rng.standard_normal(X.shape)
            h = 1e-7 / max(dX, dV / 150.0) if dV else 1e-7
            fd = (residual(X + h * dX * d, V + h * dV * d) - residual(X - h * dX * d, V - h * dV * d)) / (2 * h)
            np.testing.assert_allclose(matrix @ d.ravel(), fd, rtol=0, atol=tolerance * np.abs(fd).max())


@pytest.mark.parametrize("compression", [False, True], ids=["tension-only", "pushing"])
@pytest.mark.parametrize("slack", [False, True], ids=["no-slack-force", "moordyn-slack"])
@pytest.mark.parametrize("kind", KINDS)
def test_the_statics_energy_slopes_as_the_static_residual(kind, slack, compression, rng):
    # statics' line search takes Armijo's test on LineSystem.energy with the slope G . d: central
    # differences (h = 1e-6 m) of the rope's energy equal the static residual's work to 1e-7
    system = rope_system(kind, 2, slack)
    system.loads = [system.load("rope")]
    system.loads[0].compression = compression
    X, _, _ = rope_state(system, rng)
    d = rng.standard_normal(X.shape)
    h = 1e-6
    slope = (system.energy(X + h * d) - system.energy(X - h * d)) / (2 * h)
    assert slope == pytest.approx(float(np.sum(system.residual(X) * d)), rel=1e-7)


@pytest.mark.parametrize("kind", ["viscoelastic", "load_dependent"])
def test_a_relaxed_viscoelastic_rope_carries_its_static_EA(kind, rng):
    # statics (1/h = 0): the slow strain relaxed, the two springs in series are EA_s whatever the
    # dynamic stiffness does with the mean load: T = EA_s e exactly (to the Newton solve's 1e-15)
    system = rope_system(kind, 1)
    X, _, _ = rope_state(system, rng)
    rope = system.load("rope")
    state = system.state(X).reduced
    T, *_ = rope.tension(state)
    e = np.linalg.norm(state.dr, axis=0) - 1.0
    np.testing.assert_allclose(T, LAWS[kind].static_EA * e, rtol=1e-12)


def test_a_viscoelastic_rope_answers_a_fast_pull_with_its_dynamic_stiffness(rng):
    # a step much shorter than the relaxation time (BA / (EA_1 + EA_2) = 0.22 s here, h = 1e-6 s)
    # leaves the slow strain where it was: the fast spring takes the pull, dT / de = EA_d, less the
    # share BA_D / (BA + BA_D) of its stretch that goes through the dampers (0.5 % here) to O(h / tau);
    # relaxed (statics) the series EA_s
    system = rope_system("viscoelastic", 1)
    X, _, _ = rope_state(system, rng)
    rope = system.load("rope")
    _, dT_de, _, _, _, _ = rope.tension(system.state(X, inv_h=1e6).reduced)
    law = LAWS["viscoelastic"]
    share = law.damping / (law.damping + law.dynamic_damping)
    np.testing.assert_allclose(dT_de, law.dynamic_EA * share, rtol=1e-5)
    _, dT_de, _, _, _, _ = rope.tension(system.state(X).reduced)
    np.testing.assert_allclose(dT_de, law.static_EA, rtol=1e-9)


def test_syrope_statics_hold_the_slow_strain_of_tmean0():
    # cablefem static on SYROPE: the slow strain of the IC's Tmean0 on the working curve of Tmax0
    # (MoorDyn-C's Line::initialize), the fast part in the dynamic spring: at the strain of Tmean0
    # on that curve the tension is Tmean0, to round-off
    system = rope_system("syrope", 1)
    law = LAWS["syrope"]
    x, y, z = law.working_curve(INITIAL[0])
    strain = float(np.interp(INITIAL[1], y, x))
    system.reset_history(system.fem.interpolate(lambda s: np.column_stack([s * (1 + strain), 0 * s, 0 * s - 50.0])))
    X = system.fem.interpolate(lambda s: np.column_stack([s * (1 + strain), 0 * s, 0 * s - 50.0]))
    T, *_ = system.load("rope").tension(system.state(X).reduced)
    np.testing.assert_allclose(T, INITIAL[1], rtol=1e-12)


def test_syrope_raises_its_peak_on_the_original_curve_and_commits_it(rng):
    # a step past Tmax0 moves along the original working curve: the trial peak is the new mean
    # tension, both faces write it, and only a commit makes it the history the next step starts from
    system = rope_system("syrope", 1)
    old, new = system.history["reduced"]
    old["rope"]["slow"] = 0.0205  # a slow strain above the working curve of Tmax0
    X, V, A = rope_state(system, rng)
    fused = FusedEvaluator.for_system(system, system.props["mass"])
    fused.evaluate(X, V, A, 40.0, 1600.0, h=0.05)
    compiled = new["rope"].copy()
    system.evaluate(system.state(X, V, A, inv_h=20.0), False)
    np.testing.assert_allclose(compiled["peak"], new["rope"]["peak"], rtol=1e-12)
    assert np.all(new["rope"]["peak"] > INITIAL[0]) and np.all(old["rope"]["peak"] == INITIAL[0])
    system.commit_history()
    assert np.array_equal(old["rope"]["peak"], new["rope"]["peak"])


def test_a_history_law_in_a_run_without_a_step_size_fails_loudly(rng):
    # the compiled steps pass h with the factors; a caller that does not (v_x > 0, no h) must not
    # get the relaxed law silently
    system = rope_system("viscoelastic", 1)
    X, V, A = rope_state(system, rng)
    fused = FusedEvaluator.for_system(system, system.props["mass"])
    rows, _ = fused.evaluate(X, V, A, 40.0, 1600.0)
    assert not np.all(np.isfinite(rows))


def test_a_line_of_two_laws_carries_each_on_its_own_elements():
    # a chain segment (the tension load's T = EA e) and a table rope: the rope load's elements are
    # the rope's, the tension load has EA = 0 there (and nothing else)
    from cablefem.fem.system import LineSystem
    from cablefem.geometry import Horizontal
    from cablefem.model.line import Line, LineType, Segment
    from cablefem.model.scene import Contact, Environment
    from rope_cases import rope_type

    chain = LineType("chain", 0.1, 20.0, 5e8)
    line = Line("mixed", [0.0, 0.0, -50.0], [101.0, 0.0, -50.0],
                [Segment(chain, 50.0, 3), Segment(rope_type("table"), 50.0, 4)])
    system = LineSystem(line, Horizontal(100.0), Contact(), Environment())
    rope = system.load("rope")
    assert isinstance(rope, Rope)
    np.testing.assert_array_equal(rope.kind != 0, [False] * 3 + [True] * 4)
    np.testing.assert_array_equal(system.tension.EA[:, 0], [5e8] * 3 + [0.0] * 4)


VISCO_SCENE = """
name = "rope-run"
[environment]
gravity = 9.81
[line_types.poly]
diameter = 0.2
mass = 40.0
{law}
[[lines]]
anchor = [-300.0, 0.0, -100.0]
fairlead = [0.0, 0.0, 0.0]
segments = [{{ type = "poly", length = 310.0, elements = 12{initial} }}]
order = 2
[seabed]
kind = "horizontal"
depth = 100.0
[motion]
kind = "harmonic"
amplitude = [3.0, 0.0, 0.0]
period = 8.0
[solver]
dt = 0.1
"""
RUN_LAWS = {
    "viscoelastic": ('EA = 1.2e8\nEA_dynamic = 1.4e8\nEA_dynamic_slope = 9.0\nBA = 4e8\nBA_dynamic = 2e6', ""),
    "syrope": ('EA = { strain = [0.0, 0.01, 0.02, 0.04, 0.06], tension = [0.0, 7e5, 1.4e6, 2.6e6, 4.4e6] }\n'
               'EA_dynamic = 1.53e8\nEA_dynamic_slope = 23.12\nBA = 5e9\nBA_dynamic = 1e5\n'
               'syrope = { working_curve = "exp", k1 = 0.2, k2 = 1.5 }',
               ", syrope = { Tmax = 3.0e6, Tmean = 2.2e6 }"),
}


@pytest.mark.parametrize("kind", list(RUN_LAWS))
def test_compiled_steps_of_a_rope_with_history_equal_the_python_steps(kind, tmp_path):
    # the slow strain steps over the h that the compiled steps and the Python ops each pass to the
    # kernel (a halved step its own h): the same arithmetic in another order, round-off apart, the
    # same iterations; the run's first row is the static JSON's state (statics commit the history
    # the run starts from)
    from cablefem.io import load_scene
    from cablefem.statics.scene import static_lines
    from cablefem.study import start_line

    law, initial = RUN_LAWS[kind]
    (tmp_path / "scene.toml").write_text(VISCO_SCENE.format(law=law, initial=initial))
    scene = load_scene(tmp_path / "scene.toml")
    times = np.arange(1, 41) * 0.1
    runs = []
    for compiled in (True, False):
        integ = start_line(scene)
        if not compiled:
            integ.stepper().packer = None  # the fused kernel per evaluation, Newton in Python
        assert (integ.stepper().packer is not None) == compiled
        runs.append((integ.march(times), integ.X, integ.statistics(), integ.system.history["reduced"][0].copy()))
    (f1, X1, s1, h1), (f2, X2, s2, h2) = runs
    assert np.max(np.abs(f1 - f2)) <= 1e-9 * np.max(np.abs(f2))
    assert np.max(np.abs(X1 - X2)) <= 1e-9
    assert s1 == s2
    np.testing.assert_allclose(h1["rope"]["slow"], h2["rope"]["slow"], rtol=0, atol=1e-12)
    # the line's tension moved with the motion, and its slow strain with it
    assert np.ptp(np.linalg.norm(f1[:, 0], axis=1)) > 0.05 * np.mean(np.linalg.norm(f1[:, 0], axis=1))
    systems, results, _, _ = static_lines(scene)
    start = start_line(scene)
    static = systems[0].history["reduced"][0]["rope"]["slow"]
    np.testing.assert_allclose(start.system.history["reduced"][0]["rope"]["slow"], static, rtol=0, atol=1e-15)
