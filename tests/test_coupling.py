"""Statics of networks with coupling unknowns (issue 18, ``cablefem.statics.network``): a junction of three
lines carrying a buoy and a free body under a steady offset load, each against MoorPy's ``System``
(the elastic catenary in closed form), and the balance's Jacobian against finite differences."""

import os

import numpy as np
import pytest

from cablefem.statics.network import Network, solve_network
from cablefem.io import load_scene
from cablefem.model.network import rotation
from cablefem.runs.results import end_forces
from cablefem.fem.system import build_system

os.environ.setdefault("PYTHONBREAKPOINT", "0")
RHO, G, D, M, EA = 1025.0, 9.81, 0.1, 60.0, 5.0e8
HEADINGS = np.radians([0.0, 120.0, 240.0])
ANCHORS = [(float(400 * np.cos(h)), float(400 * np.sin(h)), -200.0) for h in HEADINGS]
FAIRLEADS = [(float(20 * np.cos(h)), float(20 * np.sin(h)), -10.0) for h in HEADINGS]
BODY = {"mass": 2.0e6, "volume": 2.3e3, "waterplane_area": 300.0, "cg": [0.0, 0.0, -5.0], "cb": [0.0, 0.0, 3.0],
        "force": [3.0e5, 1.0e5, 0.0], "moment": [0.0, 0.0, 2.0e6]}
JUNCTION = {"mass": 1.0e3, "volume": 40.0}


def _toml(value):
    return "[" + ", ".join(repr(float(x)) for x in value) + "]" if isinstance(value, (list, tuple)) else repr(value)


def network_scene(tmp_path, junction, order=2, elements=20, lengths=(430.0, 430.0, 430.0)):
    """Three chains from anchors 120 deg apart, suspended (the seabed far below), to a free body's
    fairleads (``junction`` False) or to one free point with a buoy (True)."""
    text = f"""name = "network"
[environment]
water_density = {RHO}
gravity = {G}
[seabed]
kind = "horizontal"
depth = 2000.0
[line_types.chain]
diameter = {D}
mass = {M}
EA = {EA}
"""
    if junction:
        text += "[points.j]\nkind = \"free\"\nposition = [0.0, 0.0, -60.0]\n"
        text += "".join(f"{k} = {_toml(v)}\n" for k, v in JUNCTION.items())
    else:
        text += "[bodies.platform]\nkind = \"free\"\nposition = [0.0, 0.0, 0.0]\ninertia = [1e9, 1e9, 1e9]\n"
        text += "".join(f"{k} = {_toml(v)}\n" for k, v in BODY.items())
    for i, (a, f) in enumerate(zip(ANCHORS, FAIRLEADS)):
        text += f"[points.a{i}]\nkind = \"fixed\"\nposition = {_toml(a)}\n"
        if not junction:
            text += f"[points.f{i}]\nbody = \"platform\"\nposition = {_toml(f)}\n"
    for i, length in enumerate(lengths):
        end = "j" if junction else f"f{i}"
        text += (f"[[lines]]\nname = \"l{i}\"\nanchor = \"a{i}\"\nfairlead = \"{end}\"\norder = {order}\n"
                 f"segments = [{{ type = \"chain\", length = {length}, elements = {elements} }}]\n")
    path = tmp_path / "network.toml"
    path.write_text(text)
    return load_scene(path)


def moorpy_system(junction, lengths=(430.0, 430.0, 430.0)):
    moorpy = pytest.importorskip("moorpy")
    ms = moorpy.System(depth=2500.0, rho=RHO, g=G)
    ms.setLineType(dnommm=100.0, name="c", d_vol=D, mass=M, EA=EA, w=(M - RHO * np.pi / 4 * D * D) * G)
    if junction:
        ms.addPoint(0, np.array([0.0, 0.0, -60.0]), m=JUNCTION["mass"], v=JUNCTION["volume"])
    else:
        ms.addBody(0, np.zeros(6), m=BODY["mass"], v=BODY["volume"], rCG=np.array(BODY["cg"]),
                   AWP=BODY["waterplane_area"], rM=np.array(BODY["cb"]), f6Ext=np.array(BODY["force"] + BODY["moment"]))
    for i, length in enumerate(lengths):
        ms.addPoint(1, np.array(ANCHORS[i]))
        if junction:
            ms.addLine(length, "c", pointA=len(ms.pointList), pointB=1)
        else:
            ms.addPoint(1, np.array(FAIRLEADS[i]), body=1)
            ms.addLine(length, "c", pointA=len(ms.pointList) - 1, pointB=len(ms.pointList))
    ms.initialize()
    ms.solveEquilibrium(tol=1e-10, maxIter=2000)
    return ms


def static_systems(scene):
    return lambda line: build_system(scene, line, dynamic=False)


