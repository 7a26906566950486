"""MoorDyn's own input files (tests/data/moordyn, copied from MoorDyn's repository) read as a MoorDyn
user would: each into the network it describes (points, bodies, strings and their kinds); the ones
whose strings end at fixed, coupled and body points solve in statics, and a free body too; the ones
with junctions or free bodies read, and a run steps them. Also: MoorDyn-C's v1 LINE TYPES layout read by position, the
Currents option and [environment] current_profile, body motions given by a TOML that wraps a file."""

import json
import os
from dataclasses import replace

import numpy as np
import pytest

from cablefem.cli import main
from cablefem.errors import InputError
from cablefem.io import load_scene
from cablefem.model.network import check_steppable, coupling

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "moordyn")


def data(name):
    return os.path.join(DATA, name)


def kinds(scene):
    """Point kinds ('body1' for a point on body1) and body kinds by name."""
    return ({name: point.body or point.kind for name, point in scene.points.items()},
            {name: body.kind for name, body in scene.bodies.items()})


def static_json(path, tmp_path, capsys):
    """``cablefem static FILE --json``: its JSON (exit status 0 asserted)."""
    out = tmp_path / "static.json"
    assert main(["static", str(path), "--json", str(out)]) == 0, capsys.readouterr()
    capsys.readouterr()
    return json.loads(out.read_text())


def test_three_catenaries_from_fixed_anchors_to_vessel_fairleads(tmp_path, capsys):
    """lines.txt (OC3-Hywind): three strings anchor first; the statics give three equal fairlead
    tensions (the layout is symmetric at 120 deg to 1e-2 m, so to 1e-4 relative)."""
    scene = load_scene(data("lines.txt"))
    assert [line.name for line in scene.lines] == ["line1", "line2", "line3"]
    assert kinds(scene) == ({"point1": "fixed", "point2": "fixed", "point3": "fixed", "point4": "coupled",
                             "point5": "coupled", "point6": "coupled"}, {})
    assert [line.ends for line in scene.lines] == [("point1", "point4"), ("point2", "point5"), ("point3", "point6")]
    lines = static_json(data("lines.txt"), tmp_path, capsys)["lines"]
    tensions = [entry["fairlead_tension"] for entry in lines]
    np.testing.assert_allclose(tensions, tensions[0], rtol=1e-4)
    assert 5e5 < tensions[0] < 2e6  # OC3-Hywind's pretension is ~0.9 MN


def test_fairleads_on_a_coupled_body_solve_where_the_body_holds_them(tmp_path, capsys):
    """lines_body.txt: the fairleads are points of a coupled body at (0, 0, -35): each string's
    fairlead end is the body's point r + R p, and the statics solve."""
    scene = load_scene(data("lines_body.txt"))
    assert kinds(scene) == ({"point1": "fixed", "point2": "fixed", "point3": "fixed", "point4": "body1",
                             "point5": "body1", "point6": "body1"}, {"body1": "coupled"})
    np.testing.assert_allclose(scene.lines[0].fairlead, [5.2, 0.0, -105.0])
    assert coupling(scene.lines, scene.points, scene.bodies) == ([], [])
    lines = static_json(data("lines_body.txt"), tmp_path, capsys)["lines"]
    np.testing.assert_allclose([entry["nodes"][-1] for entry in lines],
                               [[5.2, 0.0, -105.0], [-2.6, 4.5, -105.0], [-2.6, -4.5, -105.0]], atol=1e-9)


def test_a_mass_on_a_free_end_hangs_below_its_fixed_point(tmp_path, capsys):
    """pendulum.txt: a line as dense as the water, a free point of 1e5 kg on its free end: it hangs
    straight down, the top carrying the point's weight (MoorDyn's default g = 9.80665)."""
    scene = load_scene(data("pendulum.txt"))
    assert kinds(scene) == ({"point1": "fixed", "point2": "free"}, {})
    (line,) = scene.lines
    assert line.prescribed == (True, False) and line.joints[0][1].mass == 1e5
    (entry,) = static_json(data("pendulum.txt"), tmp_path, capsys)["lines"]
    weight = 1e5 * 9.80665
    np.testing.assert_allclose(entry["anchor_tension"], weight, rtol=1e-6)  # the top (fixed) end
    np.testing.assert_allclose(entry["nodes"][-1][:2], [0.0, 0.0], atol=1e-6)


