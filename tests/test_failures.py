"""Line failures (docs/scene.md, "Failures"; ``cablefem.runs.failures``): a held end lets go at a time
or at the first step whose tension there exceeds a threshold, and the line goes on with that end free.

What is held: the released line hangs where statics' free-end solve puts it once its swing has
damped; the energy is the same just before and just after the release and is kept afterwards to
the scheme's order where nothing dissipates; a tension threshold releases at the first row of the
intact run above it, and the rows before it are the intact run's; the compiled and the numpy faces
release at the same step; a line of a network lets go of its body's point and the rest of the
network does not notice; bad failures are one line naming the file and the key (exit 2)."""

import csv
import json
import os
from dataclasses import replace

import numpy as np
import pytest

from bad_input import BASE_TOML
from cablefem.cli import main
from cablefem.dynamics.energy import stored_energy
from cablefem.dynamics.registry import INTEGRATORS, integrator_options
from cablefem.io import load_scene
from cablefem.model.network import anchor_path, boundary_path
from cablefem.runs.failures import release
from cablefem.runs.run import run_scene
from cablefem.statics.scene import run_start, static_lines

#: a 31 m chain hanging 30 m from a fixed fairlead to an anchor 4 m aside, far above the seabed
HANG = """\
name = "hang"
[environment]
water_density = 1025.0
gravity = 9.81
[line_types.chain]
diameter = 0.1
mass = 20.0
EA = 1.0e7
damping = {damping}
Cd_normal = {cd}
Cd_tangential = {cd_t}
Ca_normal = {ca}
[[lines]]
name = "line1"
anchor = [-4.0, 0.0, -30.0]
fairlead = [0.0, 0.0, 0.0]
segments = [{{ type = "chain", length = 31.0, elements = 10 }}]
[seabed]
kind = "horizontal"
depth = 100.0
[solver]
integrator = "{integrator}"
dt = {dt}
duration = {duration}
{solver}
[output]
every = 1.0
{failures}
"""


def hang_scene(tmp_path, failures="", damping=0.05, cd=8.0, cd_t=0.5, ca=1.0, integrator="bdf2", dt=0.05,
               duration=60.0, solver="", name="hang.toml"):
    path = tmp_path / name
    path.write_text(HANG.format(damping=damping, cd=cd, cd_t=cd_t, ca=ca, integrator=integrator, dt=dt,
                                duration=duration, solver=solver, failures=failures))
    return load_scene(str(path))


def rows(folder):
    """tensions.csv of a run as a dict column -> array."""
    with open(os.path.join(folder, "tensions.csv"), newline="") as handle:
        table = list(csv.reader(handle))
    return {name: np.array([float(r[i]) for r in table[1:]]) for i, name in enumerate(table[0])}


def final_nodes(scene, folder):
    """The positions (N, 3) of the last frame of a run's line (meshio reads the .vtu)."""
    import meshio

    frames = sorted(f for f in os.listdir(folder) if f.startswith(scene.name + "_") and f.endswith(".vtu"))
    return meshio.read(os.path.join(folder, frames[-1])).points


def test_a_released_anchor_hangs_where_statics_free_end_solve_puts_it(tmp_path):
    """The anchor lets go at 0.5 s; after 60 s of drag (Cd 8) the chain hangs from its fairlead within
    1 cm of statics' free-end equilibrium (hang.py's start, Newton) of the same line, where at the
    release its anchor end was 4 m aside: the swing of 4 m has damped below 0.25 % of it. Its anchor
    tension is 0 from the release on (tensions.csv), and summary.json says when and at what tension
    it let go."""
    scene = hang_scene(tmp_path, '[[failures]]\nline = "line1"\nend = "anchor"\ntime = 0.5\n')
    out = tmp_path / "run"
    summary = run_scene(scene, str(out), progress=False)
    (failure,) = summary["failures"]
    table = rows(out)
    at = int(np.flatnonzero(np.isclose(table["t"], 0.5))[0])
    assert failure["released_at"] == pytest.approx(0.5, abs=1e-12)
    assert failure["condition"] == "time"
    assert failure["tension_at_release"] == pytest.approx(table["anchor_tension"][at], rel=1e-9)
    assert failure["tension_at_release"] > 0.0
    assert np.all(table["anchor_tension"][at + 1:] == 0.0)
    free = replace(scene, lines=[replace(scene.lines[0], prescribed=(False, True))])
    _, (result,), _, _ = static_lines(free)
    hanging = final_nodes(scene, out)
    assert np.max(np.linalg.norm(hanging - result.X, axis=1)) < 0.01
    assert np.linalg.norm(hanging[0] - scene.lines[0].anchor) > 3.0  # it did leave its anchor


