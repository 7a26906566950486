"""Bending on Hermite elements (issue 34): the element, the bending load's physics, clamped ends, the
three assembly paths held equal, the scene keys and their errors, MoorDyn's EI, the outputs. The
closed-form studies are tests/test_verification_bending.py and tests/test_validation_cables.py."""

import json
from dataclasses import replace
import math
import subprocess
import warnings
import sys
from pathlib import Path

import numpy as np
import pytest
from skfem import Basis, ElementLineHermite, MeshLine

from cablefem import InputError
from cablefem.compiled.evaluator import FusedEvaluator
from cablefem.fem import clamp
from cablefem.fem.forms import mass_matrix
from cablefem.fem.hermite import ElementLineHermiteLocal
from cablefem.fem.system import LineSystem
from cablefem.geometry import Horizontal
from cablefem.io import load_scene
from cablefem.loads import State
from cablefem.loads.bending import Bending, curvature
from cablefem.model.line import Line, LineType, Segment
from cablefem.model.scene import Contact, Environment
from cablefem.runs.curvature import curvature_peak, node_curvature
from cablefem.statics.newton import newton
from cablefem.statics.solve import solve_static

ROOT = Path(__file__).resolve().parents[1]
CABLE = LineType("cable", 0.2, 50.0, 1.0e7, damping=0.01, EI=2.0e4)


def cable_system(elements=8, tangents=((1.0, 0.0, 0.3), (0.0, 0.0, 1.0)), assembly="numpy", kind=CABLE):
    """A Hermite cable from (-100, 0, -50) to the origin-ish, both ends clamped by default."""
    line = Line("cable", (-100.0, 0.0, -50.0), (0.0, 0.0, -10.0), (Segment(kind, 130.0, elements),),
                element="hermite", tangents=tangents)
    return LineSystem(line, Horizontal(60.0), Contact(), Environment(), assembly=assembly)


def wavy_state(system, rng):
    """A curved, stretched state meeting the clamps, random velocities and accelerations."""
    def positions(s):
        f = s / 130.0
        return np.column_stack([-100.0 + 100.0 * f, 3.0 * np.sin(6.0 * f), -50.0 + 40.0 * f ** 2 - 5.0 * np.sin(3.0 * f)])

    X = clamp.satisfy(system.clamps, system.fem.interpolate(positions))
    return X, 0.1 * rng.standard_normal(X.shape), rng.standard_normal(X.shape)


# ------------------------------------------------------------------ the element

def test_local_hermite_basis_is_scikit_fems_on_a_short_mesh_and_exact_for_cubics_on_a_long_one():
    short = MeshLine(np.linspace(0.0, 1.0, 5))
    ours, theirs = (Basis(short, e, intorder=6) for e in (ElementLineHermiteLocal(), ElementLineHermite()))
    for a, b in zip(ours.basis, theirs.basis):
        np.testing.assert_allclose(np.asarray(a[0]), np.asarray(b[0]), atol=1e-12)
        np.testing.assert_allclose(a[0].grad, b[0].grad, atol=1e-10)
    # 600 m of 1 m elements: scikit-fem's global power basis is off by ~3e-7 there; ours holds a cubic
    mesh = MeshLine(np.linspace(0.0, 600.0, 601))
    basis = Basis(mesh, ElementLineHermiteLocal(), intorder=6)
    x = mesh.p[0]
    u = np.zeros(basis.N)
    u[0::2], u[1::2] = (x - 300.0) ** 3, 3.0 * (x - 300.0) ** 2
    field = basis.interpolate(u)
    s = np.asarray(basis.global_coordinates())[0]
    np.testing.assert_allclose(np.asarray(field), (s - 300.0) ** 3, rtol=0, atol=1e-15 * 300.0**3)
    np.testing.assert_allclose(field.hess[0, 0], 6.0 * (s - 300.0), rtol=0, atol=1e-10 * 6.0 * 300.0)


