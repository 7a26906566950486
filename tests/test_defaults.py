"""Defaults by physics (cablefem.model.defaults, docs/scene.md "Defaults by physics"): a MoorDyn file's
NumSegs read as an accuracy, steps and frames by the forcing period; every explicit key obeyed as written."""

import math
from pathlib import Path

import numpy as np
import pytest

from cablefem.io import load_scene
from cablefem.model import defaults

ROOT = Path(__file__).resolve().parents[1]
OC4 = ROOT / "examples" / "oc4_semi.dat"
FLUME = ROOT / "benchmarks" / "flume_snap_20.dat"


def test_moordyn_line_at_defaults_is_as_accurate_in_statics_as_its_numsegs():
    """MoorDyn's lumped mass at N segments is, in statics, cablefem's P1 on N elements (the consistent
    load of a uniform weight is the lumped one; the tension is constant per element). The fairlead
    tension errors against P2 x 320 scatter with where the touchdown falls in an element, so their
    power-law fits are compared: at NumSegs 10, 20, 40 and 80 the default mesh's fitted error is at
    most P1 x NumSegs's, on OC4's chain and the flume chain; above NumSegs 20 half as many P2 elements
    would not be (the reason the count grows faster there)."""
    from verification.work_precision import numsegs

    for name, path in numsegs.FILES.items():
        result = numsegs.study(name, path)
        (c1, p1), (c2, p2) = result["p1_fit"], result["p2_fit"]
        assert p1 > 2.0 and p2 > 1.5, (name, p1, p2)  # both converge: the fits mean something
        for count in (10, 20, 40, 80):
            assert c2 * defaults.moordyn_elements(count) ** -p2 <= c1 * count ** -p1, (name, count)
        for count in (40, 80):
            assert c2 * math.ceil(count / 2) ** -p2 > c1 * count ** -p1, (name, count)


def test_moordyn_file_gets_p2_from_numsegs_and_a_note_naming_the_choice():
    scene = load_scene(str(OC4))
    assert all(line.order == 2 and [s.elements for s in line.segments] == [math.ceil(20 / 2)]
               for line in scene.lines)
    mesh = [note for note in scene.notes if note.startswith("mesh:")]
    assert len(mesh) == 1 and "NumSegs 20 -> 10" in mesh[0] and "P2" in mesh[0]
    # no motion in a MoorDyn file: nothing sets a step, the plain one stays
    assert not any(note.startswith("steps:") for note in scene.notes)
    assert not scene.solver.adaptive and scene.solver.dt == 0.01 and scene.output.every == 0.1


def _wrapped(tmp_path, moordyn="", solver="", output=""):
    text = (f'name = "oc4"\n[moordyn]\nfile = "{OC4}"\n{moordyn}\n'
            '[motion]\nkind = "harmonic"\namplitude = [5.0, 0.0, 0.0]\nperiod = 10.0\nramp = 10.0\n'
            f"[solver]\nduration = 20.0\n{solver}\n[output]\n{output}\n")
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return load_scene(str(path))


def test_the_step_defaults_to_a_fortieth_of_the_forcing_period(tmp_path):
    scene = _wrapped(tmp_path)
    assert not scene.solver.adaptive
    assert scene.solver.dt == pytest.approx(10.0 / defaults.FIXED_STEPS_PER_PERIOD)
    steps = [note for note in scene.notes if note.startswith("steps:")]
    assert len(steps) == 1 and "1/40 of the shortest forcing period (10 s)" in steps[0]
    assert scene.output.every == pytest.approx(10.0 / defaults.FRAMES_PER_PERIOD)


@pytest.mark.parametrize("keys, order, elements", [
    ("order = 1", 1, 20),          # the order alone: NumSegs elements, as before
    ("elements = 10", 1, 10),      # the count alone: P1, as before
    ("order = 3\nelements = 4", 3, 4),
])
def test_moordyn_mesh_keys_in_a_toml_override_the_default(tmp_path, keys, order, elements):
    scene = _wrapped(tmp_path, moordyn=keys)
    assert all(line.order == order and sum(s.elements for s in line.segments) == elements for line in scene.lines)
    assert not any(note.startswith("mesh:") for note in scene.notes)


