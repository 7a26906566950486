"""Soil below the seabed surface (issue 17, rui2025): the macro-element's closed forms, where it acts
and how it meets the surface, the resting depth and friction of a lying chain, the pretension path,
the energy of a path and of a run (plastic work >= 0 each step, the balance closing), the JSON and
VTK fields, and one line per bad input."""

import json
import textwrap

import numpy as np
import pytest

from cablefem.dynamics.energy import step_work, stored_energy
from cablefem.geometry import Horizontal, Plane
from cablefem.io import load_scene
from cablefem.loads import State
from cablefem.loads.soil import Soil
from cablefem.statics.pretension import LoadPath, resting_depth, solve_pretension
from cablefem.runs.results import end_forces
from cablefem.fem.system import build_system

#: a small line in soil: a chain 3 m below the mudline of 30 m of water, 70 m to a fairlead 5 m deep
SMALL = """
name = "small-soil"

[line_types.chain]
diameter = 0.1
nominal_diameter = 0.055
mass = 60.0
EA = 2.5e8
{line_type}

[[lines]]
name = "line1"
anchor = [60.0, 0.0, {anchor_z}]
fairlead = [0.0, 0.0, -5.0]
segments = [{{ type = "chain", length = 10.0, elements = 10 }}, {{ type = "chain", length = 60.0, elements = 20 }}]

[seabed]
kind = "horizontal"
depth = 30.0

[soil]
su_gradient = 1500.0
installation_steps = {steps}
{soil}
{extra}
"""


def small_scene(tmp_path, anchor_z=-33.0, soil="", line_type="", extra="", steps=50, name="small.toml"):
    """The small scene with keys added to its [soil] table, its line type and the end of the file."""
    path = tmp_path / name
    path.write_text(SMALL.format(anchor_z=anchor_z, soil=soil, line_type=line_type, extra=extra, steps=steps))
    return path


def point_soil(su_mudline=2000.0, su_gradient=1500.0, d_b=0.1, seabed=None):
    """A soil of one element over a horizontal mudline at z = -50 m (or ``seabed``)."""
    return Soil(seabed or Horizontal(50.0), 8.0 * d_b, 2.5 * 7.6 * d_b, np.array([1.0 / d_b]),
                np.array([2.0 / d_b]), su_mudline, su_gradient, np.array([d_b]))


def points(soil, r, anchors, tangent=(1.0, 0.0, 0.0)):
    """Force (3, n) and trial history of the soil at points r (n, 3) held at ``anchors`` (n, 3), the
    line along ``tangent``."""
    from cablefem.loads import catalog

    n = len(r)
    old = np.zeros((1, n), catalog.layout().full_history)
    old["soil"]["anchor"][0] = anchors
    new = old.copy()
    dr = np.tile(np.asarray(tangent, dtype=float), (n, 1)).T[:, None, :]
    state = State(np.asarray(r, dtype=float).T[:, None, :], dr, old=old, new=new)
    return soil.evaluate(state, jacobian=False).force[:, 0, :], new


def test_reaction_is_the_spring_below_yield_and_the_yield_force_beyond():
    soil = point_soil()
    at = np.array([0.0, 0.0, -53.0])  # 3 m deep, the line along x
    offsets = np.array([[0.03, 0, 0], [0.3, 0, 0], [0, 0.02, 0], [0, -0.04, 0.03], [0, 0.3, -0.4]])
    depth = 3.0 - offsets[:, 2]  # each point's own depth
    su = 2000.0 + 1500.0 * depth
    t_f, n_f = 8.0 * 0.1 * su, 2.5 * 7.6 * 0.1 * su  # rui2025 Eq. 3 per unit length
    force, new = points(soil, at + offsets, np.tile(at, (5, 1)))
    # K = k f_yield (Eq. 2), k_t = 1/d_b = 10, k_n = 2/d_b = 20 [1/m]; the normal plane returns radially
    expected = [[-10.0 * t_f[0] * 0.03, 0, 0], [-t_f[1], 0, 0], [0, -20.0 * n_f[2] * 0.02, 0],
                [0, 20.0 * n_f[3] * 0.04, -20.0 * n_f[3] * 0.03], [0, -0.6 * n_f[4], 0.8 * n_f[4]]]
    np.testing.assert_allclose(force.T, expected, rtol=1e-12, atol=1e-9 * n_f.max())
    # the plastic anchors follow to the yield offsets 1/k_t = 0.1 m, 1/k_n = 0.05 m; the elastic stay
    np.testing.assert_allclose(new["soil"]["anchor"][0], at + [[0, 0, 0], [0.2, 0, 0], [0, 0, 0], [0, 0, 0],
                                                               [0, 0.27, -0.36]], atol=1e-12)
    np.testing.assert_allclose(new["soil"]["slip"][0], [0, 0.2, 0, 0, 0.45], atol=1e-12)


