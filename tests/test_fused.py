"""The compiled step kernel (cablefem.compiled.evaluator) against the reference numpy loads and assembly."""

from dataclasses import replace

import numpy as np
import pytest

from cablefem.dynamics.bdf2 import BDF2
from cablefem.dynamics.generalized_alpha import GeneralizedAlpha
from cablefem.compiled.evaluator import FusedEvaluator
from cablefem.model.network import boundary_path
from cablefem.fem.system import build_system
from cablefem.statics.scene import start_states
from cablefem.model.builtin import flume_scene


def reference(system, X, V, A, v_x, a_x):
    """Rows M A + G and the dense free tangent K + a_x M from the numpy path."""
    fem = system.fem
    M = fem.vector_mass(system.props["mass"], free_only=False)
    R, blocks = system.evaluate(system.state(X, V, A), True, v_x, a_x)
    rows = R + (M @ A.ravel()).reshape(A.shape)
    K = system.matrix(blocks) + a_x * fem.vector_mass(system.props["mass"])
    return rows, K.toarray()


@pytest.mark.parametrize("seabed", ["flat", "steep"])  # plane, and a triangulated step
@pytest.mark.parametrize("friction", ["none", "isotropic", "anisotropic"])
@pytest.mark.parametrize("order", [1, 2, 3])
def test_compiled_step_equals_the_reference_assembly(seabed, friction, order):
    scene = flume_scene(seabed, elements=10, order=order)
    scene.friction = replace(scene.friction, model=friction, static_scale=1.3)
    scene.environment = replace(scene.environment, current=(0.4, -0.2, 0.0))
    system = build_system(scene, scene.lines[0])
    rng = np.random.default_rng(order)
    X0 = start_states(scene)[0][0]
    X = X0 + 0.05 * rng.standard_normal(X0.shape)
    V = 0.3 * rng.standard_normal(X0.shape)
    A = rng.standard_normal(X0.shape)
    fused = FusedEvaluator.for_system(system, system.props["mass"])
    rows_ref, K_ref = reference(system, X, V, A, 150.0, 2.2e4)
    rows, band = fused.evaluate(X, V, A, 150.0, 2.2e4)
    # the same sums in another order: equal to round-off
    np.testing.assert_allclose(rows, rows_ref, rtol=0, atol=1e-12 * np.abs(rows_ref).max())
    np.testing.assert_allclose(fused.dense(band), K_ref, rtol=0, atol=1e-12 * np.abs(K_ref).max())
    step = fused.solve(fused.factorize(band), rows)
    expected = np.linalg.solve(K_ref, -rows_ref[system.fem.free_dofs].ravel()).reshape(-1, 3)
    np.testing.assert_allclose(step, expected, rtol=0, atol=1e-9 * np.abs(expected).max())


@pytest.mark.parametrize("cls", [BDF2, GeneralizedAlpha])
def test_compiled_and_numpy_runs_agree(cls):
    scene = flume_scene("steep", elements=20)
    line = scene.lines[0]
    X0 = start_states(scene)[0][0]
    runs = []
    for compiled in (False, True):
        integ = cls(build_system(scene, line), X0, boundary_path(scene, line), dt=0.02,
                    tolerance=1e-12, compiled=compiled, newton="full")
        assert integ.evaluator.compiled == compiled
        tensions = []
        for _ in range(100):
            integ.step()
            tensions.append(np.linalg.norm(integ.reactions()[0]))
        runs.append(np.array(tensions))
    # same equations, same Newton: the difference is round-off amplified by 100 steps
    np.testing.assert_allclose(runs[1], runs[0], rtol=1e-8)


def test_a_load_with_no_compiled_face_fails_loudly():
    # issue 15: the compiled path never falls back silently (it used to return None here and send
    # the whole run down the numpy path)
    scene = flume_scene("flat", elements=6)
    system = build_system(scene, scene.lines[0])

    class Wind:  # a load the catalog does not know
        def evaluate(self, state, jacobian=True):
            from cablefem.loads import Terms
            return Terms()

    system.loads.append(Wind())
    with pytest.raises(TypeError, match="Wind is not in the load catalog"):
        FusedEvaluator.for_system(system, system.props["mass"])
