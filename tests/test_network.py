"""Networks (issue 18): MoorDyn-C's rotation convention, the paths of points on moving bodies, the
strings of lines joined through points, the TOML keys and their errors."""

import os
import textwrap

import numpy as np
import pytest

from cablefem.errors import InputError
from cablefem.io import load_scene
from cablefem.model.motion import body_motion
from cablefem.model.network import Body, BodyPointPath, rotation, rotation_rates
from cablefem.model.scene import Motion

HERE = os.path.dirname(__file__)


def _quiet_moordyn(run):
    """``run()`` with file descriptor 1 sent to /dev/null (MoorDyn prints every step)."""
    saved, null = os.dup(1), os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    try:
        return run()
    finally:
        os.dup2(saved, 1)
        os.close(null)
        os.close(saved)


MOORDYN_BODY = """\
--------------------- MoorDyn Input File ------------------------------------
points on a coupled body, to read MoorDyn's rotation convention
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam    Mass/m     EA         BA/-zeta    EI         Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)        (N-s/-)     (N-m^2)    (-)    (-)    (-)     (-)
rope       0.1     10.0       1.0E8      -0.5        0          1.2    1.0    0.0     0.0
---------------------- BODIES ------------------------------------------------
ID   Attachment  X0     Y0    Z0     r0      p0     y0     Mass  CG*   I*      Volume   CdA*   Ca*
(#)  (-)         (m)    (m)   (m)    (deg)   (deg)  (deg)  (kg)  (m)   (kg-m^2)  (m^3)   (m^2)  (-)
1    coupled     0      0     -5     0       0      0      0     0     0       0        0      0
---------------------- POINTS --------------------------------
ID    Attachment  X       Y     Z      M      V      CdA   CA
(-)   (-)         (m)     (m)   (m)    (kg)   (m^3)  (m^2) (-)
1     Body1       1.0     0     0      0      0      0     0
2     Body1       0       1.0   0      0      0      0     0
3     Body1       0       0     1.0    0      0      0     0
4     Fixed       50      0     -50    0      0      0     0
5     Fixed       0       50    -50    0      0      0     0
6     Fixed       0       0     -60    0      0      0     0
---------------------- LINES ----------------------------------------
ID   LineType  AttachA  AttachB  UnstrLen  NumSegs  Outputs
(#)  (name)    (#)      (#)      (m)       (-)      (-)
1    rope      4        1        60        10       -
2    rope      5        2        60        10       -
3    rope      6        3        60        10       -
---------------------- OPTIONS -----------------------------------------
0.001    dtM
100      WtrDpth
-------------------------------------------------------------------------
"""


def test_body_rotations_are_moordyns(tmp_path):
    """Points on a coupled MoorDyn-C body at unit distances along its axes land where cablefem's
    R = Rx(roll) Ry(pitch) Rz(yaw) puts them, for rotations about each axis and all three."""
    moordyn = pytest.importorskip("moordyn")
    path = tmp_path / "rot.dat"
    path.write_text(MOORDYN_BODY)
    cases = [np.radians(a) for a in ([30, 0, 0], [0, 30, 0], [0, 0, 30], [30, 40, 50], [-70, 15, 200])]

    def run():
        system = moordyn.Create(str(path))
        out = []
        for k, angles in enumerate(cases):
            x = np.concatenate([[0.0, 0.0, -5.0], angles])
            if k == 0:
                moordyn.Init(system, x, np.zeros(6))
            moordyn.Step(system, x, np.zeros(6), 0.0, 0.001)
            out.append([np.array(moordyn.GetPointPos(moordyn.GetPoint(system, i))) - [0, 0, -5] for i in (1, 2, 3)])
        moordyn.Close(system)
        return out

    theirs = _quiet_moordyn(run)
    for angles, columns in zip(cases, theirs):
        np.testing.assert_allclose(np.array(columns).T, rotation(angles), rtol=0, atol=1e-12)


