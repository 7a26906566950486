"""MoorDyn's RODS as rigid bodies (issue 36, deliverable 1): a free and a pinned rod's statics against
their closed forms, fixed, coupled and zero-length rods equal to the same scene written with points
and bodies, a rod's drag against its closed form, and bad input in one line."""

import json
import math
import os

import numpy as np
import pytest

from cablefem.cli import main
from cablefem.io import load_scene
from cablefem.loads.rod import drag, mass_matrix, static_loads
from cablefem.model.rod import Rod, RodType

RHO, G = 1025.0, 9.80665
HERE = os.path.dirname(__file__)
#: a rope twice as dense as the water
ROPE_D = 0.05
ROPE_EA = 1.0e7
ROPE_MASS = 2.0 * RHO * math.pi / 4.0 * ROPE_D ** 2


def moordyn_file(tmp_path, rod_types, rods, points, lines, depth=20.0, name="rods.txt"):
    """A MoorDyn file of ``rod_types``, ``rods``, ``points`` and ``lines`` rows on the neutral rope."""
    mass = ROPE_MASS
    text = f"""\
--------------------- MoorDyn Input File ------------------------------------
rods
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam    Mass/m     EA         BA/-zeta    EI         Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)        (N-s/-)     (N-m^2)    (-)    (-)    (-)     (-)
rope       {ROPE_D}  {mass!r}  {ROPE_EA}  -0.5        0          1.2    1.0    0.0     0.0
---------------------- ROD TYPES ------------------------------------
TypeName      Diam     Mass/m    Cd     Ca      CdEnd    CaEnd
(name)        (m)      (kg/m)    (-)    (-)     (-)      (-)
{rod_types}
---------------------- RODS ----------------------------------------
ID   RodType   Attachment  Xa    Ya    Za    Xb    Yb    Zb   NumSegs  RodOutputs
(#)  (name)     (#/key)    (m)   (m)   (m)   (m)   (m)   (m)  (-)       (-)
{rods}
---------------------- POINTS ----------------------------------------
ID    Type      X       Y       Z       Mass   Volume  CdA    Ca
(#)   (-)       (m)     (m)     (m)     (kg)   (m^3)   (m^2)  (-)
{points}
---------------------- LINES ----------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (#)      (#)       (m)       (-)     (-)
{lines}
---------------------- OPTIONS -----------------------------------------
{depth}          WtrDpth              water depth (m)
{RHO}            WtrDnsty
------------------------- need this line --------------------------------------
"""
    path = tmp_path / name
    path.write_text(text)
    return path


def static_json(path, tmp_path, capsys):
    """``cablefem static FILE --json``: its JSON."""
    out = tmp_path / (os.path.basename(str(path)).rsplit(".", 1)[0] + ".json")
    assert main(["static", str(path), "--json", str(out)]) == 0, capsys.readouterr()
    capsys.readouterr()
    return json.loads(out.read_text())


def unstretched(tension, length, weight):
    """The unstretched length l [m] of the rope hanging vertical between two points ``length`` [m]
    apart, ``tension`` [N] at one end and T(u) = tension + weight u at u unstretched metres from it
    (``weight`` [N/m]: its weight per metre in water or in air, negative going down from its top):
    length = l + (tension l + weight l^2 / 2) / EA."""
    a, b, c = weight / (2.0 * ROPE_EA), 1.0 + tension / ROPE_EA, -length
    return -2.0 * c / (b + math.sqrt(b * b - 4.0 * a * c))