def tensions(result):
    """(fairlead, anchor) tension [N] of each string."""
    return np.array([[np.linalg.norm(F) for F in end_forces(s, X)] for s, X in zip(result.systems, result.states)])


def test_a_free_body_under_an_offset_load_matches_moorpy(tmp_path):
    """Weight at the centre of gravity, buoyancy at the metacentre, the waterplane's heave stiffness
    and a steady force and yaw moment: the body's pose (compared as its reference point and its
    rotation matrix: MoorPy turns z-y-x, MoorDyn-C and cablefem x-y-z, so the angles differ) and
    both end tensions of every line agree with MoorPy's catenaries."""
    scene = network_scene(tmp_path, junction=False)
    result = solve_network(scene, static_systems(scene))
    ms = moorpy_system(junction=False)
    from moorpy.helpers import rotationMatrix

    pose, r6 = result.poses["platform"], ms.bodyList[0].r6
    assert np.linalg.norm(pose[:3]) > 5.0 and abs(pose[5]) > 0.05  # a real offset and yaw
    np.testing.assert_allclose(pose[:3], r6[:3], atol=1e-5)
    np.testing.assert_allclose(rotation(pose[3:]), rotationMatrix(*r6[3:]), atol=1e-7)
    expected = np.array([[line.TB, line.TA] for line in ms.lineList])
    np.testing.assert_allclose(tensions(result), expected, rtol=1e-6)


def test_a_junction_of_three_lines_with_a_buoy_matches_moorpy(tmp_path):
    """A free point joining three chains, its buoy lifting them: position and tensions."""
    lengths = (430.0, 430.0, 436.0)
    scene = network_scene(tmp_path, junction=True, lengths=lengths)
    result = solve_network(scene, static_systems(scene))
    ms = moorpy_system(junction=True, lengths=lengths)
    np.testing.assert_allclose(result.points["j"], ms.pointList[0].r, atol=1e-5)
    expected = np.array([[line.TB, line.TA] for line in ms.lineList])
    np.testing.assert_allclose(tensions(result), expected, rtol=1e-6)


@pytest.mark.parametrize("junction", [False, True])
def test_the_balance_jacobian_equals_finite_differences(tmp_path, junction):
    """The condensed end stiffness (Schur complements), the moment's geometric terms, the body's
    own loads and the buoy's wet fraction: dr/dq against central differences of re-solved strings."""
    lengths = (430.0, 430.0, 436.0) if junction else (430.0, 430.0, 430.0)
    scene = network_scene(tmp_path, junction=junction, order=1, elements=12, lengths=lengths)
    net = Network(scene, static_systems(scene))
    q = net.start() + (np.array([3.0, -2.0, -20.0]) if junction else np.array([4.0, 1.0, 0.5, 0.02, -0.03, 0.1]))

    def balance(q):
        states = [None] * len(scene.lines)
        places = net.place(q)
        net.solve_strings(places, states, 1e-12, 100)
        return net.balance(q, states, places)

    r, J = balance(q)
    numeric = np.zeros_like(J)
    for i in range(len(q)):
        h = 1e-4 if (junction or i < 3) else 1e-6
        dq = np.zeros(len(q))
        dq[i] = h
        numeric[:, i] = (balance(q + dq)[0] - balance(q - dq)[0]) / (2 * h)
    assert np.abs(J - numeric).max() <= 1e-5 * np.abs(J).max()


def test_cablefem_static_reports_the_free_body_in_balance(tmp_path):
    """``cablefem static --json``: the strings' force and moment on the body, with its weight at the
    centre of gravity, buoyancy at cb, the waterplane's heave force and the external load, sum to
    zero (the body's equilibrium, computed from the reported pose and end forces). Free bodies in a
    run: tests/test_body_dynamics.py."""
    import json

    from cablefem.cli import main

    network_scene(tmp_path, junction=False)
    out = tmp_path / "static.json"
    assert main(["static", str(tmp_path / "network.toml"), "--json", str(out)]) == 0
    body = json.loads(out.read_text())["bodies"]["platform"]
    position, R = np.array(body["position"]), rotation(np.radians(body["rotation_deg"]))
    weight, buoyancy = np.array([0.0, 0.0, -BODY["mass"] * G]), np.array([0.0, 0.0, RHO * G * BODY["volume"]])
    heave = np.array([0.0, 0.0, -RHO * G * BODY["waterplane_area"] * position[2]])
    force = np.array(body["force"]) + weight + buoyancy + heave + BODY["force"]
    moment = (np.array(body["moment"]) + np.cross(R @ BODY["cg"], weight) + np.cross(R @ BODY["cb"], buoyancy)
              + BODY["moment"])
    assert np.abs(force).max() <= 1e-6 * BODY["mass"] * G and np.abs(moment).max() <= 1e-6 * BODY["moment"][2]