def _march_with_release(scene, t_release, t_end):
    """One line of ``scene`` marched to ``t_release``, released at its anchor, marched to ``t_end``:
    the stored energy (kinetic + strain + gravity) [J] and the kinetic energy at each accepted step
    (each (steps, 2)), and the index of the state just after the release in that list (the states
    just before and just after it as two entries)."""
    integrator = INTEGRATORS[scene.solver.integrator]
    systems, states, _ = run_start(scene)
    line, dt = scene.lines[0], scene.solver.dt
    integ = integrator(systems[0], states[0], boundary_path(scene, line), dt=dt, anchor=anchor_path(scene, line),
                       **integrator_options(scene.solver))

    def energy(i):
        parts = stored_energy(i.system, i.X, i.V, mass=i.M)
        return sum(parts.values()), parts["kinetic"]

    energies = [energy(integ)]
    times = dt * np.arange(1, int(round(t_end / dt)) + 1)
    for t in times[times <= t_release + 1e-9]:
        integ.march([t])
        energies.append(energy(integ))
    at = len(energies)
    integ = release(scene, integ, 0)
    energies.append(energy(integ))
    for t in times[times > t_release + 1e-9]:
        integ.march([t])
        energies.append(energy(integ))
    return np.array(energies), at


def test_the_energy_does_not_jump_at_a_release_and_is_kept_after_it_to_second_order(tmp_path):
    """Generalised-alpha at rho_inf = 1 (the trapezoidal rule: no numerical damping), no drag, no
    added mass, no internal damping, a fixed fairlead: the anchor lets go at 0.5 s and the chain
    falls and swings for 1.5 s. The stored energy just after the release equals the one just before
    to round-off (1e-12 relative: the same positions and velocities), and after it the energy's drift
    (largest |E - E_release|, against the largest kinetic energy the fall gives) falls at least as
    fast as dt^2 (the scheme's order; observed order above 1.8 over each halving of dt) and is under
    1e-4 of that energy at dt = 0.005 s."""
    drifts = []
    for dt in (0.01, 0.005, 0.0025):
        scene = hang_scene(tmp_path, damping=0.0, cd=0.0, cd_t=0.0, ca=0.0, integrator="generalized-alpha", dt=dt,
                           duration=2.0, solver="rho_inf = 1.0\nnewton = \"full\"\ntolerance = 1e-12",
                           name=f"energy{dt}.toml")
        energies, at = _march_with_release(scene, 0.5, 2.0)
        assert abs(energies[at, 0] - energies[at - 1, 0]) <= 1e-12 * abs(energies[at - 1, 0])
        after = energies[at:]
        drifts.append(np.max(np.abs(after[:, 0] - after[0, 0])) / np.max(after[:, 1]))
    print("energy drift after the release / largest kinetic energy, dt 0.01, 0.005, 0.0025 s:", drifts)
    orders = np.log2(np.array(drifts[:-1]) / np.array(drifts[1:]))
    assert np.all(orders > 1.8), (drifts, orders)
    assert drifts[1] < 1e-4, drifts


