"""The internal damping law of a line type (issue 16): by default a slack element carries nothing;
with ``damping_when_slack`` (MoorDyn-C's law, ``Line.cpp``: Td = BA de/dt in every segment) the
damping part acts in slack segments too. Both faces agree and their tangent is exact."""

from dataclasses import replace

import numpy as np
import pytest

from cablefem import LineType
from cablefem.compiled.evaluator import FusedEvaluator
from cablefem.geometry import Horizontal
from cablefem.io.moordyn_input import read_moordyn
from cablefem.loads import State
from cablefem.loads.tension import Tension
from cablefem.model.scene import Contact, Environment
from cablefem.fem.system import LineSystem

from conftest import make_line
from test_loads import assert_tangent_matches_finite_differences

EA, BETA = 1e8, 0.01


def one_point(e, rate, slack_damping):
    """Tension flux at one point of strain e and strain rate de/dt along x, either law."""
    dr = np.array([1.0 + e, 0.0, 0.0]).reshape(3, 1, 1)
    dv = np.array([rate, 0.0, 0.0]).reshape(3, 1, 1)
    law = Tension(np.array([EA]), np.array([BETA]), slack_damping=np.array([slack_damping]))
    return law.evaluate(State(dr, dr, dv, dv), jacobian=False).flux[0, 0, 0]


@pytest.mark.parametrize("e, rate", [(-0.01, -2.0), (-0.01, 2.0), (0.01, -2.0), (0.01, 0.5)])
def test_moordyn_law_damps_slack_segments_and_the_default_does_not(e, rate):
    moordyn = EA * (max(e, 0.0) + BETA * rate)  # may push: a slack segment closing up
    default = max(EA * (e + BETA * rate), 0.0) if e > 0 else 0.0
    assert one_point(e, rate, True) == pytest.approx(moordyn, rel=1e-14)
    assert one_point(e, rate, False) == pytest.approx(default, rel=1e-14, abs=1e-300)


def slack_system(order, slack_damping):
    """A rope lying partly slack (strain -2 % .. +2 % along it), moving, on no seabed."""
    rope = LineType("rope", diameter=0.1, mass=20.0, EA=EA, damping=BETA, Cd_normal=0.0, Ca_normal=0.0,
                    damping_when_slack=slack_damping)
    line = make_line(rope, order, elements=8, anchor=(-100.0, 0.0, -50.0), fairlead=(0.0, 0.0, -50.0),
                     length=100.0)
    return LineSystem(line, Horizontal(500.0), Contact(), Environment(), dynamic=True)


def slack_state(system, rng):
    def positions(s):
        # stretch 1 + 0.02 cos(pi s / L) along x: taut near the anchor, compressed near the fairlead
        x = s + 0.02 * 100.0 / np.pi * np.sin(np.pi * s / 100.0) - 100.0
        return np.column_stack([x, 0.2 * np.sin(0.1 * s), -50.0 + 0.0 * s])

    X = system.fem.interpolate(positions)
    V = 0.3 * rng.standard_normal(X.shape)
    A = rng.standard_normal(X.shape)
    return system.state(X, V, A), X, V, A


@pytest.mark.parametrize("order", [1, 2])
def test_moordyn_law_tangent_matches_finite_differences_at_slack_points(order, rng, monkeypatch):
    # a slack element's tangent carries a tiny isotropic stiffness that is not in the residual (it
    # keeps Newton's matrix regular, loads.tension.SLACK_STIFFNESS): left out here
    monkeypatch.setattr("cablefem.loads.tension.SLACK_STIFFNESS", 0.0)
    system = slack_system(order, True)
    state, X, V, A = slack_state(system, rng)
    e = np.linalg.norm(state.reduced.dr, axis=0) - 1.0
    assert (e < -1e-4).any() and (e > 1e-4).any() and np.abs(e).min() > 1e-5  # both sides, off the kink
    assert_tangent_matches_finite_differences(system, state, X, V, A, rng.standard_normal((3, *X.shape)))


@pytest.mark.parametrize("order", [1, 2, 3])
@pytest.mark.parametrize("slack_damping", [False, True])
def test_compiled_face_equals_numpy_face_for_both_laws(order, slack_damping, rng):
    system = slack_system(order, slack_damping)
    _, X, V, A = slack_state(system, rng)
    fused = FusedEvaluator.for_system(system, system.props["mass"])
    fem = system.fem
    M = fem.vector_mass(system.props["mass"], free_only=False)
    R, blocks = system.evaluate(system.state(X, V, A), True, 150.0, 2.2e4)
    rows_ref = R + (M @ A.ravel()).reshape(A.shape)
    K_ref = (system.matrix(blocks) + 2.2e4 * fem.vector_mass(system.props["mass"])).toarray()
    rows, band = fused.evaluate(X, V, A, 150.0, 2.2e4)
    np.testing.assert_allclose(rows, rows_ref, rtol=0, atol=1e-12 * np.abs(rows_ref).max())
    np.testing.assert_allclose(fused.dense(band), K_ref, rtol=0, atol=1e-12 * np.abs(K_ref).max())


def test_the_two_laws_differ_only_where_a_segment_is_slack(rng):
    taut, moordyn = slack_system(1, False), slack_system(1, True)
    _, X, V, A = slack_state(taut, rng)
    e = np.linalg.norm(taut.state(X).reduced.dr, axis=0)[:, 0] - 1.0
    difference = np.abs(taut.residual(X, V, A) - moordyn.residual(X, V, A)).sum(axis=1)
    slack_nodes = np.flatnonzero(e < 0)  # P1: element k spans nodes k and k + 1
    touched = np.union1d(slack_nodes, slack_nodes + 1)
    assert np.all(difference[np.setdiff1d(np.arange(len(difference)), touched)] == 0.0)
    assert difference[touched].max() > 0.0


def test_moordyn_files_are_read_with_moordyns_law():
    scene = read_moordyn("examples/flume_flat.dat")
    assert all(seg.type.damping_when_slack for seg in scene.lines[0].segments)
    assert not replace(scene.lines[0].segments[0].type, damping_when_slack=False).damping_when_slack


def test_moordyn_files_get_moordyns_seabed_damper_and_a_toml_key_sets_it(tmp_path):
    # [seabed] damping_when_opening: MoorDyn-C's damper acts on points moving out too
    from cablefem.errors import InputError
    from cablefem.io.scenes import load_scene

    assert read_moordyn("examples/flume_flat.dat").contact.damping_when_opening
    folder = tmp_path
    (folder / "lines.dat").write_text(open("examples/flume_flat.dat").read())
    path = folder / "scene.toml"
    for text, expected in (("false", False), ("true", True)):
        path.write_text(f'[moordyn]\nfile = "lines.dat"\n[seabed]\ndamping_when_opening = {text}\n')
        assert load_scene(str(path)).contact.damping_when_opening is expected
    path.write_text('[moordyn]\nfile = "lines.dat"\n[seabed]\ndamping_when_opening = "yes"\n')
    with pytest.raises(InputError) as error:
        load_scene(str(path))
    assert "seabed.damping_when_opening" in str(error.value) and "scene.toml" in str(error.value)
    # a TOML scene's own seabed keeps Eq. 11's damper
    assert not Contact().damping_when_opening