def test_hermite_rows_are_positions_then_tangents_and_interpolate_a_cubic_exactly():
    system = cable_system(tangents=(None, None))
    fem = system.fem
    curve = lambda s: np.column_stack([s, 0.01 * s**3 - s**2, 2.0 - s])  # noqa: E731
    X = fem.interpolate(curve)
    nv = fem.n_vertices
    np.testing.assert_allclose(X[:nv], curve(fem.mesh.p[0]))
    s = fem.mesh.p[0]
    np.testing.assert_allclose(X[nv:], np.column_stack([np.ones_like(s), 0.03 * s**2 - 2.0 * s, -np.ones_like(s)]),
                               atol=1e-9)


# --------------------------------------------------------------- the physics

def test_curvature_is_the_circles_in_any_parametrisation_and_rigid_motions_leave_it():
    R, t = 7.0, np.linspace(0.1, 2.0, 9)
    for speed in (1.0, 1.3):  # stretched: |r'| = 1.3
        phase = speed * t / R
        dr = speed * np.array([np.cos(phase), np.sin(phase), 0 * t])
        ddr = speed**2 / R * np.array([-np.sin(phase), np.cos(phase), 0 * t])
        np.testing.assert_allclose(curvature(dr, ddr), speed / (speed * R), rtol=1e-13)  # per stretched length
        Q, _ = np.linalg.qr(np.random.default_rng(1).standard_normal((3, 3)))
        np.testing.assert_allclose(curvature(Q @ dr, Q @ ddr), curvature(dr, ddr), rtol=1e-13)


def test_a_straight_line_feels_no_bending_and_a_rotated_bend_rotated_forces(rng):
    load = Bending(np.array([3.0]))
    a = np.array([1.2, 0.3, -0.4])[:, None, None] * np.ones((3, 1, 2))
    straight = load.evaluate(State(None, a, ddr=0.7 * a))
    assert np.abs(straight.flux).max() < 1e-14 and np.abs(straight.moment).max() < 1e-14
    b = rng.standard_normal((3, 1, 2))
    Q, _ = np.linalg.qr(rng.standard_normal((3, 3)))
    turn = lambda x: np.einsum("ij,jeq->ieq", Q, x)  # noqa: E731
    bent, turned = load.evaluate(State(None, a, ddr=b)), load.evaluate(State(None, turn(a), ddr=turn(b)))
    np.testing.assert_allclose(turn(bent.flux), turned.flux, atol=1e-12)
    np.testing.assert_allclose(turn(bent.moment), turned.moment, atol=1e-12)


def test_a_bending_line_pushes_where_a_cable_goes_slack():
    system = cable_system(tangents=(None, None))
    state = State(None, None)
    state.dr = np.zeros((3, system.fem.n_elements, 3))
    state.dr[0] = 0.99  # compressed by 1 %
    tension = system.tension.evaluate(state)
    np.testing.assert_allclose(tension.flux[0], CABLE.EA * (0.99 - 1.0))
    cable = cable_system(tangents=(None, None), kind=LineType("rope", 0.2, 50.0, 1e7))
    assert np.all(cable.tension.evaluate(state).flux == 0.0)


# ----------------------------------------------------- three paths held equal