@pytest.mark.parametrize("numsegs", [19, 76])
def test_a_beam_clamped_to_a_fixed_rod_is_a_cantilever_at_any_mesh(tmp_path, capsys, numsegs):
    """beam/BeamCantilevered.txt: a 10 m beam (EI 1e7 N m^2, 100 kg/m, in the air) clamped to a fixed
    rod's axis, its other end on a massless free point: the tip drops w L^4 / (8 EI) and the clamp
    holds w L^2 / 2, short by the large deflection's own (tip / L)^2 = 1.5e-4, at NumSegs 19 and at 76
    (from the hang, 38 and 76 Hermite elements folded the beam back at its clamp or did not converge:
    the start is now straight along the clamp)."""
    text = open(data("beam/BeamCantilevered.txt")).read().replace("10        19      -", f"10        {numsegs}      -")
    path = tmp_path / "BeamCantilevered.txt"
    path.write_text(text)
    (entry,) = static_json(path, tmp_path, capsys)["lines"]
    w, L, EI = 100.0 * 9.80665, 10.0, 1e7
    tip = np.array(entry["nodes"][-1])
    assert abs((10.0 - tip[2]) / (w * L**4 / (8.0 * EI)) - 1.0) < 2e-4  # -1.2e-4 at both meshes
    assert abs(entry["bending_moment"][0] / (w * L**2 / 2.0) - 1.0) < 1e-4  # -6.0e-5
    assert tip[0] > 9.99  # the beam stands out from its clamp, not folded back


def test_a_riser_between_two_fixed_points_in_a_current_profile(tmp_path, capsys):
    """viv/viv.txt: a line between two Fixed points (no fairlead at all), Currents 1 with its
    current_profile.txt (0.2 m/s from -11 m to the surface, 50 rows on one straight line, kept as 2),
    the v2 header with an 11th column (Cl) noted; the statics solve."""
    scene = load_scene(data("viv/viv.txt"))
    assert kinds(scene) == ({"point1": "fixed", "point2": "fixed"}, {})
    profile = scene.environment.current_profile
    assert profile.z == (-11.0, 0.0) and profile.velocity == ((0.2, 0.0, 0.0), (0.2, 0.0, 0.0))
    assert any("columns after CaAx ignored" in note for note in scene.notes)
    (entry,) = static_json(data("viv/viv.txt"), tmp_path, capsys)["lines"]
    np.testing.assert_allclose([entry["nodes"][0], entry["nodes"][-1]], [[-21.0425, 0, -10], [0, 0, -1]], atol=1e-9)


def test_lines_meeting_at_free_points_read_into_strings_and_a_junction(tmp_path):
    """tripod.txt with its EI zeroed (cables): free points joining two line ends become joints of four
    strings (nodeTether + nodeFloat up to a free end, three anchor legs of three lines each), and point
    3, where four string ends meet, is a junction (its statics: the next test), which a run steps with
    any integrator (``check_steppable`` refuses only a clamp on a body that turns). As written (EI > 0)
    its points are hinges: eleven strings, every free point joining two of them a junction, point 2 the
    float's free end."""
    scene = load_scene(without_ei("tripod.txt", tmp_path))
    assert sorted(line.name for line in scene.lines) == ["line11+10+9", "line2+1", "line5+4+3", "line8+7+6"]
    points, bodies = kinds(scene)
    assert [name for name, kind in points.items() if kind == "fixed"] == ["point6", "point9", "point12"]
    assert coupling(scene.lines, scene.points, scene.bodies) == (["point3"], [])
    legs = [line for line in scene.lines if line.name != "line2+1"]
    assert all(line.ends[1] == "point3" and line.prescribed == (True, False) for line in legs)
    check_steppable(scene)
    check_steppable(replace(scene, solver=replace(scene.solver, integrator="generalized-alpha", adaptive=True)))
    hinged = load_scene(data("tripod.txt"))
    assert sorted(line.name for line in hinged.lines) == sorted(f"line{k}" for k in range(1, 12))
    assert coupling(hinged.lines, hinged.points, hinged.bodies) == (
        sorted(f"point{k}" for k in (1, 3, 4, 5, 7, 8, 10, 11)), [])