HEAVE = '[motion]\nkind = "harmonic"\namplitude = [0.0, 0.0, 1.5]\nperiod = 3.0\n'


def _heaving(tmp_path, failures="", solver="", name="heave.toml", duration=4.0):
    """The hanging chain with its fairlead heaving 1.5 m at 3 s, its anchor tension swinging."""
    return hang_scene(tmp_path, HEAVE + failures, duration=duration, solver=solver, name=name)


def test_a_tension_threshold_lets_go_at_the_first_step_over_it(tmp_path):
    """The threshold halfway between the intact run's smallest and largest anchor tension after t = 0:
    the run with the failure lets go at the first row (step) of the intact run above it, with that
    row's tension (the interval holding it, 20 steps, marched again one step at a time from its start);
    its rows up to there are the intact run's (1e-9: the steps taken one by one against in one call),
    and its anchor tension is 0 after."""
    intact = tmp_path / "intact"
    run_scene(_heaving(tmp_path), str(intact), progress=False)
    before = rows(intact)
    T = before["anchor_tension"]
    threshold = 0.5 * (T[1:].min() + T[1:].max())
    k = int(np.flatnonzero(T > threshold)[0])
    assert 0 < k < len(T) - 1
    failing = tmp_path / "failing"
    scene = _heaving(tmp_path, f'[[failures]]\nline = "line1"\nend = "anchor"\ntension = {float(threshold)!r}\n',
                     name="failing.toml")
    (failure,) = run_scene(scene, str(failing), progress=False)["failures"]
    after = rows(failing)
    assert failure["condition"] == "tension"
    assert failure["released_at"] == pytest.approx(before["t"][k], abs=1e-12)
    assert failure["tension_at_release"] == pytest.approx(T[k], rel=1e-9)
    for column in before:
        np.testing.assert_allclose(after[column][:k + 1], before[column][:k + 1], rtol=1e-9, atol=1e-9)
    assert np.all(after["anchor_tension"][k + 1:] == 0.0)
    assert np.max(np.abs(after["fairlead_tension"][k + 2:] - before["fairlead_tension"][k + 2:])) > 10.0


def test_the_compiled_and_the_numpy_faces_let_go_at_the_same_step(tmp_path):
    """The same tension failure run on the compiled kernel and on scikit-fem's forms (the numpy face,
    ``assembly = "forms"``): both let go after the same step, at tensions equal to 1e-6 (the two faces
    agree to round-off and the Newton tolerance, tests/test_fused.py), and the fairlead tensions after
    it agree to 1e-5 of their size."""
    failure = '[[failures]]\nline = "line1"\nend = "anchor"\ntension = 420.0\n'
    found = {}
    for assembly in ("kernel", "forms"):
        scene = _heaving(tmp_path, failure, solver=f'assembly = "{assembly}"', name=f"{assembly}.toml", duration=2.0)
        (found[assembly],) = run_scene(scene, str(tmp_path / assembly), progress=False)["failures"]
        found[assembly]["rows"] = rows(tmp_path / assembly)
    kernel, forms = found["kernel"], found["forms"]
    assert kernel["released_at"] is not None
    assert kernel["released_at"] == forms["released_at"]
    assert kernel["tension_at_release"] == pytest.approx(forms["tension_at_release"], rel=1e-6)
    T_kernel, T_forms = kernel["rows"]["fairlead_tension"], forms["rows"]["fairlead_tension"]
    assert np.max(np.abs(T_kernel - T_forms)) <= 1e-5 * np.max(T_kernel)