@pytest.mark.parametrize("tangents", [(None, None), ((1.0, 0.0, 0.3), (0.0, 0.0, 1.0))], ids=["pinned", "clamped"])
def test_forms_basis_sums_and_kernel_agree_with_clamps_and_inertia(tangents, rng):
    numpy_system, forms_system = cable_system(tangents=tangents), cable_system(tangents=tangents, assembly="forms")
    X, V, A = wavy_state(numpy_system, rng)
    fem = numpy_system.fem
    rows, blocks = numpy_system.evaluate(numpy_system.state(X, V, A), True, 150.0, 2.2e4)
    forms_rows, forms_blocks = forms_system.evaluate(forms_system.state(X, V, A), True, 150.0, 2.2e4)
    K = numpy_system.matrix(blocks).toarray()
    scale = np.abs(rows).max()
    np.testing.assert_allclose(forms_rows, rows, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(forms_system.matrix(forms_blocks).toarray(), K, rtol=0, atol=1e-12 * np.abs(K).max())
    # the kernel: M A + G and K + a_x M, the clamped rows' inertia projected as the loads' are
    M = mass_matrix(numpy_system)
    if numpy_system.clamps:
        M = clamp.project(numpy_system.clamps, M, fem, free_only=False)
    free = fem.free_vector_dofs
    reference = rows + (M @ A.ravel()).reshape(A.shape)
    kernel_rows, band = FusedEvaluator.for_system(numpy_system, numpy_system.props["mass"]).evaluate(X, V, A, 150.0, 2.2e4)
    np.testing.assert_allclose(kernel_rows, reference, rtol=0, atol=1e-12 * np.abs(reference).max())
    dense = FusedEvaluator.for_system(numpy_system, numpy_system.props["mass"]).dense(band)
    tangent = K + 2.2e4 * M[free][:, free].toarray()
    np.testing.assert_allclose(dense, tangent, rtol=0, atol=1e-12 * np.abs(tangent).max())


def test_clamped_tangent_holds_its_direction_and_its_magnitude_is_the_strain(rng):
    system = cable_system(elements=12, assembly="kernel")
    result = solve_static(system)
    fem = system.fem
    for c in system.clamps:
        tangent = result.X[c.row]
        np.testing.assert_allclose(tangent / np.linalg.norm(tangent), c.direction, atol=1e-12)
    # the magnitude is free: it is the end's stretch, 1 + T / EA (T the pull along the tangent; 1.3 % apart
    # at 10.8 m elements, the vertex's strain and the consistent end force each with its own error)
    pull = system.residual(result.X)[fem.fairlead_dof] @ system.clamps[1].direction
    assert np.linalg.norm(result.X[system.clamps[1].row]) - 1.0 == pytest.approx(pull / CABLE.EA, rel=2e-2)


@pytest.mark.parametrize("scheme", ["bdf2", "generalized-alpha"])
def test_compiled_clamp_moment_is_the_numpy_reaction_after_a_step(scheme):
    """Both faces read the clamp's rows where the scheme balances the loads (generalised-alpha: at
    t_{n+1-alpha_f}, as its end forces)."""
    from cablefem.dynamics.registry import INTEGRATORS

    cls = INTEGRATORS[scheme]
    system = cable_system(elements=10, assembly="kernel")
    X = solve_static(system).X
    top = system.line.fairlead
    path = lambda t: (top + np.array([0.5 * t, 0.0, 0.0]), np.array([0.5, 0.0, 0.0]), np.zeros(3))  # noqa: E731
    compiled = cls(system, X, path, dt=0.05, tolerance=1e-10)
    python = cls(system, X, path, dt=0.05, tolerance=1e-10, compiled=False)
    compiled.march(np.array([0.05, 0.1]))
    python.march(np.array([0.05, 0.1]))
    np.testing.assert_allclose(compiled.X, python.X, rtol=0, atol=1e-9 * np.abs(X).max())
    np.testing.assert_allclose(compiled.clamp_moments(), python.clamp_moments(), rtol=1e-6,
                               atol=1e-8 * np.abs(python.clamp_moments()).max())
    assert np.abs(python.clamp_moments()).max() > 1.0  # clamped at both ends, bent by the weight


def test_newton_solves_the_elastica_from_straight_in_a_few_iterations():
    # a cantilever under a tip load of alpha = PL^2/EI = 5 (70 deg at the tip), EA L^2 / EI = 1e8
    from verification.bending.models import line_system, straight, WEIGHTLESS

    system = line_system(10, 1.0, 1.0, 1e8, WEIGHTLESS, tip_mass=5.0 / 9.81)
    X, iterations, _, _, converged = newton(system, straight(system), 1e-11, 50, scale=5.0)
    assert converged and iterations <= 12  # 9 measured; the line search alone crawled (> 100)


# ------------------------------------------------------------------- scenes

SCENE = """name = "cable"
[line_types.cable]
diameter = 0.2
mass = 50.0
EA = 5.0e8
EI = 2.0e4
[[lines]]
name = "cable"
anchor = [-250.0, 0.0, -100.0]
fairlead = [0.0, 0.0, -10.0]
segments = [{ type = "cable", length = 300.0, elements = 30 }]
element = "hermite"
fairlead_tangent = [0.0, 0.0, 1.0]
[seabed]
kind = "horizontal"
depth = 100.0
"""


def write(tmp_path, text, name="cable.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_scene_keys_give_a_clamped_hermite_line(tmp_path):
    scene = load_scene(write(tmp_path, SCENE))
    line = scene.lines[0]
    assert line.hermite and line.order == 3 and line.segments[0].type.EI == 2.0e4
    assert line.tangents[0] is None and np.allclose(line.tangents[1], (0.0, 0.0, 1.0))


@pytest.mark.parametrize("change, key, reason", [
    (("element = \"hermite\"\n", ""), "lines[0].element", "line type 'cable' has EI > 0: bending needs element = \"hermite\""),
    (("EI = 2.0e4", "EI = -1.0"), "line_types.cable.EI", ">= 0"),
    (("element = \"hermite\"\n", "element = \"hermite\"\norder = 2\n"), "lines[0].order", "Hermite elements are cubic"),
    (("fairlead_tangent = [0.0, 0.0, 1.0]", "fairlead_tangent = [0.0, 0.0, 0.0]"), "lines[0].fairlead_tangent",
     "zero vector"),
    (("element = \"hermite\"\n", "element = \"spline\"\n"), "lines[0].element", "valid: lagrange | hermite"),
])
def test_bad_bending_keys_are_one_clear_error(tmp_path, change, key, reason):
    path = write(tmp_path, SCENE.replace(*change))
    with pytest.raises(InputError) as error:
        load_scene(path)
    assert error.value.key == key and reason in str(error.value)


def test_a_clamp_on_lagrange_elements_is_refused(tmp_path):
    text = SCENE.replace("EI = 2.0e4\n", "").replace("element = \"hermite\"\n", "")
    with pytest.raises(InputError, match="clamped end needs element = \"hermite\"") as error:
        load_scene(write(tmp_path, text))
    assert error.value.key == "lines[0].fairlead_tangent"


def test_moordyn_ei_is_read_on_hermite_elements_and_its_beam_in_the_air_solves():
    scene = load_scene(ROOT / "tests" / "data" / "moordyn" / "beam" / "BeamSimplySupported.txt")
    line = scene.lines[0]
    assert line.hermite and line.segments[0].elements == 19 and line.segments[0].type.EI == 1e7
    assert any("Hermite elements" in note for note in scene.notes)
    assert line.anchor[2] == 10.0  # a point above the water, where the file puts it
    system = LineSystem(line, scene.seabed, scene.contact, scene.environment)
    X = solve_static(system).X
    drop = 10.0 - X[: system.fem.n_vertices, 2].min()
    euler_bernoulli = 5.0 * 100.0 * 9.80665 * 10.0**4 / (384.0 * 1e7)
    assert 0.98 * euler_bernoulli < drop < euler_bernoulli  # 0.9906: the beam's sag stretches it


def cablefem_cli(*args):
    return subprocess.run([sys.executable, "-m", "cablefem.cli", *args], capture_output=True, text=True, timeout=300)


def test_static_json_vtk_tensions_and_summary_carry_curvature_and_moment(tmp_path):
    path = write(tmp_path, SCENE + "[motion]\nkind = \"harmonic\"\namplitude = [2.0, 0.0, 1.0]\nperiod = 8.0\n"
                 "ramp = 4.0\n[solver]\ndt = 0.05\nduration = 0.5\n[output]\nevery = 0.25\n")
    done = cablefem_cli("static", str(path), "--json", str(tmp_path / "s.json"))
    assert done.returncode == 0, done.stderr
    line = json.loads((tmp_path / "s.json").read_text())["lines"][0]
    assert len(line["curvature"]) == len(line["bending_moment"]) == len(line["nodes"])
    # at the clamped hang-off the clamp's reaction, and the curvature that moment over EI
    assert line["bending_moment"][-1] > 10 * max(line["bending_moment"][:-1])
    for k in (5, -1):
        assert line["bending_moment"][k] == pytest.approx(2.0e4 * line["curvature"][k], rel=1e-12)
    scene = load_scene(path)  # the run starts from the statics on its own mesh (no vertex moved to the touchdown)
    system = LineSystem(scene.lines[0], scene.seabed, scene.contact, scene.environment)
    X = solve_static(system).X
    moment = np.linalg.norm(clamp.reaction_moments(system, X)[1])
    done = cablefem_cli("run", str(path), "--out", str(tmp_path / "out"))
    assert done.returncode == 0, done.stderr
    rows = (tmp_path / "out" / "tensions.csv").read_text().splitlines()
    assert rows[0].endswith("fairlead_bending_moment,anchor_bending_moment") and len(rows) == 12
    assert float(rows[1].split(",")[-2]) == pytest.approx(moment, rel=1e-2)
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    extreme = summary["curvature_extremes"]["cable"]
    assert extreme["curvature_max"] > 0 and 0.0 <= extreme["s"] <= 300.0 and 0.0 <= extreme["t"] <= 0.5
    import meshio

    frame = meshio.read(sorted((tmp_path / "out").glob("cable_*.vtu"))[-1])
    assert {"curvature", "bending_moment"} <= set(frame.point_data)


def test_lagrange_lines_report_zero_curvature_and_scenes_without_ei_no_bending_columns(tmp_path):
    text = SCENE.replace("EI = 2.0e4\n", "").replace("element = \"hermite\"\n", "").replace(
        "fairlead_tangent = [0.0, 0.0, 1.0]\n", "")
    scene = load_scene(write(tmp_path, text))
    system = LineSystem(scene.lines[0], scene.seabed, scene.contact, scene.environment)
    X = solve_static(system).X
    kappa, moment = node_curvature(system, X)
    assert not kappa.any() and not moment.any() and curvature_peak(system, X) == (0.0, None)
    from cablefem.runs.run import _columns
    from cablefem.runs.bending_rows import BendingRows

    assert not BendingRows(scene.lines) and _columns(scene, bending=BendingRows(scene.lines))[-1] == "fz"


BEAMS = """name = "beams"
[line_types.beam]
diameter = 0.01
mass = 10.0
EA = 1.0e8
EI = 1.0e8
[points.left]
kind = "fixed"
position = [0.0, 0.0, 1.0]
[points.right]
kind = "fixed"
position = [20.0, 0.0, 1.0]
[seabed]
kind = "horizontal"
depth = 1000.0
"""
#: two beams of 10 m, each clamped level at its outer end, meeting at a free point
HINGED = BEAMS + """[points.hinge]
kind = "free"
position = [10.0, 0.0, 1.0]
[[lines]]
name = "a"
anchor = "left"
fairlead = "hinge"
segments = [{ type = "beam", length = 10.0, elements = ELEMENTS }]
element = "hermite"
anchor_tangent = [1.0, 0.0, 0.0]
[[lines]]
name = "b"
anchor = "right"
fairlead = "hinge"
segments = [{ type = "beam", length = 10.0, elements = ELEMENTS }]
element = "hermite"
anchor_tangent = [-1.0, 0.0, 0.0]
"""
#: the same beam welded: one line of two segments, its tangent continuous at x = 10 m
WELDED = BEAMS + """[[lines]]
name = "a"
anchor = "left"
fairlead = "right"
segments = [{ type = "beam", length = 10.0, elements = ELEMENTS }, { type = "beam", length = 10.0, elements = ELEMENTS }]
element = "hermite"
anchor_tangent = [1.0, 0.0, 0.0]
fairlead_tangent = [1.0, 0.0, 0.0]
"""


@pytest.mark.parametrize("elements", [4, 8])
def test_two_bending_lines_meeting_at_a_free_point_are_hinged_there(tmp_path, elements):
    """Two beams of 10 m in air (EI 1e8 N m^2, 10 kg/m), each clamped level at its outer end, meet at a
    free point between them. A point is a hinge (MoorDyn's points): the two lines are strings of their
    own and the point a junction, sharing its position, each end's tangent free. By symmetry the hinge
    carries no shear and it carries no moment, so each beam is a cantilever under its weight: the
    hinge drops w L^4 / (8 EI) (Hermite vertices are exact for Euler-Bernoulli; the rest is the
    geometric nonlinearity, ~1e-7), and the curvature at the hinge ends vanishes as the mesh is
    refined (the last element's cubic against the quartic: ~(h / L)^2 / 6 of the clamp's). Welded
    (one line of two segments), the same beam is clamped-clamped: its middle drops w (2L)^4 / (384 EI),
    a third of the hinge's, and bends there with a third of the clamp's curvature."""
    from cablefem.statics.scene import static_lines

    L, EI = 10.0, 1.0e8
    drops, mid_curvatures, clamp_curvatures = [], [], []
    for text in (HINGED, WELDED):
        scene = load_scene(write(tmp_path, text.replace("ELEMENTS", str(elements))))
        w = 10.0 * scene.environment.gravity
        systems, results, _, network = static_lines(scene)
        ends = []
        for system, result in zip(systems, results):
            n = system.fem.n_vertices
            kappa, _ = node_curvature(system, result.X)
            ends.append((1.0 - result.X[:n, 2], kappa))
        if network is not None:  # the hinge: two strings, each from its clamp to the junction
            assert sorted(line.name for line in scene.lines) == ["a", "b"] and network.points.keys() == {"hinge"}
            (drop_a, kappa_a), (drop_b, kappa_b) = ends
            np.testing.assert_allclose(drop_a, drop_b, rtol=0, atol=1e-9 * drop_a[-1])  # symmetric
            np.testing.assert_allclose(network.points["hinge"][2], 1.0 - drop_a[-1], rtol=0, atol=1e-12)
            drops.append(drop_a[-1])
            mid_curvatures.append(max(kappa_a[-1], kappa_b[-1]))
            clamp_curvatures.append(kappa_a[0])
        else:
            (drop, kappa), = ends
            middle = len(drop) // 2
            drops.append(drop[middle])
            mid_curvatures.append(kappa[middle])
            clamp_curvatures.append(kappa[0])
    cantilever = w * L**4 / (8.0 * EI)
    assert abs(drops[0] / cantilever - 1.0) < 1e-6
    assert abs(drops[1] / (w * (2 * L) ** 4 / (384.0 * EI)) - 1.0) < 1e-6
    clamp_kappa = w * L**2 / (2.0 * EI)  # the cantilever's clamp: M = w L^2 / 2
    assert mid_curvatures[0] < 0.25 * (L / elements) ** 2 / L**2 * clamp_kappa
    assert abs(mid_curvatures[1] / (w * L**2 / (6.0 * EI)) - 1.0) < 0.1  # clamped-clamped: w (2L)^2 / 24
    assert abs(clamp_curvatures[1] / (w * L**2 / (3.0 * EI)) - 1.0) < 0.3  # and at its clamps w (2L)^2 / 12


ON_A_BODY = SCENE.replace('fairlead = [0.0, 0.0, -10.0]', 'fairlead = "hangoff"') + """[bodies.vessel]
kind = "coupled"
position = [0.0, 0.0, -10.0]
[bodies.vessel.motion]
kind = "harmonic"
amplitude = [1.0, 0.0, 0.0, 0.0, PITCH, 0.0]
period = 10.0
[points.hangoff]
body = "vessel"
position = [0.0, 0.0, 0.0]
"""


def test_a_clamp_on_a_body_that_turns_or_is_free_is_refused_with_its_key(tmp_path):
    """A clamp that turns with its body (R(t) d) is not built: a clamped line end on a coupled body whose
    motion turns it is refused in a run, naming the body's motion (its statics, at rest, solve); one on a
    free body is refused when the scene is read (the clamp's moment is not in the body's balance). A
    body that only translates keeps the clamp's direction, as a moving fairlead does."""
    from cablefem.model.network import check_steppable

    check_steppable(load_scene(write(tmp_path, ON_A_BODY.replace("PITCH", "0.0"))))
    turning = load_scene(write(tmp_path, ON_A_BODY.replace("PITCH", "0.05")))
    with pytest.raises(InputError, match="whose motion turns it .* a clamp that turns with its body is not built") as error:
        check_steppable(turning)
    assert error.value.key == "bodies.vessel.motion"
    free = ON_A_BODY.replace('kind = "coupled"', 'kind = "free"\nmass = 1e5\ninertia = [1e6, 1e6, 1e6]').replace(
        "[bodies.vessel.motion]\nkind = \"harmonic\"\namplitude = [1.0, 0.0, 0.0, 0.0, PITCH, 0.0]\nperiod = 10.0\n", "")
    with pytest.raises(InputError, match="free body 'vessel' is not built") as error:
        load_scene(write(tmp_path, free))
    assert error.value.key == "lines[0].fairlead_tangent"


@pytest.mark.parametrize("assembly", ["numpy", "kernel"])
def test_a_bending_line_with_its_own_axial_law_pulls_and_pushes_as_with_its_ea(assembly, rng):
    """A line type that bends with an axial law of its own (``cablefem.loads.rope``) on Hermite elements:
    its law is the tension, with the Hermite strain at the same Simpson points, and it pushes (a rod: the
    law carried into compression at the slope EA). A linear strain-tension table of slope EA gives the
    constant EA's rows and tangent, taut and compressed (1e-12; the push not zero)."""
    from cablefem.model.axial import AxialLaw, Curve

    EA = 1.0e7
    law = AxialLaw("table", Curve.from_rows([0.0, 0.1], [0.0, 0.1 * EA], "EA"))
    plain = replace(CABLE, damping=0.0)  # a law of its own takes BA, not beta; statics has neither
    roped = replace(plain, name="roped", EA=law.reference_EA, axial=law)
    for stretch in (1.02, 0.99):  # taut, then compressed
        rows = []
        for kind in (plain, roped):
            system = cable_system(kind=kind, assembly=assembly)
            assert system.has("rope") == (kind is roped)
            X, _, _ = wavy_state(system, rng)
            n = system.fem.n_vertices
            X[:n] = X[0] + stretch * (X[:n] - X[0])  # the vertices' chords scaled
            R, blocks = system.evaluate(system.state(X))
            rows.append((R, system.matrix(blocks).toarray()))
        (R0, K0), (R1, K1) = rows
        np.testing.assert_allclose(R1, R0, rtol=0, atol=1e-12 * np.abs(R0).max())
        np.testing.assert_allclose(K1, K0, rtol=0, atol=1e-12 * np.abs(K0).max())
    system = cable_system(kind=roped)  # the compressed state once more, the rope told not to push
    system.load("rope").rod[:] = False
    slack = system.evaluate(system.state(X))[0]
    assert np.abs(slack - R1).max() > 0.1 * np.abs(R1).max()  # the push is no round-off


def test_a_bending_line_in_a_junction_network_runs_compiled_as_in_python(tmp_path):
    # benchmarks/crowfoot.toml with its upper line a cable of EI = 1e4 N m^2 on Hermite elements: the
    # junction's compiled steps take the Hermite string with the chain legs (one numba type)
    from cablefem.dynamics.group import junction_groups
    from cablefem.dynamics.registry import INTEGRATORS, integrator_options
    from cablefem.fem.system import build_system
    from cablefem.model.network import anchor_path, boundary_path, dynamic_lines
    from cablefem.statics.scene import start_states

    text = (ROOT / "benchmarks" / "crowfoot.toml").read_text().replace(
        '[bodies.platform]', '[line_types.cable]\ndiameter = 0.1\nmass = 60.0\nEA = 5e8\ndamping = 0.01\n'
        'Cd_normal = 1.2\nCa_normal = 1.0\nEI = 1.0e4\n[bodies.platform]').replace(
        'segments = [{ type = "chain", length = 185.0, elements = 20 }]',
        'segments = [{ type = "cable", length = 185.0, elements = 20 }]\nelement = "hermite"')
    path = tmp_path / "crowfoot_bending.toml"
    path.write_text(text)
    finals = []
    for compiled in (True, False):
        scene = load_scene(path)
        assert any(line.hermite for line in scene.lines)
        systems = [build_system(scene, line) for line in dynamic_lines(scene)]
        states, _ = start_states(scene, systems=systems)
        options = {**integrator_options(scene.solver), "compiled": compiled}
        integrators = [INTEGRATORS[scene.solver.integrator](system, X0, boundary_path(scene, line), dt=0.05,
                                                            anchor=anchor_path(scene, line), **options)
                       for system, line, X0 in zip(systems, scene.lines, states)]
        steps = junction_groups(scene, integrators)[0]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            steps.march(0.05 * np.arange(1, 21))
        assert not any("differ in type" in str(w.message) for w in caught)
        finals.append([integ.X.copy() for integ in integrators])
    for compiled, python in zip(*finals):
        np.testing.assert_allclose(compiled, python, rtol=0, atol=1e-8 * np.abs(python).max())