def without_ei(name, tmp_path):
    """A copy of MoorDyn file ``name`` with the EI column of its LINE TYPES zeroed (its lines cables)."""
    rows, table = [], False
    for row in open(data(name), encoding="utf-8").read().splitlines():
        if row.startswith("---"):
            table = "LINE TYPES" in row
        fields = row.split()
        if table and len(fields) >= 10 and fields[5].replace(".", "").replace("E", "").replace("e", "").isdigit():
            fields[5] = "0"
            row = " ".join(fields)
        rows.append(row)
    path = tmp_path / name
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return path


def test_tripod_statics_converge_with_the_float_lying_at_its_waterline(tmp_path, capsys):
    """tripod.txt, its lines cables (EI zeroed; as written: ``test_tripod_with_its_ei_converges_with_its_float_standing_on_its_hinge``), in
    statics: the float (EA 2.2e9 N on 0.21 m elements) on a free end starts risen from the junction
    to where it floats (``cablefem.statics.hang``), and continuation on the axial stiffness settles it
    there, where Newton alone finds a basin of micrometres; at each move of the junction the string is
    translated with it and Newton converges. Nothing pulls sideways in
    still water, so the three anchors' horizontal forces cancel (1e-6 of their size), the tether
    stands vertical above the junction (point 3, moved from where the file put it), and the float's
    nodes lie within its half-diameter of the surface."""
    solved = static_json(without_ei("tripod.txt", tmp_path), tmp_path, capsys)
    points = solved["points"]
    anchors = np.array([points[name]["force"] for name in ("point6", "point9", "point12")])
    horizontal = anchors[:, :2]
    assert np.linalg.norm(horizontal.sum(axis=0)) <= 1e-6 * np.abs(horizontal).max()
    (string,) = [line for line in solved["lines"] if line["name"] == "line2+1"]
    nodes = np.array(string["nodes"])
    junction = np.array(points["point3"]["position"])
    assert np.linalg.norm(junction - [-0.82037111325625, 1.4824722198985547, -1.2840966813934565]) > 0.1
    np.testing.assert_allclose(nodes[:6, :2], np.tile(junction[:2], (6, 1)), atol=1e-9)  # tether: 5 elements
    assert np.all(np.abs(nodes[6:, 2]) < 0.41)  # the float, d = 0.82 m
    assert string["fairlead_tension"] < 1e-3 * string["anchor_tension"]  # its free end


def test_tripod_with_its_ei_converges_with_its_float_standing_on_its_hinge(tmp_path, capsys):
    """tripod.txt as it stands: its line types have EI > 0, so its lines are on Hermite elements and its
    free points are hinges (MoorDyn's points pass no moment): each line its own string, each point
    joining two of them a junction. The float (EI 9.3e7 N m^2, 0.63 m) starts standing straight on its
    hinge (point 1) and stays there; in still water nothing pulls sideways, so the anchors' horizontal
    forces cancel (1e-6 of their size), the tether and the float stand vertical above point 3 (the
    hinge carries no moment, so neither bends: the curvature is round-off) and the float's free end
    carries nothing."""
    solved = static_json(data("tripod.txt"), tmp_path, capsys)
    points = solved["points"]
    anchors = np.array([points[name]["force"] for name in ("point6", "point9", "point12")])
    horizontal = anchors[:, :2]
    assert np.linalg.norm(horizontal.sum(axis=0)) <= 1e-6 * np.abs(horizontal).max()
    lines = {line["name"]: line for line in solved["lines"]}
    junction = np.array(points["point3"]["position"])
    for name in ("line1", "line2"):  # the float and the tether
        nodes = np.array(lines[name]["nodes"])
        np.testing.assert_allclose(nodes[:, :2], np.tile(junction[:2], (len(nodes), 1)), atol=1e-9)
        assert max(lines[name]["curvature"]) < 1e-9
    float_nodes = np.array(lines["line1"]["nodes"])
    assert float_nodes[-1, 2] - float_nodes[0, 2] == pytest.approx(0.63, rel=1e-6)  # standing, stretched 1e-7
    assert lines["line1"]["fairlead_tension"] < 1e-6 * lines["line1"]["anchor_tension"]  # its free end