def test_a_free_rod_piercing_the_surface_takes_the_tilt_and_tensions_of_its_closed_form(tmp_path, capsys):
    """A rod (d 0.5 m, 150 kg/m, L 10 m) piercing the surface, end A 6 m under it held down by a
    vertical rope from an anchor, end B 2 m above it hanging from a vertical rope to a point 6 m
    away: the ropes are vertical where they hold it, so its tilt is asin(8/10); its submerged
    fraction f = 6/8 of the axis carries rho g A L f at f L/2 from A, its weight W = m g L acts at
    L/2; the moment about A gives T_B = (W - B f)/2, the vertical balance T_A = T_B + B - W. The
    ropes' unstretched lengths are designed for that pose (``unstretched``), and the file starts the
    rod turned by 3 degrees about its middle. Tolerance 1e-6 relative: the solver's."""
    d, m, L = 0.5, 150.0, 10.0
    A, B_ = np.array([0.0, 0.0, -6.0]), np.array([6.0, 0.0, 2.0])
    f = 6.0 / 8.0
    buoyancy = RHO * G * math.pi / 4.0 * d ** 2 * L * f
    weight = m * G * L
    T_B = (weight - buoyancy * f) / 2.0
    T_A = T_B + buoyancy - weight
    middle, turn = 0.5 * (A + B_), math.radians(math.degrees(math.asin(0.8)) - 3.0)
    axis = 0.5 * L * np.array([math.cos(turn), 0.0, math.sin(turn)])
    wet = (ROPE_MASS - RHO * math.pi / 4.0 * ROPE_D ** 2) * G
    path = moordyn_file(
        tmp_path, f"float {d} {m} 1.0 1.0 0.5 0.5",
        "1 float Free " + " ".join(f"{x:.6f}" for x in (*(middle - axis), *(middle + axis))) + " 4 -",
        "1 Fixed 0 0 -20 0 0 0 0\n2 Fixed 6 0 10 0 0 0 0",
        f"1 rope 1 R1A {unstretched(T_A, 14.0, -wet)!r} 20 -\n"
        f"2 rope R1B 2 {unstretched(T_B, 8.0, ROPE_MASS * G)!r} 20 -")
    solved = static_json(path, tmp_path, capsys)
    lines = {line["name"]: line for line in solved["lines"]}
    np.testing.assert_allclose(lines["line1"]["fairlead_tension"], T_A, rtol=1e-6)
    np.testing.assert_allclose(lines["line2"]["fairlead_tension"], T_B, rtol=1e-6)
    np.testing.assert_allclose(solved["bodies"]["rod1"]["position"], A, atol=1e-6 * L)
    np.testing.assert_allclose(solved["points"]["rod1B"]["position"], B_, atol=1e-6 * L)


def pinned_rod_file(tmp_path):
    """A buoyant rod pinned at A = (0, 0, -15), held at B by a vertical line to an anchor 8 m away,
    turned 5 degrees from where it rests: (file, the line's tension T [N], A, B at rest)."""
    d, m, L = 0.5, 50.0, 10.0
    A = np.array([0.0, 0.0, -15.0])
    B_ = A + [8.0, 0.0, 6.0]
    T = (RHO * G * math.pi / 4.0 * d ** 2 * L - m * G * L) / 2.0
    turn = math.asin(0.6) - math.radians(5.0)
    start_b = A + L * np.array([math.cos(turn), 0.0, math.sin(turn)])
    wet = (ROPE_MASS - RHO * math.pi / 4.0 * ROPE_D ** 2) * G
    path = moordyn_file(
        tmp_path, f"float {d} {m} 1.0 1.0 0.5 0.5", "1 float Pinned 0 0 -15 " + " ".join(f"{x:.6f}" for x in start_b)
        + " 4 -", "1 Fixed 8 0 -20 0 0 0 0", f"1 rope 1 R1B {unstretched(T, 11.0, -wet)!r} 20 -")
    return path, T, A, B_


def test_a_pinned_rod_turns_about_its_pin_to_its_closed_form(tmp_path, capsys):
    """A buoyant rod pinned at A = (0, 0, -15), held at B by a vertical line to an anchor 8 m away:
    the line is vertical at B, so B = A + L (cos a, 0, sin a) with cos a = 8/10; submerged, its
    buoyancy and weight act at L/2 and the moment about the pin gives T = (B - W)/2 whatever the
    angle. The file starts it turned by 5 degrees. Tolerance 1e-6 relative: the solver's."""
    L = 10.0
    path, T, A, B_ = pinned_rod_file(tmp_path)
    solved = static_json(path, tmp_path, capsys)
    np.testing.assert_allclose(solved["lines"][0]["fairlead_tension"], T, rtol=1e-6)
    np.testing.assert_allclose(solved["points"]["rod1B"]["position"], B_, atol=1e-6 * L)
    np.testing.assert_allclose(solved["bodies"]["rod1"]["position"], A, atol=1e-9 * L)