@pytest.mark.parametrize("solver, adaptive, dt, note", [
    ("dt = 0.02", False, 0.02, False),                 # a step: fixed steps of it
    ("adaptive = false", False, 0.01, False),          # fixed steps of the plain default
    ("adaptive = true", True, 0.5, True),              # error control, its largest step chosen
    ("adaptive = true\ndt = 0.2", True, 0.2, False),   # the OC4 case, as written
])
def test_solver_keys_override_the_default_step(tmp_path, solver, adaptive, dt, note):
    scene = _wrapped(tmp_path, solver=solver)
    assert scene.solver.adaptive == adaptive and scene.solver.dt == pytest.approx(dt)
    assert any(n.startswith("steps:") for n in scene.notes) == note


def test_adaptive_frames_fall_at_most_once_per_largest_step(tmp_path):
    scene = _wrapped(tmp_path, solver="adaptive = true\ndt = 2.0")
    assert scene.output.every == pytest.approx(2.0)


def test_an_explicit_frame_interval_is_obeyed(tmp_path):
    assert _wrapped(tmp_path, output="every = 0.1").output.every == 0.1


def test_moordyn_dtout_sets_the_frame_interval(tmp_path):
    text = OC4.read_text().replace("200.0     WtrDpth", "200.0     WtrDpth\n0.25      dtOut")
    path = tmp_path / "oc4.dat"
    path.write_text(text)
    scene = load_scene(str(path))
    assert scene.output.every == 0.25
    assert scene.keys["output.every"][1].endswith("OPTIONS.dtOut")


def test_largest_step_follows_the_shortest_strong_wave_period():
    from cablefem.model.scene import Motion
    from cablefem.waves.sea import Sea

    sea = Sea.from_components([1.0, 0.5, 0.01], [2 * np.pi / 10, 2 * np.pi / 8, 2 * np.pi / 2], [0, 0, 0],
                              [0, 0, 0], depth=200.0)
    # the 2 s component is 1 % of the largest amplitude: the 8 s one sets the step
    assert defaults.largest_step(Motion(), sea) == pytest.approx(8.0 / defaults.STEPS_PER_PERIOD)
    assert defaults.largest_step(Motion(kind="harmonic", period=6.0)) == pytest.approx(0.3)
    assert defaults.largest_step(Motion()) == defaults.LONGEST_STEP
    table = Motion(kind="table", times=np.array([0.0, 0.5, 1.0]), positions=np.zeros((3, 3)), ramp=17.0)
    assert defaults.forcing_periods(table) == [1.0, 17.0]  # twice its rows' interval, and its ramp


def test_a_network_driven_by_its_platform_alone_steps_a_fortieth_of_the_platforms_period():
    """validation/networks' semi-taut system without its [solver] dt and [output] every: its fairleads
    sit on a coupled platform moving at 14.9 s (no [motion]), so the defaults' step is 14.9 / 40 s and
    its frames 1.49 s, where a scene read before coupled bodies' motions counted got the plain 0.01 s."""
    import tomllib

    from cablefem.io.toml_scene import read_toml_scene

    path = Path(__file__).resolve().parents[1] / "validation" / "networks" / "inputs" / "semitaut.toml"
    data = tomllib.loads(path.read_text())
    data.get("solver", {}).pop("dt", None)
    data.get("output", {}).pop("every", None)
    scene = read_toml_scene(str(path), data)
    period = next(body.motion.period for body in scene.bodies.values() if body.kind == "coupled")
    assert period == pytest.approx(14.9) and "motion" not in data
    assert scene.solver.dt == pytest.approx(period / defaults.FIXED_STEPS_PER_PERIOD)
    assert scene.output.every == pytest.approx(period / defaults.FRAMES_PER_PERIOD)