def test_strength_is_taken_at_the_depth_below_the_local_surface_along_its_normal():
    slope = Plane.from_slope([0.0, 0.0, -50.0], np.radians(25.0), azimuth=0.3)
    soil = point_soil(su_mudline=0.0, seabed=slope)
    depths = np.array([0.5, 2.0, 7.0])
    r = slope.point - depths[:, None] * slope.normal + [[10.0, 3.0, 0.0]] * np.array([[1.0], [-2.0], [0.5]])
    r[:, 2] = slope.elevation(r[:, :2]) - depths / slope.normal[2]  # straight down, depths along the normal
    level = np.cross(slope.normal, [0.0, 0.0, 1.0])
    level /= np.linalg.norm(level)  # along the slope, at constant depth
    force, _ = points(soil, r + 0.5 * level, r, tangent=level)  # an offset beyond the yield: f = t_f
    np.testing.assert_allclose(np.linalg.norm(force, axis=0), 8.0 * 0.1 * 1500.0 * depths, rtol=1e-12)


def test_reaction_vanishes_continuously_at_the_surface_and_is_zero_above():
    soil = point_soil(su_mudline=5000.0)  # a strength at the mudline: the engagement ramp makes it continuous
    depths = np.array([-0.2, -1e-9, 1e-9, 1e-3, 0.1 - 1e-9, 0.1 + 1e-9, 0.5])
    at = np.column_stack([np.zeros(7), np.zeros(7), -50.0 - depths])
    force, new = points(soil, at + [0.0, 0.5, 0.0], at)
    size = np.linalg.norm(force, axis=0)
    n_f = 2.5 * 7.6 * 0.1 * (5000.0 + 1500.0 * depths)
    # the depth of a point 50 m down is known to ~1e-14 m: 1e-8 N here
    np.testing.assert_allclose(size, np.where(depths > 0, np.clip(depths / 0.1, 0, 1) * n_f, 0.0), rtol=1e-12,
                               atol=1e-8)
    assert size[1] == 0.0 and size[2] < 1e-4 and abs(size[4] - size[5]) < 1e-5 * size[5]
    np.testing.assert_allclose(new["soil"]["anchor"][0, :2], at[:2] + [0.0, 0.5, 0.0])  # above: held nowhere


def test_both_faces_write_the_same_trial_history(rng):
    from cablefem.compiled.evaluator import FusedEvaluator

    from test_loads import soil_state, soil_system

    system = soil_system(Plane.from_slope([-600.0, 0.0, -100.0], np.radians(20.0), np.pi / 2), 2)
    system.loads = [system.load("soil")]
    state, X, V, A = soil_state(system, rng)
    old, new = system.history["full"]
    system.evaluate(state, jacobian=False)
    numpy_face = new.copy()
    new[...] = old
    FusedEvaluator.for_system(system, system.props["mass"]).evaluate(X, V, A, 0.0, 0.0)
    for key in ("anchor", "slip", "work", "reaction"):
        scale = max(np.abs(numpy_face["soil"][key]).max(), 1.0)
        np.testing.assert_allclose(new["soil"][key], numpy_face["soil"][key], rtol=0, atol=1e-12 * scale)


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    """The small scene's static system, its pretension result and the trace of its path."""
    folder = tmp_path_factory.mktemp("small")
    scene = load_scene(small_scene(folder))
    system = build_system(scene, scene.lines[0], dynamic=False)
    trace = []
    return scene, system, solve_pretension(system, trace=trace), trace


def test_a_lying_chain_sinks_until_its_bearing_carries_its_weight(small):
    scene, system, result, trace = small
    w = (60.0 - 1025.0 * np.pi * 0.1**2 / 4) * 9.81
    # su(0) = 0: E_n d_b N_c su_gradient z = w (deeper than the engagement d_b = 0.055 m)
    z_rest = w / (2.5 * 0.055 * 7.6 * 1500.0)
    np.testing.assert_allclose(resting_depth(system), z_rest, rtol=1e-12)
    s, n = system.fem.mesh.p[0], system.fem.n_vertices
    depth = -30.0 - trace[0][0][:n, 2]  # the laid line, settled with its end held
    np.testing.assert_allclose(depth[(s > 15.0) & (s < 60.0)], z_rest, rtol=1e-6)
    # after the path it lies a little deeper: the touchdown, where the catenary's tension presses the
    # line down (T kappa), swept over it (measured 2 %)
    depth = -30.0 - result.X[:n, 2]
    lying = depth[(s > 15.0) & (s < 23.0)]
    assert np.all((lying > z_rest) & (lying < 1.05 * z_rest))