#: two chains of HANG's line type from anchors to a coupled buoy's points
NETWORK = HANG.split("[[lines]]")[0].format(damping=0.05, cd=2.0, cd_t=0.5, ca=1.0).replace('"hang"', '"pair"') + """\
[bodies.buoy]
kind = "coupled"
position = [0.0, 0.0, 0.0]
[bodies.buoy.motion]
kind = "harmonic"
amplitude = [1.0, 0.0, 0.5, 0.0, 0.0, 0.0]
period = 4.0
[points.a1]
kind = "fixed"
position = [-20.0, 0.0, -30.0]
[points.a2]
kind = "fixed"
position = [20.0, 0.0, -30.0]
[points.p1]
body = "buoy"
position = [-2.0, 0.0, -1.0]
[points.p2]
body = "buoy"
position = [2.0, 0.0, -1.0]
[[lines]]
name = "west"
anchor = "a1"
fairlead = "p1"
segments = [{ type = "chain", length = 38.0, elements = 10 }]
[[lines]]
name = "east"
anchor = "a2"
fairlead = "p2"
segments = [{ type = "chain", length = 38.0, elements = 10 }]
[seabed]
kind = "horizontal"
depth = 100.0
[solver]
dt = 0.05
duration = 3.0
[output]
every = 0.5
"""


def test_a_network_line_lets_go_of_its_body_and_the_rest_of_the_network_does_not_notice(tmp_path):
    """Two chains from anchors to a coupled buoy's points; the west one lets go of the buoy at 1 s. Its
    fairlead force is 0 after, and so is the force on the point it left (``point:p1``); the buoy's
    force is the east chain's alone; the east chain's rows are the intact run's exactly (its own
    group, untouched); the west chain's end falls away from the point the buoy carries on moving."""
    intact_path, failing_path = tmp_path / "intact.toml", tmp_path / "failing.toml"
    intact_path.write_text(NETWORK)
    failing_path.write_text(NETWORK + '[[failures]]\nline = "west"\nend = "fairlead"\ntime = 1.0\n')
    run_scene(load_scene(str(intact_path)), str(tmp_path / "intact"), progress=False)
    scene = load_scene(str(failing_path))
    (failure,) = run_scene(scene, str(tmp_path / "failing"), progress=False)["failures"]
    before, after = rows(tmp_path / "intact"), rows(tmp_path / "failing")
    assert failure["released_at"] == pytest.approx(1.0, abs=1e-12)
    k = int(np.flatnonzero(np.isclose(after["t"], 1.0))[0])
    for column in [c for c in before if c.startswith("east:")]:
        np.testing.assert_array_equal(after[column], before[column])
    assert np.all(after["west:fairlead_tension"][k + 1:] == 0.0)
    for c in ("fx", "fy", "fz"):
        assert np.all(after[f"point:p1:{c}"][k + 1:] == 0.0)
        np.testing.assert_array_equal(after[f"body:buoy:{c}"][k + 1:], after[f"point:p2:{c}"][k + 1:])
    import meshio

    last = sorted(f for f in os.listdir(tmp_path / "failing") if f.startswith("pair_") and f.endswith(".vtu"))[-1]
    mesh = meshio.read(str(tmp_path / "failing" / last))
    west_end = mesh.points[10]  # the west chain's 11 nodes come first, its fairlead last
    carried = np.array([-2.0, 0.0, -1.0]) + np.array([np.sin(2 * np.pi * 3.0 / 4.0), 0.0,
                                                      0.5 * np.sin(2 * np.pi * 3.0 / 4.0)])
    assert np.linalg.norm(west_end - carried) > 2.0


# ---------------------------------------------------------------------------------------- bad input
BAD = [
    ('line = "line9"\nend = "anchor"\ntime = 1.0', "failures[0].line", "no line 'line9'"),
    ('line = "line1"\nend = "middle"\ntime = 1.0', "failures[0].end", "unknown value 'middle'"),
    ('line = "line1"\nend = "anchor"\ntime = 1.0\ntension = 5.0e5', "failures[0]", "not both"),
    ('line = "line1"\nend = "anchor"', "failures[0]", "not neither"),
    ('line = "line1"\nend = "anchor"\ntension = -1.0', "failures[0].tension", "must be > 0"),
]


