"""Statics of MoorDyn's inputs with a mass on a line's free end (tests/data/moordyn: lifting.txt,
pendulum.txt, seafloor.txt): the line starts from where it hangs (``cablefem.statics.hang``) and
Newton converges to the closed form, to MoorPy's ``System`` where MoorPy solves them, and on a
sloping seabed to the balance of the line's support, its weight and the seabed's normal force;
``cablefem static`` reports how each line was solved. Their time is in benchmarks/moordyn_statics.py."""

import json
import os

import numpy as np
import pytest

from cablefem.cli import main
from cablefem.io import load_scene

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "moordyn")


def static_json(path, tmp_path, capsys):
    """``cablefem static FILE --json``: its JSON and what it printed (exit status 0 asserted)."""
    out = tmp_path / "static.json"
    assert main(["static", str(path), "--json", str(out)]) == 0, capsys.readouterr()
    return json.loads(out.read_text()), capsys.readouterr().out


def hang(scene):
    """The closed form of a line hanging from its fixed end with a point on its free end: the nodes
    (n, 3) and the top tension [N]. T(s) = W + w (L - s), z(s) = z_top - s - (W s + w (L s - s^2 / 2)) / EA."""
    (line,) = scene.lines
    env = scene.environment
    (segment,) = line.segments
    L, EA = line.unstretched_length, segment.type.EA
    w = segment.type.submerged_weight(env.water_density, env.gravity)
    joint = line.joints[-1][1]
    W = joint.mass * env.gravity - env.water_density * env.gravity * joint.volume
    s = line.node_arc_lengths()
    nodes = np.tile(line.anchor, (s.size, 1))
    nodes[:, 2] -= s + (W * s + w * (L * s - 0.5 * s * s)) / EA
    return nodes, W + w * L, W * L / EA


def with_gravity(name, tmp_path, g):
    """A copy of the MoorDyn file ``name`` with the OPTIONS row ``g`` (MoorPy's gravity, read alike)."""
    text = open(os.path.join(DATA, name), encoding="utf-8").read()
    row = next(r for r in text.splitlines() if "WtrDnsty" in r)
    path = tmp_path / name
    path.write_text(text.replace(row, f"{g}     g     gravity\n{row}"))
    return path


@pytest.mark.parametrize("name", ["lifting.txt", "pendulum.txt"])
def test_a_mass_on_a_free_end_hangs_where_the_closed_form_and_moorpy_put_it(name, tmp_path, capsys):
    """lifting.txt (1e3 kg given 0.5 m above where it hangs) and pendulum.txt (1e5 kg given 10 m to
    the side): the line, as dense as the water, hangs straight down, each node at the closed form
    to the Newton tolerance's share of the stretch (1e-8 W L / EA) and the top tension the weight
    below (1e-9); Newton starts there (at most 2 iterations, where continuation from the points
    without their weight crawled through 643-1171). MoorPy's System (at its g = 9.81, the file
    given the same) puts the mass at the same depth (1e-6 m) with the same top tension (1e-8)
    and within 1 cm of straight below (its catenary of a vertical line leaves the horizontal
    force of a sub-centimetre offset unresolved)."""
    moorpy = pytest.importorskip("moorpy")
    path = with_gravity(name, tmp_path, 9.81)
    solved, printed = static_json(path, tmp_path, capsys)
    nodes, top, stretch = hang(load_scene(str(path)))
    (entry,) = solved["lines"]
    np.testing.assert_allclose(entry["nodes"], nodes, rtol=0, atol=1e-8 * stretch + 1e-12)
    np.testing.assert_allclose(entry["anchor_tension"], top, rtol=1e-9)
    assert solved["strategies"] == ["newton"] and solved["line_iterations"][0] <= 2
    assert solved["newton_iterations"] == solved["line_iterations"][0]
    (row,) = [r for r in printed.splitlines() if r.startswith(entry["name"])]
    assert row.split()[-1] == "newton"  # the line's row names its strategy

    system = moorpy.System(file=str(path), g=9.81)
    system.initialize()
    assert system.solveEquilibrium(tol=1e-9, maxIter=5000)
    mass, line = system.pointList[1], system.lineList[0]
    assert np.linalg.norm(mass.getForces()) < 1e-6
    np.testing.assert_allclose(mass.r[2], entry["nodes"][-1][2], rtol=0, atol=1e-6)
    np.testing.assert_allclose(line.TA, entry["anchor_tension"], rtol=1e-8)
    np.testing.assert_allclose(mass.r[:2], entry["nodes"][-1][:2], rtol=0, atol=1e-2)