def test_moordyns_rod_hanging_between_two_ropes_sits_where_the_elastic_catenary_puts_it(tmp_path, capsys):
    """MoorDyn's RodHanging.txt: a free rod (20 m, heavier than water) hanging from two 450 m ropes
    from Fixed points 900 m apart. Symmetric, so each rope spans 440 m and carries half the rod's
    weight in water at its lower end: MoorPy's elastic catenary of a rope over the solved drop gives
    that vertical force (3 %: it is 3e-3 of the tension, which 45 P1 elements resolve to ~1e-4) and
    both end tensions (1e-3). MoorDyn-C's own start (TmaxIC 0) is no equilibrium: benchmarks/
    moordyn_corpus.py."""
    catenary = pytest.importorskip("moorpy.Catenary").catenary
    solved = static_json(os.path.join(HERE, "data", "moordyn", "RodHanging.txt"), tmp_path, capsys)
    a = np.array(solved["bodies"]["rod1"]["position"])
    np.testing.assert_allclose(a[:2], [-10.0, 0.0], atol=1e-6)
    rope = (77.7066 - RHO * math.pi / 4.0 * 0.09 ** 2) * G
    rod = (77.7066 - RHO * math.pi / 4.0 * 0.25 ** 2) * G * 20.0
    low_h, low_v, high_h, high_v, _ = catenary(440.0, -a[2], 450.0, 384.243e6, rope, CB=0)
    np.testing.assert_allclose(low_v, rod / 2.0, rtol=0.03)
    for line in solved["lines"]:
        np.testing.assert_allclose(line["fairlead_tension"], math.hypot(low_h, low_v), rtol=1e-3)
        np.testing.assert_allclose(line["anchor_tension"], math.hypot(high_h, high_v), rtol=1e-3)


@pytest.mark.parametrize("rod, point, second, length", [
    ("1 float Fixed 0 0 -10 0 0 -5 4 -", "3 Fixed 0 0 -5 0 0 0 0", "R1B", 18.5),
    ("1 float Coupled 0 0 -10 0 0 -5 4 -", "3 Coupled 0 0 -5 0 0 0 0", "R1B", 18.5),
    ("1 float Free 0 0 -8 0 0 -8 0 -", "3 Free 0 0 -8 0 0 0 0", "R1A", 13.0),
], ids=["fixed", "coupled", "zero-length"])
def test_a_fixed_coupled_or_zero_length_rod_is_the_same_scene_written_with_points(rod, point, second, length, tmp_path,
                                                                                 capsys):
    """Two lines from anchors to end B of a fixed or coupled rod solve as two lines to a point there (a
    coupled rod is a coupled body, its end a point of it: equal to round-off); a zero-length free
    rod (NumSegs 0) joining two lines is a massless free point (MoorDyn-C gives it no mass or
    volume): the same string. Equal to 1e-9 of the tension."""
    end, other = "R1B", second
    with_rod = moordyn_file(tmp_path, "float 0.5 50 1 1 0.5 0.5", rod,
                            "1 Fixed -10 0 -20 0 0 0 0\n2 Fixed 10 0 -20 0 0 0 0",
                            f"1 rope 1 {end} {length} 20 -\n2 rope 2 {other} {length} 20 -", name="rod.txt")
    text = with_rod.read_text()
    rows = text.split("---------------------- ROD TYPES")[0] + "---------------------- POINTS" + \
        text.split("---------------------- POINTS")[1]
    rows = rows.replace("2 Fixed 10 0 -20 0 0 0 0", "2 Fixed 10 0 -20 0 0 0 0\n" + point)
    rows = rows.replace(end, "3").replace(other, "3")
    with_points = tmp_path / "points.txt"
    with_points.write_text(rows)
    a, b = static_json(with_rod, tmp_path, capsys), static_json(with_points, tmp_path, capsys)
    tensions = [[line["fairlead_tension"], line["anchor_tension"]] for line in a["lines"]]
    expected = [[line["fairlead_tension"], line["anchor_tension"]] for line in b["lines"]]
    np.testing.assert_allclose(tensions, expected, rtol=1e-9)


def test_a_rod_on_a_free_body_adds_its_weight_and_buoyancy_to_the_body(tmp_path, capsys):
    """A free body (1 t, no volume) carrying a fixed rod (submerged, buoyant) hangs from one vertical
    line: the line holds the body's weight less the rod's net buoyancy, 1e-6 relative."""
    d, m, L = 0.5, 50.0, 4.0
    net = RHO * G * math.pi / 4.0 * d ** 2 * L - m * G * L
    path = moordyn_file(tmp_path, f"float {d} {m} 1 1 0.5 0.5", "1 float Body1 0 0 0 0 0 4 4 -",
                        "1 Fixed 0 0 0 0 0 0 0\n2 Body1 0 0 0 0 0 0 0", "1 rope 2 1 9.9 20 -", depth=30.0)
    text = path.read_text().replace("---------------------- RODS", "---------------------- BODIES ---\n"
                                    "1 free 0 0 -10 0 0 0 1000 0 1e3 0 0 0\n---------------------- RODS")
    path.write_text(text)
    solved = static_json(path, tmp_path, capsys)
    np.testing.assert_allclose(solved["lines"][0]["fairlead_tension"], 1000.0 * G - net, rtol=1e-6)