@pytest.mark.parametrize("entry, key, reason", BAD, ids=["no-line", "bad-end", "both", "neither", "negative"])
def test_a_bad_failure_is_one_line_naming_the_file_and_the_key(entry, key, reason, tmp_path, capsys):
    """``cablefem run`` on a scene with a bad [[failures]] entry: exit 2, one line on stderr naming the
    file, the key and the reason, and no output folder written."""
    path = tmp_path / "bad.toml"
    path.write_text(BASE_TOML + "[[failures]]\n" + entry + "\n")
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert str(path) in err and key in err and reason in err, err
    assert not (tmp_path / "out").exists()


FAILURE_SECTION = """---------------------- FAILURE ----------------------
FailureID  Point    Line(s)   FailTime   FailTen
()           ()       (,)      (s or 0)   (N or 0)
{rows}
"""


def _moordyn_with(tmp_path, rows):
    text = open(os.path.join(os.path.dirname(__file__), "..", "examples", "flume_flat.dat"), encoding="utf-8").read()
    text = text.replace("---------------------- OPTIONS", FAILURE_SECTION.format(rows=rows) + "---------------------- OPTIONS")
    path = tmp_path / "failure.dat"
    path.write_text(text)
    return path


def test_moordyn_failure_rows_are_read_as_failures(tmp_path):
    """MoorDyn-F's FAILURE: a time, a tension, or both (whichever first), at the line's point by its ID:
    point 1 is line 1's AttachA (its anchor), point 2 its AttachB (its fairlead)."""
    scene = load_scene(str(_moordyn_with(tmp_path, "1  1  1  12.5  0\n2  2  1  0  2.0e6")))
    anchor, fairlead = scene.failures
    assert (anchor.line, anchor.end, anchor.time, anchor.tension) == ("line1", "anchor", 12.5, None)
    assert (fairlead.line, fairlead.end, fairlead.time, fairlead.tension) == ("line1", "fairlead", None, 2.0e6)
    assert (anchor.string, anchor.string_end, fairlead.string_end) == (0, 0, 1)


