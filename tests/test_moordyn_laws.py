"""MoorDyn files with what issue 36 (items 3 and 5) reads: nonlinear and viscoelastic EA and BA, SYROPE
and its IC section, the points' FX FY FZ, the v1 LINES columns, g = 0, and the free body of
MoorDyn's body_tests/bodyDrag.txt, each against a closed form or the MoorDyn-C library."""

import math
import os
import shutil

import numpy as np
import pytest

from cablefem.io import load_scene
from cablefem.statics.scene import static_lines
from verification.axial_laws.moordyn_side import case_folder, moordyn_run

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "moordyn")


def static_fairlead(scene):
    """The first line's fairlead force (3,) [N] and fairlead position (3,) of ``cablefem static``."""
    systems, results, _, _ = static_lines(scene)
    system, X = systems[0], results[0].X
    return -system.residual(X)[system.fem.fairlead_dof], X[system.fem.fairlead_dof]


def static_anchor(scene):
    """The first line's force on its anchor (3,) [N] and its free end's position (3,)."""
    systems, results, _, _ = static_lines(scene)
    system, X = systems[0], results[0].X
    return -system.residual(X)[system.fem.anchor_dof], X[system.fem.fairlead_dof]


@pytest.mark.parametrize("case, third_line", [("linear_wc", False), ("quadratic_wc", True), ("exp_wc", True)])
def test_syrope_statics_equal_moordyn_c_s_initial_condition(case, third_line, tmp_path):
    # MoorDyn-C's IC of its own SYROPE cases (one 1 m segment, TmaxIC 1 s against a slow strain that
    # relaxes in ~300 s): the slow strain of Tmean0 on the working curve of Tmax0. The quadratic
    # and exponential working curves need owc.dat's (0, 0) row in both codes (a third header line:
    # verification/axial_laws/moordyn_side.py); agreement to 1e-9 (both 1e-15 as measured)
    path = case_folder(case, tmp_path, owc_header=third_line)
    scene = load_scene(path)
    law = scene.lines[0].segments[0].type.axial
    assert law.kind == "syrope" and law.syrope.form == case.split("_")[0]
    assert scene.lines[0].segments[0].syrope == (1.3886e6, 4.339e5)
    force, _ = static_fairlead(scene)
    _, peer = moordyn_run(path, 0.0, 1.0, 0.0, 1.0)
    assert np.linalg.norm(force) == pytest.approx(peer[0], rel=1e-9)


def test_moordyn_s_own_owc_file_is_read_as_moordyn_c_reads_it(tmp_path):
    # owc.dat has two header lines; MoorDyn-C skips three of a curve file, so does cablefem, and says so
    scene = load_scene(case_folder("linear_wc", tmp_path))
    assert any("line 3 of owc.dat holds numbers" in note for note in scene.notes)
    curve = scene.lines[0].segments[0].type.axial.curve
    assert curve.x[:2] == (0.0, 2.06897e-03)  # (0, 0) is cablefem's own start of a table, not the file's row


def test_visco_txt_is_a_load_dependent_viscoelastic_rope_relaxed_in_statics(tmp_path):
    # polyester/visco.txt: 1.424e+08|1.586e+08|0.4 and 4E9|11E6, g = 0, water density 0 (its last
    # WtrDnsty), its fairlead moved from 2 m (100 % strain, refused) to 1.02 m: statics relax the
    # slow strain, T = EA_s e
    scene = load_scene(case_folder("visco", tmp_path))
    law = scene.lines[0].segments[0].type.axial
    assert (law.kind, law.static_EA, law.dynamic_EA, law.dynamic_slope) == ("viscoelastic", 1.424e8, 1.586e8, 0.4)
    assert (law.damping, law.dynamic_damping) == (4e9, 11e6)
    assert (scene.environment.gravity, scene.environment.water_density) == (0.0, 0.0)
    force, _ = static_fairlead(scene)
    assert np.linalg.norm(force) == pytest.approx(1.424e8 * 0.02, rel=1e-12)


def test_curve_files_for_ea_and_ba_hang_the_pendulum_on_the_table(tmp_path):
    text = open(os.path.join(DATA, "pendulum.txt"), encoding="utf-8").read()
    (tmp_path / "ea.txt").write_text("--- EA ---\nStrain Tension\n(-) (N)\n0.0 0.0\n0.01 5e6\n0.02 2.0e7\n")
    (tmp_path / "ba.txt").write_text("--- BA ---\nRate Tension\n(1/s) (N)\n0.01 1e3\n0.1 5e3\n")
    text = text.replace("main       0.1     7.85398    1.0E9      -0.01", "main       0.1     7.85398    ea.txt     ba.txt")
    (tmp_path / "pendulum.txt").write_text(text)
    scene = load_scene(tmp_path / "pendulum.txt")
    law = scene.lines[0].segments[0].type.axial
    assert law.kind == "table" and law.curve.y[-1] == 2.0e7
    assert law.damping_curve.x == (0.0, 0.01, 0.1)  # (0, 0) before a table of positive rates
    force, end = static_anchor(scene)
    weight = 1e5 * 9.80665  # the line is as dense as the water: the point's weight alone
    assert np.linalg.norm(force) == pytest.approx(weight, rel=1e-8)  # 7.85398 kg/m, not 7.8539816
    strain = float(np.interp(weight, law.curve.y, law.curve.x))
    assert -end[2] == pytest.approx(100.5 * (1.0 + strain), rel=1e-9)