def test_a_rods_drag_is_the_closed_form_of_a_cylinder_across_and_along_the_flow():
    """Across a uniform current U a submerged rod feels 1/2 rho Cd d L U^2 at its middle; along it,
    1/2 rho A CdEnd U^2 at each submerged end (Rod.cpp's Dp and Dq); half out of the water, half
    the transverse drag at a quarter of its length. 1e-12 relative."""
    rod = Rod("rod1", RodType("r", 0.4, 10.0, 1.2, 1.0, 0.8, 0.5), [0, 0, -10], [0, 0, -6])
    U, zero = 1.5, np.zeros(3)
    force, moment = drag(rod.end_a, rod.end_b, zero, zero, rod, RHO, np.array([U, 0.0, 0.0]))
    across = 0.5 * RHO * 1.2 * 0.4 * 4.0 * U * U
    np.testing.assert_allclose(force, [across, 0.0, 0.0], rtol=1e-12)
    np.testing.assert_allclose(moment, np.cross([0.0, 0.0, 2.0], [across, 0.0, 0.0]), rtol=1e-12)
    force, _ = drag(rod.end_a, rod.end_b, zero, zero, rod, RHO, np.array([0.0, 0.0, U]))
    np.testing.assert_allclose(force, [0.0, 0.0, 2 * 0.5 * RHO * rod.area * 0.8 * U * U], rtol=1e-12)
    half = Rod("rod1", rod.type, [0, 0, -2], [0, 0, 2])
    force, moment = drag(half.end_a, half.end_b, zero, zero, half, RHO, np.array([U, 0.0, 0.0]))
    end_a = 0.0  # the current is across the rod: no axial drag at the submerged end
    np.testing.assert_allclose(force, [across / 2.0 + end_a, 0.0, 0.0], rtol=1e-12)
    np.testing.assert_allclose(moment, np.cross([0.0, 0.0, 1.0], force), rtol=1e-12)


def test_a_rods_mass_matrix_is_a_cylinders_with_its_added_mass_across_and_at_its_ends():
    """A submerged rod along x: across it m L + rho Ca A L, along it m L + 2 rho CaEnd (2/3) pi r^3;
    turned about its end A across the axis (m + rho Ca A) L^3 / 3 + m L r^2 / 4, about its axis
    m L r^2 / 2; symmetric. Half out of the water: the added mass of the submerged half and its one
    submerged end. 1e-12 relative."""
    t = RodType("r", 0.4, 60.0, 1.2, 1.0, 0.8, 0.6)
    rod = Rod("rod1", t, [0, 0, -10], [5, 0, -10])
    M = mass_matrix(rod.end_a, rod.end_b, rod, RHO)
    m, L, r, area = 60.0, 5.0, 0.2, math.pi * 0.04
    across, end = m * L + RHO * 1.0 * area * L, RHO * 0.6 * 2.0 / 3.0 * math.pi * r ** 3
    np.testing.assert_allclose(np.diag(M), [m * L + 2 * end, across, across, m * L * r * r / 2,
                                            (m + RHO * area) * L ** 3 / 3 + m * L * r * r / 4,
                                            (m + RHO * area) * L ** 3 / 3 + m * L * r * r / 4], rtol=1e-12)
    np.testing.assert_allclose(M, M.T, rtol=0, atol=1e-12 * np.abs(M).max())
    np.testing.assert_allclose(M[5, 1], (m + RHO * area) * L ** 2 / 2, rtol=1e-12)  # a y push turns it about z
    half = Rod("rod1", t, [0, 0, -2], [0, 0, 2])
    M = mass_matrix(half.end_a, half.end_b, half, RHO)
    np.testing.assert_allclose(np.diag(M)[:3], [m * 4 + RHO * area * 2, m * 4 + RHO * area * 2, m * 4 + end],
                               rtol=1e-12)


def test_a_rods_buoyancy_is_archimedes_in_and_partly_out_of_the_water():
    """Submerged: rho g A L up at the middle; piercing the surface at a third of its axis: a third
    of that at a sixth of the axis from A. 1e-12 relative."""
    rod = Rod("rod1", RodType("r", 0.4, 0.0), [0, 0, -2], [3, 0, 4])
    force, moment = static_loads(rod.end_a, rod.end_b, rod, RHO, G)
    whole = RHO * G * rod.area * rod.length
    np.testing.assert_allclose(force, [0.0, 0.0, whole / 3.0], rtol=1e-12)
    np.testing.assert_allclose(moment, np.cross((rod.end_b - rod.end_a) / 6.0, force), rtol=1e-12)
    deep = Rod("rod1", rod.type, [0, 0, -20], [3, 0, -14])
    force, moment = static_loads(deep.end_a, deep.end_b, deep, RHO, G)
    np.testing.assert_allclose(force, [0.0, 0.0, whole], rtol=1e-12)
    np.testing.assert_allclose(moment, np.cross((deep.end_b - deep.end_a) / 2.0, force), rtol=1e-12)