def test_a_free_body_reads_solves_in_statics_and_runs(tmp_path, capsys):
    """lines_body.txt with its body made free (mass, inertia, volume): read with MoorDyn's CG (one
    number: its z) and inertia (one number: all three); `cablefem static` finds where the hanging
    chain's pull balances its net buoyancy (rho V - M) g (1e-6); a run starts there and stays (its pose
    columns at the statics' pose to 1e-6 m after two steps)."""
    text = open(data("lines_body.txt"), encoding="utf-8").read()
    row = "1    Coupled     0.0    0.0   -35   0       0      0      0     -35      0        0       0      0"
    path = tmp_path / "free_body.txt"
    path.write_text(text.replace(row, "1    Free   0.0  0.0  -35  0  0  30  2e6  -5  1e8  2000  0  0"))
    scene = load_scene(path)
    body = scene.bodies["body1"]
    assert body.kind == "free" and body.mass == 2e6 and body.volume == 2000.0
    np.testing.assert_allclose(body.cg, [0, 0, -5])
    np.testing.assert_allclose(body.inertia, [1e8, 1e8, 1e8])
    np.testing.assert_allclose(body.rotation, [0, 0, np.radians(30)])
    assert coupling(scene.lines, scene.points, scene.bodies)[1] == ["body1"]
    solved = static_json(path, tmp_path, capsys)["bodies"]["body1"]
    net_buoyancy = (1025.0 * 2000.0 - 2e6) * 9.80665
    np.testing.assert_allclose(solved["force"], [0.0, 0.0, -net_buoyancy], rtol=0, atol=1e-6 * net_buoyancy)
    from cablefem.runs.run import run_scene

    summary = run_scene(scene, tmp_path / "run", duration=2 * scene.solver.dt, dt=scene.solver.dt)
    assert summary["completed"]
    table = np.genfromtxt(tmp_path / "run" / "tensions.csv", delimiter=",", names=True)
    np.testing.assert_allclose([table[f"bodybody1{axis}"][-1] for axis in "xyz"], solved["position"], atol=1e-6)


def test_zero_length_rods_of_a_moordyn_file_are_massless_points_joining_their_lines():
    """complex_system.txt's four free rods have NumSegs 0: MoorDyn-C gives a zero-length rod no mass
    and no volume, so each is a massless free point (the rods' ends R1A and R1B are the one point
    ``rod1``); its lines bend (EI > 0), so each such point is a hinge and every line a string of its own."""
    scene = load_scene(data("complex_system.txt"))
    assert [line.name for line in scene.lines] == [f"line{k}" for k in range(1, 8)]
    assert {"rod1", "rod2", "rod3", "rod4"} <= set(coupling(scene.lines, scene.points, scene.bodies)[0])
    rods = {name: point for name, point in scene.points.items() if name.startswith("rod")}
    assert sorted(rods) == ["rod1", "rod2", "rod3", "rod4"]
    assert all(p.kind == "free" and p.mass == 0.0 and p.volume == 0.0 and p.body is None for p in rods.values())


def test_v1_line_types_are_read_by_position_as_moordyn_c_reads_them(tmp_path):
    """The v1 header LineType Diam MassDenInAir EA BA/-zeta EI Can Cat Cdn Cdt: MoorDyn-C's
    readLineProps reads entries 6-9 as Cdn, Can, Cdt, Cat whatever the header names, and so does
    cablefem, with a note: the value under 'Can' is the normal drag coefficient."""
    text = open(data("lines.txt"), encoding="utf-8").read()
    text = text.replace("TypeName   Diam    Mass/m     EA         BA/-zeta    EI         Cd     Ca     CdAx    CaAx",
                        "LineType   Diam    MassDenInAir EA       BA/-zeta    EI         Can    Cat    Cdn     Cdt")
    text = text.replace("0          1.6    1.0    0.1     0.0", "0          1.6    1.0    0.1     0.2")
    path = tmp_path / "v1.txt"
    path.write_text(text)
    scene = load_scene(path)
    kind = scene.lines[0].segments[0].type
    assert (kind.Cd_normal, kind.Ca_normal, kind.Ca_tangential) == (1.6, 1.0, 0.2)
    np.testing.assert_allclose(kind.Cd_tangential, np.pi * 0.1)  # CdAx: MoorDyn's pi d reference
    assert any("read by position as MoorDyn-C reads them" in note for note in scene.notes)