@pytest.mark.parametrize("row, reason", [
    ("1  1  1,2  10  0", "fail together"),
    ("1  R1a  1  10  0", "RODS"),
    ("1  1  1  0  0", "both 0"),
    ("1  3  1  10  0", "no point 3"),
    ("1  1  4  10  0", "no line 4"),
], ids=["several-lines", "rod-end", "neither", "no-point", "no-line"])
def test_what_cablefem_cannot_honour_in_a_moordyn_failure_is_one_line(row, reason, tmp_path, capsys):
    """A FAILURE row cablefem cannot honour, or that names what is not there: exit 2, one line naming
    the file and the row."""
    path = _moordyn_with(tmp_path, row)
    assert main(["static", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert str(path) in err and "FAILURE.1" in err and reason in err, err


#: a small crowfoot: two legs from anchors and an upper line to a coupled buoy meet at a clump (a junction)
CROWFOOT = HANG.split("[[lines]]")[0].format(damping=0.05, cd=2.0, cd_t=0.5, ca=1.0).replace('"hang"', '"crow"') + """\
[bodies.buoy]
kind = "coupled"
position = [0.0, 0.0, 0.0]
[bodies.buoy.motion]
kind = "harmonic"
amplitude = [1.0, 0.0, 0.3, 0.0, 0.0, 0.0]
period = 4.0
[points.f]
body = "buoy"
position = [-1.0, 0.0, -1.0]
[points.j]
kind = "free"
position = [-16.0, 0.0, -8.0]
mass = 200.0
volume = 0.02
[points.a1]
kind = "fixed"
position = [-40.0, 15.0, -20.0]
[points.a2]
kind = "fixed"
position = [-40.0, -15.0, -20.0]
[[lines]]
name = "upper"
anchor = "j"
fairlead = "f"
segments = [{ type = "chain", length = 18.5, elements = 8 }]
[[lines]]
name = "leg1"
anchor = "a1"
fairlead = "j"
segments = [{ type = "chain", length = 33.0, elements = 8 }]
[[lines]]
name = "leg2"
anchor = "a2"
fairlead = "j"
segments = [{ type = "chain", length = 33.0, elements = 8 }]
[seabed]
kind = "horizontal"
depth = 60.0
[solver]
dt = 0.05
duration = 2.0
[output]
every = 0.5
"""


def test_a_leg_of_a_junction_lets_go_of_its_anchor_and_the_junction_steps_on(tmp_path):
    """A leg of a crowfoot lets go of its anchor at 0.5 s: the junction's group is made again with the
    leg's new integrator, the other strings' accelerations kept. The rows up to the release are the
    intact run's exactly; after it the leg's anchor tension is 0 and the group steps on to 2 s, the
    released anchor end falling more than 0.5 m from where it was held."""
    intact_path, failing_path = tmp_path / "intact.toml", tmp_path / "failing.toml"
    intact_path.write_text(CROWFOOT)
    failing_path.write_text(CROWFOOT + '[[failures]]\nline = "leg1"\nend = "anchor"\ntime = 0.5\n')
    run_scene(load_scene(str(intact_path)), str(tmp_path / "intact"), progress=False)
    scene = load_scene(str(failing_path))
    summary = run_scene(scene, str(tmp_path / "failing"), progress=False)
    assert summary["completed"] and summary["failures"][0]["released_at"] == pytest.approx(0.5, abs=1e-12)
    before, after = rows(tmp_path / "intact"), rows(tmp_path / "failing")
    k = int(np.flatnonzero(np.isclose(after["t"], 0.5))[0])
    for column in before:
        np.testing.assert_array_equal(after[column][:k + 1], before[column][:k + 1])
    assert np.all(after["leg1:anchor_tension"][k + 1:] == 0.0)
    assert np.max(np.abs(after["leg2:anchor_tension"][k + 1:] - before["leg2:anchor_tension"][k + 1:])) > 1.0
    import meshio

    last = sorted(f for f in os.listdir(tmp_path / "failing") if f.startswith("crow_") and f.endswith(".vtu"))[-1]
    nodes = meshio.read(str(tmp_path / "failing" / last)).points
    names = [line.name for line in scene.lines]
    start = 9 * names.index("leg1")  # each string's 9 nodes in scene order, its anchor first
    assert np.linalg.norm(nodes[start] - np.array([-40.0, 15.0, -20.0])) > 0.5


def test_a_failure_names_a_line_end_as_the_scene_wrote_it(tmp_path):
    """A line written from the buoy's point to its anchor is turned round in its string (its most
    fixed end first): its 'anchor' as written is the string's fairlead end, and its 'fairlead' the
    string's anchor end; a line of a scene without a network keeps its ends."""
    turned = NETWORK.replace('anchor = "a1"\nfairlead = "p1"', 'anchor = "p1"\nfairlead = "a1"')
    for end, expected in (("anchor", 1), ("fairlead", 0)):
        path = tmp_path / f"turned_{end}.toml"
        path.write_text(turned + f'[[failures]]\nline = "west"\nend = "{end}"\ntime = 1.0\n')
        scene = load_scene(str(path))
        (failure,) = scene.failures
        assert scene.lines[failure.string].name == "west" and failure.string_end == expected
        assert scene.lines[failure.string].ends[failure.string_end] == ("p1" if end == "anchor" else "a1")
    (failure,) = hang_scene(tmp_path, '[[failures]]\nline = "line1"\nend = "fairlead"\ntime = 1.0\n').failures
    assert (failure.string, failure.string_end) == (0, 1)


def test_cablefem_run_says_when_an_end_let_go(tmp_path, capsys):
    """``cablefem run`` prints a line per failure with the time and tension summary.json has, and says
    so of an end that did not let go before the run ended."""
    path = tmp_path / "hang.toml"
    path.write_text(HANG.format(damping=0.05, cd=8.0, cd_t=0.5, ca=1.0, integrator="bdf2", dt=0.05, duration=1.0,
                                solver="", failures='[[failures]]\nline = "line1"\nend = "anchor"\ntime = 0.5\n'
                                '[[failures]]\nline = "line1"\nend = "fairlead"\ntime = 5.0\n'))
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 0
    printed = capsys.readouterr().out
    anchor, fairlead = json.loads((tmp_path / "out" / "summary.json").read_text())["failures"]
    assert f"line1: anchor let go at 0.5 s, its tension {anchor['tension_at_release']:.4e} N" in printed
    assert fairlead["released_at"] is None and "line1: fairlead did not let go" in printed


@pytest.mark.parametrize("integrator", ["bdf2", "generalized-alpha"])
def test_adaptive_steps_land_on_a_failure_time(integrator, tmp_path):
    """With adaptive steps (error control; dt the largest step) the steps land on a failure's time as
    on an output time: the anchor lets go at 0.37 s, between two frames, to round-off (the adaptive
    steps sum to it), the run's rows carry that time and the anchor's tension is 0 after it."""
    scene = hang_scene(tmp_path, '[[failures]]\nline = "line1"\nend = "anchor"\ntime = 0.37\n',
                       integrator=integrator, duration=1.0, solver="adaptive = true")
    (failure,) = run_scene(scene, str(tmp_path / "out"), progress=False)["failures"]
    assert failure["released_at"] == pytest.approx(0.37, abs=1e-12)
    table = rows(tmp_path / "out")
    at = int(np.argmin(np.abs(table["t"] - 0.37)))
    assert abs(table["t"][at] - 0.37) < 1e-9 and table["anchor_tension"][at] > 0.0
    assert np.all(table["anchor_tension"][at + 1:] == 0.0)


def test_a_march_that_fails_while_a_tension_is_watched_goes_on_step_by_step(tmp_path, monkeypatch):
    """Where the march of an output interval in one call fails (here: made to, for every call of more
    than one step while the anchor is held), the interval is taken again one step at a time from its
    snapshot, where the end may let go before the step that failed: a threshold never reached then
    runs to the end with the intact run's rows (1e-9), and one that is reached lets go at the same
    step as without the fault, with the same rows."""
    from cablefem.dynamics.group import Group
    from cablefem.errors import ConvergenceError

    never = '[[failures]]\nline = "line1"\nend = "anchor"\ntension = 1.0e9\n'
    reached = '[[failures]]\nline = "line1"\nend = "anchor"\ntension = 420.0\n'
    plain = {}
    for name, failure in (("intact", ""), ("reached", reached)):
        out = tmp_path / name
        plain[name] = run_scene(_heaving(tmp_path, failure, name=f"{name}.toml", duration=2.0), str(out),
                                progress=False)
        plain[name]["rows"] = rows(out)
    original = Group.march

    def failing_in_one_call(self, times):
        if len(times) > 1 and self.members[0].fem.prescribed[0]:
            error = ConvergenceError("a march of several steps fails (made to)")
            error.forces = np.zeros((0, len(self.members), 2, 3))
            raise error
        return original(self, times)

    monkeypatch.setattr(Group, "march", failing_in_one_call)
    for name, failure in (("intact", never), ("reached", reached)):
        out = tmp_path / f"{name}-faulty"
        summary = run_scene(_heaving(tmp_path, failure, name=f"{name}-faulty.toml", duration=2.0), str(out),
                            progress=False)
        assert summary["completed"]
        for column, values in plain[name]["rows"].items():
            np.testing.assert_allclose(rows(out)[column], values, rtol=1e-9, atol=1e-9)
    assert summary["failures"][0]["released_at"] == plain["reached"]["failures"][0]["released_at"]