def test_a_mass_resting_on_a_slope_balances_support_weight_and_seabed(tmp_path, capsys):
    """seafloor.txt: 10 kg on the free end of a 32 m line as dense as the water, hung from 30 m
    above a frictionless 11.3 deg slope (a planar SeafloorFile grid): the end slides downhill until
    the line's pull along the slope holds the mass's weight there. Whatever the mesh, the support
    force less the weight is the seabed's push, normal to the plane (its tangential part 1e-6 of
    the weight: the solve's residual) and upwards; the end lies downhill of the support, in the
    seabed, and every node but the last (the seabed acts at the last element's Gauss points, the
    mass at its end) on the chord from the support, within the bow of the line's slight buoyancy
    (|w| L^2 / 8 T). Newton from the taut start, then continuation
    on the axial stiffness (at most 200 iterations, where the strategies from the file's start
    took 680); MoorPy's System leaves the mass 2 m inside this seabed, so it is no second opinion here."""
    solved, _ = static_json(os.path.join(DATA, "seafloor.txt"), tmp_path, capsys)
    scene = load_scene(os.path.join(DATA, "seafloor.txt"))
    (line,), env, plane = scene.lines, scene.environment, scene.seabed
    (entry,) = solved["lines"]
    nodes = np.array(entry["nodes"])
    weight = line.joints[-1][1].mass * env.gravity + line.segments[0].type.submerged_weight(
        env.water_density, env.gravity) * line.unstretched_length
    push = np.array(entry["anchor_force"]) - [0.0, 0.0, -weight]
    normal = plane.normal
    assert np.linalg.norm(push - (push @ normal) * normal) <= 1e-6 * weight
    assert push @ normal > 0.0
    downhill = normal[:2] / np.linalg.norm(normal[:2])  # an upward normal leans downhill
    assert (nodes[-1, :2] - line.anchor[:2]) @ downhill > 1.0
    assert plane.project(nodes[-1:]).gap[0] <= 0.0
    chord = (nodes[-2] - nodes[0]) / np.linalg.norm(nodes[-2] - nodes[0])
    off = (nodes[:-1] - nodes[0]) - ((nodes[:-1] - nodes[0]) @ chord)[:, None] * chord
    w = line.segments[0].type.submerged_weight(env.water_density, env.gravity)  # -1.6e-5 N/m: its bow
    assert np.max(np.linalg.norm(off, axis=1)) <= abs(w) * line.unstretched_length**2 / (8 * entry["anchor_tension"])
    assert solved["line_iterations"][0] <= 200 and solved["strategies"][0] in ("newton", "axial continuation")


def test_network_strings_report_how_their_solves_went(tmp_path, capsys):
    """tripod.txt, its lines cables (EI zeroed: ``test_moordyn_files.without_ei``; as it stands its
    statics does not converge, ``test_tripod_with_its_ei_does_not_converge``): each string of the
    junction's network reports 'network (...)' with how its solves converged, its own Newton
    iterations summing to the scene's, and the outer iterations."""
    from test_moordyn_files import without_ei

    solved, printed = static_json(without_ei("tripod.txt", tmp_path), tmp_path, capsys)
    assert all(s.startswith("network (") for s in solved["strategies"])
    assert sum(solved["line_iterations"]) == solved["newton_iterations"]
    assert solved["network_iterations"] >= 1
    assert f"network: {solved['network_iterations']} outer Newton iterations" in printed


@pytest.mark.parametrize("slope_deg", [5.0, 20.0])
def test_a_chain_hanging_onto_a_slope_from_a_free_end_slides_until_the_seabed_pushes_normal(slope_deg):
    """A 50 m chain held 20 m above a frictionless plane, its other end free: it starts hanging onto
    the plane and lying downhill from the foot (``cablefem.statics.hang``), and settles where the
    support force less the chain's weight is the seabed's push, normal to the plane (1e-6 of the
    weight) and upwards, with the free end downhill of the support and the lying part along the
    fall line (y = 0 to 1e-9 m)."""
    from cablefem.fem.system import LineSystem
    from cablefem.geometry import Plane
    from cablefem.model.line import Line, LineType, Segment
    from cablefem.model.scene import Contact, Environment
    from cablefem.statics.solve import solve_static

    chain = LineType("chain", 0.1, 50.0, 1e9)
    env = Environment()
    normal = np.array([-np.sin(np.radians(slope_deg)), 0.0, np.cos(np.radians(slope_deg))])
    plane = Plane((0.0, 0.0, -30.0), normal)
    line = Line("chain", [0.0, 0.0, -10.0], [0.0, 0.0, -40.0], (Segment(chain, 50.0, 25),), prescribed=(True, False))
    system = LineSystem(line, plane, Contact(), env)
    result = solve_static(system)
    residual, _ = system.evaluate(system.state(result.X))
    on_support = -residual[0]  # the force the chain exerts on its support (statics.network.condensed)
    weight = chain.submerged_weight(env.water_density, env.gravity) * line.unstretched_length
    push = on_support - [0.0, 0.0, -weight]
    assert np.linalg.norm(push - (push @ normal) * normal) <= 1e-6 * weight
    assert push @ normal > 0.0
    assert result.X[-1, 0] < -1.0  # downhill: the normal leans to -x
    np.testing.assert_allclose(result.X[:, 1], 0.0, atol=1e-9)