def test_a_point_on_a_moving_body_has_the_velocity_and_acceleration_of_its_path():
    """BodyPointPath's velocity and acceleration (dR/dt, d2R/dt2 through the three factors) against
    central differences of its positions, for a six-component harmonic motion with phases."""
    motion = Motion("harmonic", amplitude=np.array([3.0, 1.0, 2.0, 0.2, 0.3, 0.5]), period=7.0,
                    offset=np.array([1.0, 0, 0, 0.1, 0, 0]), ramp=5.0, phase=np.array([0, 1.0, 2.0, 0.3, 0.7, 1.1]))
    body = Body("b", "coupled", [10.0, -5.0, 2.0], rotation=[0.1, -0.2, 0.4], motion=motion)
    path = BodyPointPath(body, [30.0, -12.0, -20.0])
    times = np.array([0.7, 3.1, 6.0, 11.3])
    x, v, a = path.states(times)
    h = 1e-4
    xp, xm = path.positions(times + h), path.positions(times - h)
    np.testing.assert_allclose(v, (xp - xm) / (2 * h), rtol=0, atol=1e-6 * np.abs(v).max())
    np.testing.assert_allclose(a, (xp - 2 * x + xm) / h**2, rtol=0, atol=2e-4 * np.abs(a).max())
    R, dR, ddR = rotation_rates(np.array([0.1, 0.2, 0.3]), np.zeros(3), np.zeros(3))
    np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-15)
    d = body_motion(motion, 0.0)[0]
    np.testing.assert_allclose(d, 0.0, atol=1e-15)  # ramped from rest


NETWORK = """\
name = "net"
[line_types.chain]
diameter = 0.15
mass = 140.0
EA = 1.2e9
[line_types.poly]
diameter = 0.2
mass = 30.0
EA = 1.5e8
[bodies.platform]
kind = "coupled"
position = [0.0, 0.0, 0.0]
rotation_deg = [0.0, 0.0, 90.0]
[points.a1]
kind = "fixed"
position = [-700.0, 0.0, -200.0]
[points.clump1]
kind = "free"
position = [-500.0, 0.0, -190.0]
mass = 20000.0
volume = 2.5
[points.buoy1]
kind = "free"
position = [-250.0, 0.0, -120.0]
mass = 2000.0
volume = 15.0
[points.f1]
body = "platform"
position = [0.0, 40.0, -15.0]
[[lines]]
name = "top"
anchor = "f1"
fairlead = "buoy1"
segments = [{ type = "chain", length = 230.0, elements = 11 }]
[[lines]]
name = "bottom"
anchor = "a1"
fairlead = "clump1"
segments = [{ type = "chain", length = 250.0, elements = 12 }]
[[lines]]
name = "rope"
anchor = "clump1"
fairlead = "buoy1"
segments = [{ type = "poly", length = 300.0, elements = 13 }]
[seabed]
kind = "horizontal"
depth = 200.0
"""