def test_a_pinned_rod_s_run_from_its_statics_holds_still(tmp_path):
    """The pinned rod above run for 2 s from its statics: its pin is a stiff spring (``Pin``), so end
    A rises by the pin's reaction B - W - T over its stiffness (1.5e-5 m) and stays there (1e-7 m:
    tensions.csv's 10 digits), and the line's tension stays within 2e-4 of its static value (8e-5
    measured: the pin's give at the first step, which statics does not have, rings the line, whose
    EA / l times it is 14 N)."""
    from cablefem.loads.rod_body import pin_stiffness
    from cablefem.runs.run import run_scene

    path, T, A, B_ = pinned_rod_file(tmp_path)
    scene = load_scene(path)
    rod = scene.bodies["rod1"].rod
    give = (RHO * G * rod.area * rod.length - rod.mass * G - T) / pin_stiffness(rod, G)
    summary = run_scene(scene, tmp_path / "run", duration=2.0, dt=0.05)
    assert summary["completed"]
    table = np.genfromtxt(tmp_path / "run" / "tensions.csv", delimiter=",", names=True)
    for k, axis in enumerate("xyz"):
        assert np.max(np.abs(table[f"bodyrod1{axis}"][1:] - A[k] - (give if axis == "z" else 0.0))) < 1e-7
    force = np.stack([table[f"pointrod1Bf{axis}"] for axis in "xyz"], axis=1)
    assert np.max(np.abs(np.linalg.norm(force, axis=1) - T)) < 2e-4 * T


@pytest.mark.parametrize("rod, line, key, reason", [
    ("1 flaot Free 0 0 -10 0 0 -5 4 -", "1 rope 1 R1A 10 20 -", "RODS.1.RodType", "unknown rod type 'flaot'"),
    ("1 float Free 0 0 -10 0 0 -5 4 -", "1 rope 1 R2A 10 20 -", "LINES.1.AttachB", "no rod 2 in RODS for 'R2A'"),
    ("1 float Free 0 0 -10 0 0 -5 4 -", "1 rope 1 R1C 10 20 -", "LINES.1.AttachB", "a rod end is A or B"),
    ("1 float Free 0 0 -10 0 0 -5 4 -\n2 float Free 0 0 -10 0 0 -5 4 -", "1 rope 1 R1A 10 20 -", "RODS.2",
     "nothing holds it"),
    ("1 float Floating 0 0 -10 0 0 -5 4 -", "1 rope 1 R1A 10 20 -", "RODS.1.Attachment",
     "unknown attachment 'Floating'"),
    ("1 float Body3 0 0 -10 0 0 -5 4 -", "1 rope 1 R1A 10 20 -", "RODS.1.Attachment", "no body 3 in BODIES"),
    ("2 float Free 0 0 -10 0 0 -5 4 -", "1 rope 1 R2A 10 20 -", "RODS.2", "rod IDs must be 1, 2, ..."),
], ids=["rod-type", "no-rod", "no-end", "unheld", "attachment", "no-body", "order"])
def test_bad_rod_input_is_one_line_naming_the_file_the_row_and_the_reason(rod, line, key, reason, tmp_path, capsys):
    """Exit 2, one line: the file, 'line N: KEY' and the reason; nothing written."""
    path = moordyn_file(tmp_path, "float 0.5 50 1 1 0.5 0.5", rod, "1 Fixed 0 0 -20 0 0 0 0", line)
    out = tmp_path / "out.json"
    assert main(["static", str(path), "--json", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and str(path) in err[0] and key in err[0] and reason in err[0], err
    assert not out.exists()


def test_a_free_rod_that_cannot_float_is_refused_with_its_weight_and_buoyancy(tmp_path, capsys):
    """A free rod heavier than the water it displaces (500 kg/m against 201 kg/m), held only by a
    line to an anchor on the seabed: nothing can hold it up (the line lifts at most its own
    buoyancy, none). Exit 2, one line naming the file, its RODS row and its weight."""
    path = moordyn_file(tmp_path, "lead 0.5 500 1 1 0.5 0.5", "1 lead Free 0 0 -10 0 0 -5 4 -",
                        "1 Fixed 0 0 -20 0 0 0 0", "1 rope 1 R1A 10 20 -")
    assert main(["static", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and str(path) in err[0] and "line 14: RODS.1" in err[0], err
    assert f"it weighs {500 * 5 * G:.6g} N" in err[0] and "cannot float" in err[0], err