def test_a_dragged_lying_chain_has_the_friction_of_its_depth(tmp_path):
    # the lying chain's friction is E_t d_b s_u(z_rest) = E_t / (E_n N_c) w per unit length: dragged
    # along by 1 m (>> 1/k_t), the whole chain slides and every lying point holds that friction and,
    # at its resting depth still, its weight
    scene = load_scene(small_scene(tmp_path, anchor_z=-30.0))
    system = build_system(scene, scene.lines[0], dynamic=False)
    from cablefem.statics.pretension import start_laid

    X, end = start_laid(system)
    ends = np.array([system.line.anchor, end])
    towards = ends + [-1.0, 0.0, 0.0]  # the line lies from the padeye towards -x: its end leads
    path = LoadPath(system)
    system.tension.compression = True
    path.settle(X, ends, "start")
    path.follow(ends, towards, 20)
    system.tension.compression = False
    path.settle(path.X, towards, "end")
    w = (60.0 - 1025.0 * np.pi * 0.1**2 / 4) * 9.81
    lying = system.fem.full.s > 5.0
    reaction = system.history["full"][0]["soil"]["reaction"][lying]
    # (next to the padeye's drop the line lies up to 0.05 % deeper)
    np.testing.assert_allclose(reaction[:, 0], 8.0 / (2.5 * 7.6) * w, rtol=1e-3)  # 0.42 w against the motion
    np.testing.assert_allclose(reaction[:, 2], w, rtol=1e-3)
    fairlead, anchor = end_forces(system, path.X)
    # the supports hold the soil's pull on the line: the forces the line exerts on them add up to it
    assert fairlead[0] + anchor[0] == pytest.approx(8.0 / (2.5 * 7.6) * w * 70.0, rel=0.01)


def test_the_pretension_path_reports_its_steps_and_halves_a_failing_one(tmp_path, small):
    scene = load_scene(small_scene(tmp_path, steps=1))
    system = build_system(scene, scene.lines[0], dynamic=False)
    result = solve_pretension(system)
    assert result.halvings >= 1 and result.steps >= 2  # one step over the whole path fails
    reference = small[2]
    assert reference.steps == 50 and reference.halvings == 0
    # the path's plasticity is integrated step by step: coarser steps, nearly the same end
    f_coarse, f_fine = end_forces(system, result.X)[0], end_forces(small[1], reference.X)[0]
    assert np.linalg.norm(f_coarse - f_fine) < 1e-2 * np.linalg.norm(f_fine)


def test_the_catenary_start_mobilises_less_friction_than_the_laid_path(tmp_path):
    # a padeye on the mudline (rui2025's Case 3): laid and pulled, the lying chain slides and its
    # friction takes most of the pull off the padeye; started at the frictionless equilibrium, the
    # soil's springs only hold the chain as it settles, and the padeye takes about the pull
    padeye = {}
    for installation in ("laid", "catenary"):
        scene = load_scene(small_scene(tmp_path, anchor_z=-30.0, soil=f'installation = "{installation}"'))
        system = build_system(scene, scene.lines[0], dynamic=False)
        result = solve_pretension(system)
        assert result.installation == installation and (result.steps == 0) == (installation == "catenary")
        padeye[installation] = np.linalg.norm(end_forces(system, result.X)[1])
    assert padeye["catenary"] > 1.2 * padeye["laid"]  # measured 15.1 against 11.6 kN (rui2025 Case 3: 1451 and 140)


def test_plastic_work_is_never_negative_and_the_path_s_energy_balance_closes(small):
    scene, system, result, trace = small
    system.tension.compression = True  # the law of the path (``solve_pretension``)
    try:
        states = [{"X": X, "rows": system.residual(X), "history": history} for X, _, history in trace[:-1]]
        energy = [sum(stored_energy(system, s["X"]).values()) for s in states]
    finally:
        system.tension.compression = False
    steps = [step_work(system, a, b) for a, b in zip(states, states[1:])]
    plastic = np.array([s["plastic"] for s in steps])
    assert plastic.min() >= 0.0 and plastic.sum() > 0.0
    work_in, soil = sum(s["work_in"] for s in steps), sum(s["soil"] for s in steps)
    # quasi-static: what the end puts in is stored or taken by the soil; the trapezoidal rule over
    # 50 steps leaves a few 1e-4 of it (measured -4.4e-4; the soil took 10 %, 95 % of that plastically)
    assert abs(work_in - (energy[-1] - energy[0]) - soil) < 1e-3 * abs(work_in)
    assert plastic.sum() < soil  # the soil also stores some of its work in its springs