def test_a_free_point_s_fx_fy_fz_pulls_the_pendulum_aside(tmp_path):
    # pendulum.txt's 1e5 kg free point with FX = 2e5 N, FY = -1e5 N in a row of 12: the weightless
    # line stands along (FX, FY, -W), its tension sqrt(FX^2 + FY^2 + W^2), its length L (1 + T / EA)
    text = open(os.path.join(DATA, "pendulum.txt"), encoding="utf-8").read()
    text = text.replace("2     Free      10      0       -100    1E5    0       0      0",
                        "2     Free      10      0       -100    1E5    0       2e5  -1e5  0   0      0")
    text = text.replace("Mass   Volume  CdA    Ca", "Mass   Volume  FX FY FZ CdA    Ca")
    (tmp_path / "pendulum.txt").write_text(text)
    scene = load_scene(tmp_path / "pendulum.txt")
    force, end = static_anchor(scene)
    pull = np.array([2e5, -1e5, -1e5 * 9.80665])
    tension = float(np.linalg.norm(pull))
    np.testing.assert_allclose(force, pull, rtol=1e-8)  # the line: 7.85398 kg/m against rho pi d^2 / 4 = 7.8539816
    np.testing.assert_allclose(end, pull / tension * 100.5 * (1.0 + tension / 1e9), rtol=1e-9)


def test_a_coupled_point_s_fx_is_noted_and_changes_nothing(tmp_path):
    text = open(os.path.join(DATA, "lines.txt"), encoding="utf-8").read()
    rows = [row for row in text.splitlines() if " Vessel " in row]
    fields = rows[0].split()
    text = text.replace(rows[0], " ".join(fields[:7] + ["5e5", "0", "0"] + fields[7:]))
    (tmp_path / "lines.txt").write_text(text)
    shutil.copy(os.path.join(DATA, "lines.txt"), tmp_path / "original.txt")
    scene = load_scene(tmp_path / "lines.txt")
    assert any("FX FY FZ of a point whose motion is given ignored" in note for note in scene.notes)
    assert np.allclose(static_fairlead(scene)[0], static_fairlead(load_scene(tmp_path / "original.txt"))[0],
                       rtol=0, atol=0)


def test_v1_lines_columns_are_read_as_their_header_names_them(tmp_path):
    text = open(os.path.join(DATA, "pendulum.txt"), encoding="utf-8").read()
    v1 = text.replace("ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs",
                      "Line LineType   UnstrLen NumSegs  NodeAnch  NodeFair Flags/Outputs")
    v1 = v1.replace("1     main       1        2         100.5     20      -",
                    "1     main       100.5    20        1         2       -")
    (tmp_path / "v1.txt").write_text(v1)
    (tmp_path / "v2.txt").write_text(text)
    a, b = load_scene(tmp_path / "v1.txt"), load_scene(tmp_path / "v2.txt")
    assert any("MoorDyn v1 columns" in note for note in a.notes)
    assert a.lines[0].ends == b.lines[0].ends and a.lines[0].segments == b.lines[0].segments


def test_body_drag_s_free_body_hangs_below_its_anchor(tmp_path):
    # MoorDyn's body_tests/bodyDrag.txt: a 10 kg body (no volume) on a 4.5 m spring (EA 500 N) whose
    # other end is fixed 5 m below the body. Above the anchor its weight and the line both pull it
    # down: no equilibrium within Newton's reach, and on the way the slack line gives the balance no
    # stiffness (a Newton step of ~1e6 m). The pseudo-transient fallback finds where it hangs below
    # the anchor: one element, half the line's submerged weight on the body's end, T = W_b + w L / 2
    path = os.path.join(DATA, "laws", "bodyDrag.txt")
    scene = load_scene(path)
    systems, results, _, network = static_lines(scene)
    w = (10.0 - 1025.0 * math.pi * 0.1 ** 2 / 4) * 9.81
    tension = 10.0 * 9.81 + 0.5 * w * 4.5
    assert network.poses["body1"][2] == pytest.approx(-5.0 - 4.5 * (1.0 + tension / 500.0), rel=1e-9)


def test_rotating_body_with_g_0_is_read(tmp_path):
    scene = load_scene(os.path.join(DATA, "laws", "rotatingBody.txt"))
    assert scene.environment.gravity == 0.0