def write(tmp_path, text, name="net.toml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return str(path)


def test_lines_joined_through_free_points_are_one_string_anchored_at_the_fixed_point(tmp_path):
    scene = load_scene(write(tmp_path, NETWORK))
    (line,) = scene.lines
    assert line.name == "bottom+rope+top"
    assert line.ends == ("a1", "f1") and line.prescribed == (True, True)
    assert [seg.elements for seg in line.segments] == [12, 13, 11]  # 'top' turned round to run on
    assert [(k, joint.name, joint.mass) for k, joint in line.joints] == [(1, "clump1", 20000.0), (2, "buoy1", 2000.0)]
    np.testing.assert_allclose(line.anchor, [-700.0, 0.0, -200.0])
    np.testing.assert_allclose(line.fairlead, [-40.0, 0.0, -15.0], atol=1e-12)  # yawed 90 deg: +y to -x


@pytest.mark.parametrize("change, key, message", [
    (("anchor = \"a1\"", "anchor = \"a2\""), "lines[1].anchor", "no point 'a2'"),
    (("body = \"platform\"", "body = \"platfrom\""), "points.f1.body", "no body 'platfrom'"),
    (("[[lines]]\nname = \"top\"", "[points.spare]\nkind = \"fixed\"\nposition = [0.0, 0.0, -100.0]\n"
      "[[lines]]\nname = \"top\""), "points.spare", "no line uses this point"),
    (("kind = \"coupled\"", "kind = \"free\"\nmass = 1e6\ninertia = [1e8, 0.0, 1e8]"), "bodies.platform.inertia",
     "singular"),
])
def test_bad_network_input_gets_one_clear_error(tmp_path, change, key, message):
    text = NETWORK.replace(*change)
    assert text != NETWORK
    with pytest.raises(InputError) as caught:
        load_scene(write(tmp_path, text))
    assert key in str(caught.value) and message in str(caught.value)


def test_a_six_column_table_with_the_wrong_number_of_columns_is_refused(tmp_path):
    (tmp_path / "motion.csv").write_text("t x y z roll pitch yaw\n0 0 0 0 0 0 0\n1 1 0 0 0 0\n")
    text = NETWORK.replace("rotation_deg = [0.0, 0.0, 90.0]", "[bodies.platform.motion]\nkind = \"table\"\n"
                                                               "file = \"motion.csv\"")
    with pytest.raises(InputError, match="motion.csv line 3: expected 7 columns"):
        load_scene(write(tmp_path, text))


def test_an_openfast_output_drives_a_body_by_its_platform_channels(tmp_path):
    """The PtfmSurge ... PtfmYaw channels of an OpenFAST .out file, found by name among others."""
    rows = ["Predictions were generated on ...", "", "Time  Wave1Elev  PtfmSurge  PtfmSway  PtfmHeave  PtfmRoll  "
            "PtfmPitch  PtfmYaw", "(s)  (m)  (m)  (m)  (m)  (deg)  (deg)  (deg)"]
    rows += [f"{t:.1f} 0.3 {2 * t:.3f} 0 {0.5 * t:.3f} 0 {t:.3f} 0" for t in np.arange(0, 5.01, 0.5)]
    (tmp_path / "platform.out").write_text("\n".join(rows) + "\n")
    text = NETWORK.replace("rotation_deg = [0.0, 0.0, 90.0]", "[bodies.platform.motion]\nkind = \"table\"\n"
                                                               "file = \"platform.out\"")
    scene = load_scene(write(tmp_path, text))
    body = scene.bodies["platform"]
    d = body_motion(body.motion, 2.0)[0]
    np.testing.assert_allclose(d, [4.0, 0.0, 1.0, 0.0, np.radians(2.0), 0.0], atol=1e-12)
    path = BodyPointPath(body, scene.points["f1"].position)
    np.testing.assert_allclose(path(2.0)[0], [4.0, 0.0, 1.0] + rotation(d[3:]) @ [0.0, 40.0, -15.0], atol=1e-12)


def test_a_run_reports_each_point_and_body_force_and_the_bodys_moment(tmp_path):
    """tensions.csv's network columns: a point's force is the force of the string ending there, the
    body's force their sum and its moment the sum of (x - r) x F with x - r = R(t) p computed here
    from the body's path; summary.json's extremes are the largest magnitudes of those columns."""
    import json

    import pandas as pd

    from cablefem.model.motion import body_motion
    from cablefem.model.network import rotation
    from cablefem.runs.run import run_scene

    motion = """[bodies.platform.motion]
kind = "harmonic"
amplitude = [3.0, 1.0, 0.5, 2.0, 3.0, 5.0]
period = 6.0
ramp = 3.0
[solver]
dt = 0.05
duration = 3.0
[output]
every = 3.0
"""
    text = NETWORK.replace('rotation_deg = [0.0, 0.0, 90.0]\n', 'rotation_deg = [0.0, 0.0, 90.0]\n' + motion)
    text = text.replace("[points.a1]", "[points.f2]\nbody = \"platform\"\nposition = [30.0, 0.0, -15.0]\n"
                        "[points.a2]\nkind = \"fixed\"\nposition = [700.0, 0.0, -200.0]\n[points.a1]")
    text += ('[[lines]]\nname = "second"\nanchor = "a2"\nfairlead = "f2"\n'
             'segments = [{ type = "chain", length = 760.0, elements = 20 }]\n')
    scene = load_scene(write(tmp_path, text))
    summary = run_scene(scene, tmp_path / "out", progress=False)
    table = pd.read_csv(tmp_path / "out" / "tensions.csv")
    f1 = table[[f"point:f1:f{c}" for c in "xyz"]].to_numpy()
    f2 = table[[f"point:f2:f{c}" for c in "xyz"]].to_numpy()
    np.testing.assert_allclose(f2, table[[f"second:f{c}" for c in "xyz"]].to_numpy(), rtol=0, atol=1e-3)
    body = table[[f"body:platform:{c}" for c in ("fx", "fy", "fz", "mx", "my", "mz")]].to_numpy()
    np.testing.assert_allclose(body[:, :3], f1 + f2, rtol=1e-9, atol=1e-3)
    d = body_motion(scene.bodies["platform"].motion, table["t"].to_numpy())[0]
    R = rotation(scene.bodies["platform"].rotation + d[:, 3:])
    moment = (np.cross(R @ scene.points["f1"].position, f1) + np.cross(R @ scene.points["f2"].position, f2))
    np.testing.assert_allclose(body[:, 3:], moment, rtol=1e-8, atol=1e-2)
    assert np.abs(d[:, 3:]).max() > 0.01  # the body has turned
    extremes = json.loads((tmp_path / "out" / "summary.json").read_text())["network_extremes"]
    assert extremes["body:platform"]["moment_max"] == pytest.approx(np.linalg.norm(body[:, 3:], axis=1).max(), rel=1e-8)
    assert extremes["point:f1"]["force_max"] == pytest.approx(np.linalg.norm(f1, axis=1).max(), rel=1e-8)
    assert summary["completed"]
    import meshio

    from cablefem.runs.network_output import body_reference

    frame = meshio.read(sorted((tmp_path / "out").glob("net_*.vtu"))[-1])  # at t = 3 s
    kinds = np.concatenate(frame.cell_data["network"])
    cells = np.concatenate([block.data[:, 0] for block in frame.cells])  # each cell's first point
    assert (kinds == 1).sum() == len(scene.points)  # a vertex at every named point
    reference = frame.points[cells[kinds == 2]]  # the body's segments start at its reference point
    np.testing.assert_allclose(reference, np.broadcast_to(body_reference(scene.bodies["platform"], 3.0), reference.shape),
                               atol=1e-9)
    assert len(reference) == 2  # to its two points


class _Crawl:
    """A scalar problem r(x) = x whose Newton step is cut to a ``fraction`` of the way: Newton crawls
    when ``fraction`` is small (what network statics meets far from a free body's equilibrium)."""

    def __init__(self, fraction):
        self.fraction = fraction

    def evaluate(self, x):
        return np.array([x]), np.array([[1.0]]), abs(x)

    def solve(self, J, r):
        return -self.fraction * r

    def trial(self, x, step, lam):
        return x + lam * step[0]

    def small(self, step):
        return abs(step[0]) < 1e-14


@pytest.mark.parametrize("fraction, converged", [(0.5, True), (0.05, False)])
def test_halving_gives_up_on_newton_that_crawls(fraction, converged):
    from cablefem.statics.newton import Halving, iterate

    x, iterations, norm, history, ok = iterate(_Crawl(fraction), 1.0, 1e-8, 200, Halving())
    assert ok == converged
    if converged:  # halving the residual at each step: 27 steps to 1e-8
        assert norm <= 1e-8 and iterations == 27
    else:  # 5 % a step: 8 steps leave 0.66 of the residual, so the ninth gives up
        assert len(history) == Halving.WINDOW + 1 and norm > 0.5