def test_a_run_dissipates_plastic_work_at_every_step_and_its_energy_balance_closes(tmp_path):
    from cablefem.dynamics.bdf2 import BDF2
    from cablefem.model.network import boundary_path
    from cablefem.statics.scene import start_states

    extra = '[motion]\nkind = "harmonic"\namplitude = [2.0, 0.0, 1.0]\nperiod = 4.0\nramp = 2.0\n'
    scene = load_scene(small_scene(tmp_path, extra=extra, line_type="Cd_normal = 0.0\nCa_normal = 0.0"))
    line = scene.lines[0]
    system = build_system(scene, line)
    assert [type(load).__name__ for load in system.loads] == ["Tension", "Weight", "Soil"]  # nothing else takes work
    (X0,), _ = start_states(scene, systems=[system])
    integ = BDF2(system, X0, boundary_path(scene, line), dt=0.005)

    def now():
        return {"X": integ.X.copy(), "V": integ.V.copy(), "rows": _rows(integ),
                "history": system.history["full"][0].copy()}

    states = [now()]
    for k in range(1, 801):  # 4 s: the ramp and half a period
        integ.march(np.array([0.005 * k]))
        states.append(now())
    steps = [step_work(system, a, b) for a, b in zip(states, states[1:])]
    plastic = np.array([s["plastic"] for s in steps])
    assert plastic.min() >= 0.0 and plastic.sum() > 0.0
    energy = [sum(stored_energy(system, s["X"], s["V"], integ.M).values()) for s in (states[0], states[-1])]
    work_in, soil = sum(s["work_in"] for s in steps), sum(s["soil"] for s in steps)
    # what is left is what BDF2 dissipates: >= 0, and second order in dt (measured 2.6e-4 of the work in
    # at dt 0.01 s, 5.9e-5 at 0.005 s; the soil took 22 % of it, nearly all plastically)
    remainder = work_in - (energy[1] - energy[0]) - soil
    assert 0.0 <= remainder < 2e-4 * work_in


def _rows(integ):
    """M A + G (N, 3) of an integrator at its state (the end rows: the supports' forces on the line)."""
    residual, _ = integ.system.evaluate(integ.system.state(integ.X, integ.V, integ.A, integ.t), jacobian=False)
    return residual + integ.inertia(integ.A)


def test_static_json_and_run_frames_carry_the_soil(tmp_path):
    from cablefem.cli import main

    path = small_scene(tmp_path, extra='[solver]\nduration = 0.2\ndt = 0.05\n[output]\nevery = 0.1\n')
    assert main(["static", str(path), "--json", str(tmp_path / "static.json")]) == 0
    line = json.loads((tmp_path / "static.json").read_text())["lines"][0]
    assert len(line["tension"]) == len(line["nodes"])
    assert line["padeye_tension"] == pytest.approx(line["anchor_tension"], rel=1e-12)
    assert line["padeye_force"] == line["anchor_force"]
    assert 20.0 < line["embedded_length"] < 70.0 and 0.0 < line["mudline_angle_deg"] < 30.0
    assert line["padeye_tension"] < line["mudline_tension"] < line["fairlead_tension"]
    assert line["tension"][0] == line["anchor_tension"] and line["tension"][-1] == line["fairlead_tension"]
    assert line["pretension"]["steps"] == 50
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 0
    import meshio

    frame = meshio.read(tmp_path / "out" / "small-soil_00001.vtu")
    assert {"soil_reaction", "soil_slip"} <= set(frame.point_data)
    assert np.abs(frame.point_data["soil_reaction"]).max() > 0.0