def test_a_toml_gives_the_files_coupled_body_a_motion_and_the_current_a_profile(tmp_path):
    scene_file = tmp_path / "wrap.toml"
    body = '[bodies.body1.motion]\nkind = "harmonic"\namplitude = [2, 0, 0, 0, 0, 5]\nperiod = 10.0\n'
    current = '[environment]\ncurrent_profile = { z = [-320, 0], velocity = [[0.1, 0, 0], [0.8, 0, 0]] }\n'
    scene_file.write_text(f'[moordyn]\nfile = "{data("lines_body.txt")}"\n{body}{current}')
    scene = load_scene(scene_file)
    assert scene.bodies["body1"].motion.kind == "harmonic"
    np.testing.assert_allclose(scene.bodies["body1"].motion.amplitude, [2, 0, 0, 0, 0, np.radians(5)])
    assert scene.environment.current_profile.z == (-320.0, 0.0)
    assert not any("no body motion" in note for note in scene.notes)
    for extra, key, reason in (
            ('[bodies.body2.motion]\nkind = "fixed"\n', "bodies.body2", "no body 'body2'"),
            ('[bodies.body1]\nmass = 5.0\n', "bodies.body1.mass", "holds motion only"),
            ('[environment]\ncurrent = [1, 0, 0]\ncurrent_profile = "p.txt"\n', "environment.current_profile",
             "either current")):
        scene_file.write_text(f'[moordyn]\nfile = "{data("lines_body.txt")}"\n{extra}')
        with pytest.raises(InputError) as error:
            load_scene(scene_file)
        assert f"{key}: " in error.value.message() and reason in error.value.message(), error.value.message()


def test_motion_checks_the_chord_only_of_lines_it_alone_sets(tmp_path):
    """[motion]'s chord-strain check reads a line's chord from its anchor to its moving fairlead. On
    bodyDrag.txt with its anchor made Coupled and heaved 0.5 m, the line's other end is on the free
    body, which the file puts 5 m above the anchor (the body hangs 10.8 m below the surface): the
    chord the check would read, 5.5 m for 4.5 m of line, is no chord of the run, and the scene reads.
    On lines.txt, whose lines run from Fixed anchors to the Coupled fairleads, a surge that would
    stretch them 25 % is still refused."""
    text = open(data(os.path.join("laws", "bodyDrag.txt")), encoding="utf-8").read()
    (tmp_path / "driven.txt").write_text(text.replace("2         Fixed", "2         Coupled"))
    motion = '[motion]\nkind = "harmonic"\namplitude = [{}]\nperiod = 5.0\n'
    (tmp_path / "driven.toml").write_text('[moordyn]\nfile = "driven.txt"\n' + motion.format("0, 0, 0.5"))
    scene = load_scene(tmp_path / "driven.toml")
    assert scene.points["point2"].kind == "coupled" and scene.bodies["body1"].kind == "free"
    (tmp_path / "surged.toml").write_text(f'[moordyn]\nfile = "{data("lines.txt")}"\n' + motion.format("250, 0, 0"))
    with pytest.raises(InputError) as error:
        load_scene(tmp_path / "surged.toml")
    assert "motion.amplitude: " in error.value.message() and "absurd strain" in error.value.message()


def test_the_one_list_of_refusals_is_the_table_in_the_docs():
    """docs/scene.md "What stays refused" holds every row of moordyn_sections.REFUSED as written there."""
    from cablefem.io.moordyn_sections import REFUSED

    with open(os.path.join(DATA, "..", "..", "..", "docs", "scene.md"), encoding="utf-8") as handle:
        docs = handle.read()
    for what, instead in REFUSED.values():
        assert f"| {what.replace('|', chr(92) + '|')} | {instead} |" in docs, what


