"""A new integrator is one file and one registry entry (docs/architecture.md, "Adding an integrator"):
``tests/toy_integrator.py``'s backward Euler runs a line and a junction network, compiled and on the
Python ops, with the policy's Newton and step control, and is first order in time as it should be."""

import numpy as np
import pytest
from toy_integrator import BackwardEuler

from cablefem.dynamics.registry import INTEGRATORS
from cablefem.io import load_scene
from cablefem.model.builtin import flume_scene
from cablefem.runs.run import run_scene
from cablefem.study import start_line, tensions
from test_junction_steps import CROWFOOT, SURGE


@pytest.fixture
def registered(monkeypatch):
    """The one registry entry."""
    monkeypatch.setitem(INTEGRATORS, "backward-euler", BackwardEuler)


def surge_line(dt, integrator="backward-euler", python=False, motion="dynamic", duration=3.0):
    """The flat flume line (P1 x 12) under its surge, ``duration`` s: the fairlead tensions [N] and
    the integrator."""
    scene = flume_scene("flat", motion, 12, 1, 1.0, dt)
    integ = start_line(scene, dt=dt, integrator=integrator, newton="full", tolerance=1e-10)
    if python:
        integ.stepper().packer = None
    times = dt * np.arange(1, int(round(duration / dt)) + 1)
    return tensions(integ, times)[0], integ


def test_a_registered_integrator_runs_a_line_compiled_and_in_python_alike(registered):
    compiled, integ = surge_line(0.02)
    assert integ.stepper().packer is not None  # its steps compiled without an edit elsewhere
    python, other = surge_line(0.02, python=True)
    np.testing.assert_allclose(compiled, python, rtol=0, atol=1e-9 * np.abs(python).max())
    assert integ.statistics()["newton_iterations"] == other.statistics()["newton_iterations"]


def test_backward_euler_converges_at_first_order(registered):
    """Against BDF2 at a step 8 times smaller, under the quasi-static surge (6 s): the fairlead
    tension's largest error halves with the step. The observed order climbs towards one as the step
    shrinks (0.55, 0.76, 0.84 from dt = 0.04 to 0.005 s: backward Euler's damping of the line's
    axial ring keeps the coarse steps out of the asymptotic range; under the dynamic surge even
    0.01 s is not in it), where BDF2's would be two."""
    reference, _ = surge_line(0.00125, "bdf2", motion="quasi-static", duration=6.0)
    errors = []
    for dt in (0.01, 0.005):
        series, _ = surge_line(dt, motion="quasi-static", duration=6.0)
        stride = int(round(dt / 0.00125))
        errors.append(np.abs(series - reference[stride - 1::stride]).max())
    order = np.log2(errors[0] / errors[1])
    assert 0.75 <= order <= 1.25, (errors, order)


def test_a_registered_integrator_steps_a_junction_network(registered, tmp_path, monkeypatch):
    """The crowfoot (three strings meeting at a junction with a clump) by name from a scene, compiled
    and on the Python ops: the same forces to round-off."""
    path = tmp_path / "crowfoot.toml"
    path.write_text(CROWFOOT.replace("dt = 0.05", 'dt = 0.05\nintegrator = "backward-euler"') + SURGE)
    scene = load_scene(path)
    assert scene.solver.integrator == "backward-euler"
    summary = run_scene(scene, str(tmp_path / "out"), duration=2.0, progress=False)
    assert summary["completed"] and summary["integrator"][0]["integrator"] == "backward-euler"
    compiled = np.loadtxt(tmp_path / "out" / "tensions.csv", delimiter=",", skiprows=1)
    from cablefem.dynamics import group

    original = group.Group.__init__

    def python_only(self, *args, **kwargs):
        original(self, *args, **kwargs)
        self.packer = None

    monkeypatch.setattr(group.Group, "__init__", python_only)
    run_scene(scene, str(tmp_path / "python"), duration=2.0, progress=False)
    python = np.loadtxt(tmp_path / "python" / "tensions.csv", delimiter=",", skiprows=1)
    np.testing.assert_allclose(compiled, python, rtol=0, atol=1e-8 * np.abs(python).max())