@pytest.mark.parametrize("soil, line_type, anchor_z, extra, message", [
    ("su_mudline = -5.0", "", -33.0, "", "soil.su_mudline: must be >= 0"),
    ("su_gradient = -1500.0", "", -33.0, "", "soil.su_gradient: must be >= 0"),
    ("", "", -33.0, "", None),
    ('installation = "dropped"', "", -33.0, "", "soil.installation: unknown value 'dropped'; valid: laid | catenary"),
    ("stiffness_normal = 0.0", "", -33.0, "", "soil.stiffness_normal: must be > 0"),
    ("", "", -25.0, "", "lines[0].anchor: the anchor (padeye) lies 5 m above the seabed"),
])
def test_bad_soil_input_is_one_line_naming_the_key(tmp_path, soil, line_type, anchor_z, extra, message):
    from cablefem.errors import InputError

    gradient = soil.startswith("su_gradient")  # replaces the scene's own
    path = small_scene(tmp_path, anchor_z=anchor_z, soil="" if gradient else soil, line_type=line_type, extra=extra)
    if gradient:
        path.write_text(path.read_text().replace("su_gradient = 1500.0", soil))
    if message is None:  # su_gradient = 0 with su_mudline = 0: no strength
        path.write_text(path.read_text().replace("su_gradient = 1500.0", "su_gradient = 0.0"))
        message = "soil.su_gradient: su_mudline and su_gradient are both 0"
    with pytest.raises(InputError) as error:
        load_scene(path)
    assert message in error.value.message() and "\n" not in error.value.message()


def test_soil_keys_need_their_tables_line_types_their_bar_diameter_and_lines_fixed_ends(tmp_path):
    from cablefem.errors import InputError

    path = small_scene(tmp_path)
    text = path.read_text()
    for changed, message in ((text.replace("su_gradient = 1500.0\n", ""), "soil.su_gradient: missing required key"),
                             (text.replace("nominal_diameter = 0.055\n", ""),
                              "line_types.chain.nominal_diameter: missing: [soil] needs the chain's bar diameter"),
                             (text.replace("[soil]", "[soil_]").replace("su_gradient", "x").replace(
                                 "installation_steps = 50", ""), "unknown key"),
                             (text.replace('fairlead = [0.0, 0.0, -5.0]', 'fairlead = "buoy"')
                              + '[points.buoy]\nkind = "free"\nposition = [0.0, 0.0, -5.0]\nvolume = 2.0\n',
                              "lines[0]: line 'line1' has a free end or points on it"),
                             (textwrap.dedent(text[:text.index("[soil]")]),
                              "lines[0].anchor: the anchor lies 3 m below the seabed (more than the line's diameter, "
                              "0.1 m): a padeye below the seabed needs a [soil] table")):
        path.write_text(changed)
        with pytest.raises(InputError) as error:
            load_scene(path)
        assert message in error.value.message(), error.value.message()


def test_a_bad_soil_scene_exits_2_with_one_line(tmp_path, capsys):
    from cablefem.cli import main

    path = small_scene(tmp_path, soil="bearing_factor = -7.6")
    assert main(["static", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "soil.bearing_factor: must be > 0" in err and str(path) in err


def test_compiled_steps_commit_the_history_of_the_converged_point_as_the_python_steps(tmp_path):
    # a step that converges on its increment evaluates its end elements only for the reactions; a
    # line keeping history evaluates them all, so that every point commits the converged state's
    # (before: 645 iterations against 643, the plastic slip 4e-11 of its largest apart)
    from cablefem.dynamics.bdf2 import BDF2
    from cablefem.model.network import boundary_path
    from cablefem.statics.scene import start_states

    extra = '[motion]\nkind = "harmonic"\namplitude = [2.0, 0.0, 1.0]\nperiod = 4.0\nramp = 2.0\n'
    runs = []
    for python in (False, True):
        scene = load_scene(small_scene(tmp_path, extra=extra, line_type="Cd_normal = 0.0\nCa_normal = 0.0",
                                       name=f"small{python}.toml"))
        system = build_system(scene, scene.lines[0])
        (X0,), _ = start_states(scene, systems=[system])
        integ = BDF2(system, X0, boundary_path(scene, scene.lines[0]), dt=0.005)
        if python:
            integ.stepper().packer = None  # the compiled kernel per evaluation, Newton in Python
        integ.march(0.005 * np.arange(1, 401))
        runs.append((system.history["full"][0]["soil"].copy(), integ.X, integ.statistics()["newton_iterations"]))
    (compiled, X_compiled, its_compiled), (python, X_python, its_python) = runs
    assert its_compiled == its_python
    np.testing.assert_allclose(X_compiled, X_python, rtol=0, atol=1e-13 * np.abs(X_python).max())
    for field in python.dtype.names:
        np.testing.assert_allclose(compiled[field], python[field], rtol=0, atol=1e-13 * np.abs(python[field]).max())