def test_oc4_adaptive_with_steps_up_to_02_s_runs_past_where_it_failed(tmp_path):
    """Issue 33's case: OC4's chains, P1 x NumSegs, adaptive BDF2 allowed steps of 0.2 s, failed with
    "Newton did not converge at t = 77.1 s" (the compiled steps never grew after a cut step), then at
    t = 44.5 s with its residual stuck at 9.5e-5 at every step down to 4.4e-4 s: the seabed damper
    (cBot) switched on in full as a moving point touched down, a jump in the residual that no step
    can solve (the same run without cBot completed). The damper engages over a depth now
    (``cablefem.loads.contact``), and the run goes to 80 s."""
    from dataclasses import replace

    from cablefem.runs.run import run_scene

    scene = _wrapped(tmp_path, moordyn="order = 1", solver="adaptive = true\ndt = 0.2")
    scene.output = replace(scene.output, every=1.0)
    summary = run_scene(scene, str(tmp_path / "out"), duration=80.0, progress=False)
    from cablefem.post import read_tensions

    assert summary["status"] == "completed"
    assert read_tensions(str(tmp_path / "out"))["t"][-1] == pytest.approx(80.0)


def test_buoyant_and_bending_moordyn_lines_keep_the_files_mesh(tmp_path):
    """tripod.txt: its float string (a buoyant segment) keeps P1 x NumSegs, where P2 elements fold at
    zero tension (``defaults.keeps_numsegs``; its statics converge: tests/test_moordyn_files.py); its
    legs, all heavier than water, get P2 x NumSegs / 2; with its EI, every line keeps NumSegs Hermite
    elements. The note names each choice."""
    from test_moordyn_files import data, without_ei

    scene = load_scene(str(without_ei("tripod.txt", tmp_path)))
    meshes = {line.name: (line.element, line.order, [s.elements for s in line.segments]) for line in scene.lines}
    assert meshes["line2+1"] == ("lagrange", 1, [5, 3])
    assert all(meshes[name] == ("lagrange", 2, [3, 7, 4]) for name in ("line5+4+3", "line8+7+6", "line11+10+9"))
    (note,) = [note for note in scene.notes if note.startswith("mesh:")]
    assert "line2+1: NumSegs 5+3 -> 5+3 P1, a buoyant segment" in note
    bending = load_scene(data("tripod.txt"))
    assert all(line.element == "hermite" for line in bending.lines)
    counts = {line.name: [s.elements for s in line.segments] for line in bending.lines}  # hinged: a string each
    assert (counts["line2"], counts["line1"]) == ([5], [3])


def test_oc4_at_defaults_with_error_control_steps_through_its_seabed_strikes(tmp_path):
    """``cablefem run`` of OC4 at its defaults (P2 x 10) with ``adaptive = true``: at t = 13.96 s a
    node of line 2 strikes the seabed at 2.2 m/s and cBot stops it within milliseconds. Newton
    solves that step at any size from 0.5 s to 1 ms, but the error control, which counted the
    node's sideways difference as tension, rejected it down to 1.3 ms, where Newton stalled ("did
    not converge at t = 13.9557 s"). The step error is the tension the difference makes (its
    component along the line, ``Integrator.tension_error``): the run completes (without cBot it
    always did). In a child process, as a user runs it: inside pytest's own process the same run
    took other steps and passed either way (round-off in the steps' history, not found)."""
    import json
    import subprocess
    import sys

    path = tmp_path / "scene.toml"
    path.write_text(f'name = "oc4"\n[moordyn]\nfile = "{OC4}"\n[motion]\nkind = "harmonic"\n'
                    'amplitude = [5.0, 0.0, 0.0]\nperiod = 10.0\nramp = 10.0\n[solver]\nduration = 20.0\n'
                    'adaptive = true\n')
    done = subprocess.run([sys.executable, "-m", "cablefem.cli", "run", str(path), "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["status"] == "completed"