SHARED = """--------------------- MoorDyn Input File ------------------------------------
two coupled bodies, each moored to one anchor, and a shared line between them (lines.txt's line type)
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam    Mass/m     EA         BA/-zeta    EI         Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)        (N-s/-)     (N-m^2)    (-)    (-)    (-)     (-)
main       0.09    77.7066    384.243E6  -0.8        0          1.6    1.0    0.1     0.0
---------------------------- BODIES -----------------------------------------------------
ID   Attachment  X0     Y0    Z0    r0      p0     y0     Mass  CG*      I*       Volume  CdA*   Ca
(#)  (-)         (m)    (m)   (m)   (deg)   (deg)  (deg)  (kg)  (m)      (kg-m^2) (m^3)   (m^2)  (-)
1    Coupled     0.0    0.0   0     0       0      0      0     0        0        0       0      0
2    Coupled     400.0  0.0   0     0       0      180    0     0        0        0       0      0
---------------------- POINTS --------------------------------
ID    Type      X       Y       Z       Mass   Volume  CdA    Ca
(#)   (-)       (m)     (m)     (m)     (kg)   (m^3)   (m^2)  (-)
1     Fixed     -800.0  0       -320.0  0      0       0      0
2     Body1     -5.0    0       -20.0   0      0       0      0
3     Body1     5.0     0       -20.0   0      0       0      0
4     Body2     5.0     0       -20.0   0      0       0      0
5     Body2     -5.0    0       -20.0   0      0       0      0
6     Fixed     1200.0  0       -320.0  0      0       0      0
---------------------- LINES ----------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (#)      (#)       (m)       (-)     (-)
1     main       1        2         902.2     20      -
2     main       3        4         420.0     20      -
3     main       5        6         902.2     20      -
---------------------- OPTIONS -----------------------------------------
320           WtrDpth       water depth (m)
------------------------- need this line --------------------------------------
"""


def test_a_shared_line_between_two_coupled_bodies(tmp_path, capsys):
    """Two coupled bodies (the second yawed 180 deg: its point at x = +5 in its frame is at x = 395),
    each moored to an anchor, and a line shared between them: three strings, the shared one between
    two body points; the statics solve, and by symmetry the shared line's ends carry equal tensions
    (1e-6) as do the two mooring legs."""
    path = tmp_path / "shared.txt"
    path.write_text(SHARED)
    scene = load_scene(path)
    assert kinds(scene)[1] == {"body1": "coupled", "body2": "coupled"}
    shared = scene.lines[1]
    assert shared.ends == ("point3", "point4") and shared.prescribed == (True, True)
    np.testing.assert_allclose([shared.anchor, shared.fairlead], [[5, 0, -20], [395, 0, -20]], atol=1e-12)
    lines = static_json(path, tmp_path, capsys)["lines"]
    np.testing.assert_allclose(lines[1]["anchor_tension"], lines[1]["fairlead_tension"], rtol=1e-6)
    assert scene.lines[2].ends == ("point6", "point5")  # its fixed end first
    np.testing.assert_allclose(lines[0]["fairlead_tension"], lines[2]["fairlead_tension"], rtol=1e-6)


def test_lines_txt_tensions_agree_with_moorpys_system_reading_the_same_file(tmp_path, capsys):
    """MoorPy's System reads lines.txt itself (g set to MoorDyn's 9.80665, which cablefem reads as
    the default of a file without g): fairlead and anchor tensions within 3e-5 (60 P2 elements per
    line: converged to 1e-6; the 1.3e-5 left is the seabed, springs of kBot here, rigid in MoorPy)."""
    mp = pytest.importorskip("moorpy")
    wrap = tmp_path / "wrap.toml"
    wrap.write_text(f'[moordyn]\nfile = "{data("lines.txt")}"\nelements = 60\norder = 2\n')
    lines = static_json(wrap, tmp_path, capsys)["lines"]
    system = mp.System(file=data("lines.txt"), g=9.80665)
    system.initialize()
    system.solveEquilibrium()
    for entry, line in zip(lines, system.lineList):
        np.testing.assert_allclose([entry["anchor_tension"], entry["fairlead_tension"]], [line.TA, line.TB], rtol=3e-5)
