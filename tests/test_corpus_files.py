"""Bad MoorDyn files, seabed files (grids, meshes, soundings) and motion tables (issue 14): each is
refused before any work with exit status 2 and one line naming the file, the key and the reason,
without a traceback (``bad_input.assert_one_line``)."""

import os
import tempfile

import meshio
import numpy as np
import pytest

from bad_input import BASE_MOORDYN, GRID_C, Case, assert_refused, edit, toml_case

# -------------------------------------------------------------- MoorDyn v2 input files

ROW_CHAIN = "1     chain       1        2        500.0     20       -"
POLYESTER = "polyester  0.160    25.0     2.0e8     -0.8       0.0   2.0   1.0   0.4    0.0"
#: a polyester strain-tension curve file (three header lines, MoorDyn-C's layout) and a SYROPE file
CURVE = "--- polyester ---\nStrain Tension\n(-) (N)\n0.0 0.0\n0.01 5e6\n0.02 1.2e7\n0.05 4e7\n"
SYROPE_FILE = "owc.txt OWC\nLINEAR WCType\n1.25e8 k1\n0.0 k2\n"
OWC = "--- OWC ---\nStrain Tension\n(-) (N)\n0.0 0.0\n0.01 1e6\n0.02 2.2e6\n0.05 6e6\n"


def moordyn(name, reason, edits=None, text=None, files=None, file_name="mooring.dat"):
    """A Case running ``cablefem static`` on the base MoorDyn file with ``edits`` (or ``text``)."""
    content = edit(BASE_MOORDYN, edits or {}) if text is None else text
    return Case(name, reason, files={file_name: content, **(files or {})},
                argv=("static", "{tmp}/" + file_name), file=file_name)


MOORDYN = [
    moordyn("point-id-superscript", "line 11: POINTS.\u00b9: expected a point number",
            {"1      Fixed": "\u00b9      Fixed"}),
    moordyn("point-id-arabic", "expected a point number", {"3      Coupled": "\u0663      Coupled"}),
    moordyn("attach-superscript", "line 17: LINES.1.AttachB: no point '\u00b2'",
            {ROW_CHAIN: ROW_CHAIN.replace("1        2 ", "1        \u00b2 ")}),
    moordyn("numsegs-superscript", "LINES.1.NumSegs: expected a whole number",
            {ROW_CHAIN: ROW_CHAIN.replace("500.0     20", "500.0     2\u00b2")}),
    moordyn("numsegs-arabic", "LINES.1.NumSegs: expected a whole number",
            {ROW_CHAIN: ROW_CHAIN.replace("500.0     20", "500.0     \u0662\u0660")}),
    moordyn("unstrlen-arabic", "LINES.1.UnstrLen: expected a number",
            {ROW_CHAIN: ROW_CHAIN.replace("500.0", "\u0665\u0660\u0660.0")}),
    moordyn("unstrlen-underscore", "LINES.1.UnstrLen: expected a number", {ROW_CHAIN: ROW_CHAIN.replace("500.0", "5_00.0")}),
    moordyn("numsegs-1e8", "LINES.1.NumSegs: 100000000 is beyond the sane limit",
            {ROW_CHAIN: ROW_CHAIN.replace("500.0     20", "500.0     100000000")}),
    moordyn("numsegs-float", "LINES.1.NumSegs: expected a whole number",
            {ROW_CHAIN: ROW_CHAIN.replace("500.0     20", "500.0     1e20")}),
    moordyn("unstrlen-huge", "LINES.1.UnstrLen: 1e+300 m is beyond", {ROW_CHAIN: ROW_CHAIN.replace("500.0", "1e300")}),
    moordyn("EA-1e308", "line 6: LINE TYPES.chain.EA: 1e+308 N is beyond the sane limit", {"1.23e9": "1e308"}),
    moordyn("EA-inf", "LINE TYPES.chain.EA: must be finite", {"1.23e9": "inf   "}),
    moordyn("EA-dynamic-below-static", "the dynamic stiffness must exceed the static EA", {"1.23e9": "1.23e9|5e8"}),
    moordyn("diam-nan", "LINE TYPES.chain.Diam: must be finite", {"0.216 ": "nan   "}),
    moordyn("diam-huge", "LINE TYPES.chain.Diam: 1000 m is beyond", {"0.216 ": "1e3   "}),
    moordyn("mass-negative", "LINE TYPES.chain.MassDen: must be > 0", {"286.6": "-286.6"}),
    moordyn("ba-huge", "LINE TYPES.chain.BA/-zeta (beta)", {"1.23e9    -0.8": "1.23e9    1e300"}),
    moordyn("depth-huge", "line 21: OPTIONS.WtrDpth: 1e+300 m is beyond", {"850.0     WtrDpth": "1e300     WtrDpth"}),
    moordyn("kbot-huge", "line 22: OPTIONS.kBot", {"3.0e6     kBot": "1e300     kBot"}),
    moordyn("kbot-negative", "line 22: OPTIONS.kBot: must be > 0", {"3.0e6     kBot": "-3.0e6    kBot"}),
    moordyn("gravity-huge", "OPTIONS.g: 1e+10", {"850.0     WtrDpth": "850.0     WtrDpth\n1e10      g"}),
    moordyn("dtm-negative", "OPTIONS.dtM: must be > 0", {"0.0002    dtM": "-0.0002   dtM"}),
    moordyn("tmax-huge", "OPTIONS.TMax: 1e+300 s in steps", {"850.0     WtrDpth": "850.0     WtrDpth\n1e300     TMax"}),
    moordyn("point-x-huge", "line 11: POINTS.1.X: -1e+300 m is beyond", {"-1130.0": "-1e300 "}),
    moordyn("anchor-below-seabed", "line 11: POINTS.1: the anchor lies 50 m below the seabed",
            {"850.0     WtrDpth": "800.0     WtrDpth"}),
    moordyn("fairlead-below-seabed", "line 13: POINTS.3: the fairlead lies 50 m below the seabed",
            {"-58.0     0.0   -14.0": "-58.0     0.0   -900.0"}),
    moordyn("line-id-control", "must not hold control or invisible characters",
            {ROW_CHAIN: ROW_CHAIN.replace("1     chain", "1\x01    chain")}),
    moordyn("binary", "not a MoorDyn input file", text=b"\xff\xfe\x00\x01binary"),
    moordyn("empty", "not a MoorDyn v2 input file", text=""),
    moordyn("title-only", "not a MoorDyn v2 input file", text="--- MoorDyn Input File ---\njust a title\n"),
    moordyn("attachment", "line 13: POINTS.3.Attachment: unknown attachment 'Floating'",
            {"3      Coupled": "3      Floating"}),
    moordyn("duplicate-point", "line 12: POINTS.1: duplicate point ID", {"2      Free": "1      Free"}),
    moordyn("short-row", "line 17: LINES: expected 6 columns", {ROW_CHAIN: "1     chain       1        2"}),
    moordyn("body-singular-inertia", "line 9: BODIES.1: a free body needs three moments of inertia > 0",
            {"---------------------- POINTS": "---------------------- BODIES ---\n1 free 0 0 -5 0 0 0 1e4 0 0 0 0 0\n"
             "---------------------- POINTS"}),
    moordyn("unused-point", "line 14: POINTS.4: no line uses this point",
            {"-14.0    0      0        0     0\n": "-14.0    0      0        0     0\n4 Free 0 0 -10 0 0 0 0\n"}),
    moordyn("rods", "line 17: RODS: expected 11 columns (ID RodType Attachment Xa Ya Za Xb Yb Zb NumSegs Outputs)",
            {"---------------------- LINES": "---------------------- RODS "
            "------\nID RodType\n(#) (name)\n1 rod 0 0 0 1 1 1 10 -\n---------------------- LINES"}),
    moordyn("seafloor-missing", "line 21: OPTIONS.SeafloorFile: file not found",
            {"850.0     WtrDpth": "bathy.txt SeafloorFile"}),
    moordyn("seafloor-hole", "line 21: OPTIONS.SeafloorFile", {"850.0     WtrDpth": "bathy.txt SeafloorFile"},
            files={"bathy.txt": GRID_C.rsplit("\n", 2)[0] + "\n"}),
    moordyn("seafloor-above-water", "line 21: OPTIONS.SeafloorFile: the seabed is 10 m above",
            {"850.0     WtrDpth": "bathy.txt SeafloorFile"}, files={"bathy.txt": GRID_C.replace("-150", "10")}),
    moordyn("hidden-file-name", "name (from the file name): must not start with '.'", file_name=".mooring.dat"),
    moordyn("long-file-name", "name (from the file name): is 240 bytes long", file_name="m" * 240 + ".dat"),
    *[moordyn(name, reason, {POLYESTER: POLYESTER.replace("2.0e8     -0.8", entry)}, files=files)
      for name, reason, entry, files in (
          ("curve-missing", "line 7: LINE TYPES.polyester.EA: file not found", "poly.txt  -0.8", {}),
          ("curve-not-monotonic", "LINE TYPES.polyester.EA (poly.txt).tension: not monotonic",
           "poly.txt  -0.8", {"poly.txt": CURVE.replace("1.2e7", "4e6")}),
          ("curve-row", "line 7: LINE TYPES.polyester.EA: poly.txt line 5: expected two numbers 'x y', got '0.01'",
           "poly.txt  -0.8", {"poly.txt": CURVE.replace("0.01 5e6", "0.01")}),
          ("ba-curve-at-zero", "BA/-zeta (ba.txt).tension: the tension at zero strain_rate must be 0",
           "poly.txt  ba.txt", {"poly.txt": CURVE, "ba.txt": "h\nh\nh\n-0.1 -2e4\n-0.01 5e3\n0.1 2e4\n"}),
          ("four-bars", "line 7: LINE TYPES.polyester.EA: at most 3 values separated by '|'", "2e8|3e8|1e8|0.4 -0.8", {}),
          ("ba-bars", "line 7: LINE TYPES.polyester.BA/-zeta: '1|2|3': BA has at most", "2e8|3e8|0.4 1|2|3", {}),
          ("syrope-two", "a SYROPE entry is 'SYROPE:file|EA_Dc|EA_D_Lm'", "SYROPE:s.dat|1e8 1e9", {}),
          ("syrope-file-k1", "line 7: LINE TYPES.polyester.EA: s.dat: missing k1", "SYROPE:s.dat|1.5e8|20 5e10",
           {"s.dat": "poly.txt OWC\nLINEAR WCType\n0.0 k2\n", "poly.txt": CURVE}),
          ("syrope-without-ic", "line 18: LINES.2: line type 'polyester' is a SYROPE rope: its segment needs its "
           "initial condition", "SYROPE:s.dat|1.5e8|20 5e10", {"s.dat": SYROPE_FILE, "owc.txt": OWC}),
      )],
    moordyn("ic-without-syrope", "line 22: SYROPE IC: a SYROPE IC section, but no line type is a SYROPE rope",
            {"---------------------- OPTIONS": "--- SYROPE IC ---\nLine Tmax0 Tmean0\n(-) (N) (N)\n2 1e6 5e5\n"
             "---------------------- OPTIONS"}),
    moordyn("ic-unknown-line", "SYROPE IC.7: no line '7' in LINES",
            {POLYESTER: POLYESTER.replace("2.0e8     -0.8", "SYROPE:s.dat|1.5e8|20 5e10"),
             "---------------------- OPTIONS": "--- SYROPE IC ---\nLine Tmax0 Tmean0\n(-) (N) (N)\n7 1e6 5e5\n"
             "---------------------- OPTIONS"}, files={"s.dat": SYROPE_FILE, "owc.txt": OWC}),
]

# -------------------------------------------------------------- seabed files behind a TOML scene

SEABED = 'kind = "horizontal"\ndepth = 150.0'


def seabed(name, reason, kind, file_name, content):
    """A Case whose scene.toml reads its seabed (``kind``) from ``file_name`` holding ``content``."""
    return toml_case(name, reason, {SEABED: f'kind = "{kind}"\nfile = "{file_name}"'},
                     files={file_name: content})


def grid_f(rows="0 150 150 150\n100 150 150 150\n", x="-1000 0 1000", nx="3", ny="2"):
    """A MoorDyn-F/MoorPy bathymetry file (depths positive down) with the given parts."""
    return f"--- MoorDyn Bathymetry Input File ---\nnGridX {nx}\nnGridY {ny}\n{x}\n{rows}"


def _obj(vertices, faces):
    """A Wavefront .obj text of vertices (rows of 3 numbers as text) and faces (1-based)."""
    return "".join(f"v {v}\n" for v in vertices) + "".join(f"f {f}\n" for f in faces)


SQUARE = ["-2000 -1000 -150", "2000 -1000 -150", "2000 1000 -150", "-2000 1000 -150"]


def _truncated_vtu():
    """The first half of a valid .vtu surface: meshio calls exit() on it."""
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "s.vtu")
        points = np.array([[float(c) for c in v.split()] for v in SQUARE])
        meshio.write(path, meshio.Mesh(points, [("triangle", np.array([[0, 1, 2], [0, 2, 3]]))]))
        data = open(path, "rb").read()
    return data[:len(data) // 2]


GRID_ROWS = GRID_C.splitlines(keepends=True)
SEABEDS = [
    seabed("grid-hole", "bathy.txt", "grid", "bathy.txt", "".join(GRID_ROWS[:-1])),
    seabed("grid-not-number", "'abc' is not a number", "grid", "bathy.txt", GRID_C.replace("1000 100 -150", "1000 100 abc")),
    seabed("grid-nx-superscript", "not a bathymetry grid", "grid", "bathy.txt", GRID_C.replace("3 2", "\u00b3 2", 1)),
    seabed("grid-nx-arabic", "not a bathymetry grid", "grid", "bathy.txt", GRID_C.replace("3 2", "\u0663 2", 1)),
    seabed("grid-z-huge", "beyond the sane limit", "grid", "bathy.txt", GRID_C.replace("1000 100 -150", "1000 100 -1e300")),
    seabed("grid-z-nan", "not a finite number", "grid", "bathy.txt", GRID_C.replace("1000 100 -150", "1000 100 nan")),
    seabed("grid-z-underscore", "is not a number", "grid", "bathy.txt", GRID_C.replace("1000 100 -150", "1000 100 -1_50")),
    seabed("grid-x-decreasing", "must increase strictly", "grid", "bathy.txt", GRID_C.replace("-1000 0 1000", "0 -1000 1000")),
    seabed("grid-node-twice", "is given twice", "grid", "bathy.txt", GRID_C.replace("1000 100 -150", "1000 -100 -150")),
    seabed("grid-off-grid", "is not on the grid", "grid", "bathy.txt", GRID_C.replace("1000 100 -150", "999 100 -150")),
    seabed("grid-short", "found 3 non-blank lines", "grid", "bathy.txt", "3 2\n-1000 0 1000\n-100 100\n"),
    seabed("grid-empty", "not a bathymetry grid", "grid", "bathy.txt", ""),
    seabed("grid-binary", "not a bathymetry grid", "grid", "bathy.txt", b"\x00\xff\xfe binary"),
    seabed("grid-nx-huge", "beyond the sane limit", "grid", "bathy.txt", GRID_C.replace("3 2", "1000000000 2", 1)),
    seabed("grid-level-above-water", "seabed.file: the seabed is 5 m above", "grid", "bathy.txt",
           GRID_C.replace("-150", "5")),
    seabed("grid-f-nx-word", "nGridX must be an integer", "grid", "bathy.txt", grid_f(nx="three")),
    seabed("grid-f-hole", "hole: no depth", "grid", "bathy.txt", grid_f(rows="0 150 150\n100 150 150 150\n")),
    seabed("grid-f-extra", "4 depths, but nGridX = 3", "grid", "bathy.txt", grid_f(rows="0 150 150 150 150\n100 1 1 1\n")),
    seabed("grid-f-y-twice", "is given twice", "grid", "bathy.txt", grid_f(rows="0 150 150 150\n0 150 150 150\n")),
    seabed("grid-f-not-number", "is not a number", "grid", "bathy.txt", grid_f(rows="0 150 deep 150\n100 150 150 150\n")),
    seabed("points-two", "need at least 3 points", "points", "s.xyz", "0 0 -150\n1 0 -150\n"),
    seabed("points-collinear", "lie on one line", "points", "s.xyz", "0 0 -150\n1 0 -150\n2 0 -150\n"),
    seabed("points-same-xy", "give the same (x, y)", "points", "s.xyz", "0 0 -150\n0 0 -140\n1 1 -150\n"),
    seabed("points-word", "expected three numbers", "points", "s.xyz", "0 0 -150\n1 0 deep\n0 1 -150\n"),
    seabed("points-four", "got 4 fields", "points", "s.xyz", "0 0 -150 1\n1 0 -150\n0 1 -150\n"),
    seabed("points-nan", "not a finite number", "points", "s.xyz", "0 0 nan\n1 0 -150\n0 1 -150\n"),
    seabed("points-huge", "beyond the sane limit", "points", "s.xyz", "0 0 -1e300\n1 0 -150\n0 1 -150\n"),
    seabed("points-arabic", "expected three numbers", "points", "s.xyz", "0 0 -\u0661\u0665\u0660\n1 0 -150\n0 1 -150\n"),
    seabed("points-empty", "need at least 3 points", "points", "s.xyz", "# nothing\n"),
    seabed("points-above-water", "seabed.file: the seabed is 5 m above", "points", "s.xyz",
           "-2000 -1000 5\n2000 -1000 5\n2000 1000 5\n-2000 1000 5\n"),
    seabed("mesh-garbage-stl", "cannot read as a surface mesh", "mesh", "s.stl", "this is not an STL\n"),
    seabed("mesh-empty-stl", "no triangles or quads", "mesh", "s.stl", ""),
    seabed("mesh-junk-vtu", "cannot read as a surface mesh", "mesh", "s.vtu", b"\x00\x01junk" * 50),
    seabed("mesh-truncated-vtu", "cannot read as a surface mesh", "mesh", "s.vtu", _truncated_vtu()),
    seabed("mesh-no-faces", "no triangles or quads", "mesh", "s.obj", _obj(SQUARE, [])),
    seabed("mesh-nan", "non-finite coordinate", "mesh", "s.obj", _obj(SQUARE[:3] + ["nan 1000 -150"], ["1 2 3", "1 3 4"])),
    seabed("mesh-huge", "beyond the sane limit", "mesh", "s.obj", _obj(SQUARE[:3] + ["-1e300 1000 -150"], ["1 2 3", "1 3 4"])),
    seabed("mesh-degenerate", "is degenerate", "mesh", "s.obj", _obj(SQUARE, ["1 2 2", "1 3 4"])),
    seabed("mesh-above-water", "seabed.file: the seabed is 5 m above", "mesh", "s.obj",
           _obj([v.replace("-150", "5") for v in SQUARE], ["1 2 3", "1 3 4"])),
]

# -------------------------------------------------------------- motion tables


def table(name, reason, content, ramp=""):
    """A Case whose scene.toml moves the fairlead along motion.csv holding ``content``."""
    return toml_case(name, reason, {"[solver]": f'[motion]\nkind = "table"\nfile = "motion.csv"\n{ramp}[solver]'},
                     files={"motion.csv": content} if content is not None else {})


TABLES = [
    table("table-word", "motion.csv line 3: expected numbers", "t,x,y,z\n0,0,0,0\n1,one,0,0\n"),
    table("table-arabic", "motion.csv line 2: expected numbers", "0,0,0,0\n\u0661,1,0,0\n"),
    table("table-underscore", "expected numbers", "0,0,0,0\n1_0,1,0,0\n"),
    table("table-backwards", "times must strictly increase", "0,0,0,0\n1,1,0,0\n0.5,2,0,0\n"),
    table("table-one-row", "needs at least 2 rows", "0,0,0,0\n"),
    table("table-five-columns", "expected 4 columns", "0,0,0,0,0\n1,1,0,0,0\n"),
    table("table-nan", "values must be finite", "0,0,0,0\n1,nan,0,0\n"),
    table("table-inf", "values must be finite", "0,0,0,0\ninf,1,0,0\n"),
    table("table-not-utf8", "cannot read", b"0,0,0,0\n1,\xff,0,0\n"),
    table("table-missing", "motion.file: file not found", None),
    table("table-empty", "needs at least 2 rows", ""),
    table("table-header-only", "needs at least 2 rows", "t,x,y,z\n"),
    table("table-huge", "beyond the sane limit", "0,0,0,0\n1,1e300,0,0\n"),
    table("table-strain", "motion.file: moves the fairlead of line 'line1' by [300, 0, 0] m at t = 5 s",
          "0,0,0,0\n5,300,0,0\n10,0,0,0\n"),
    table("table-speed", "motion.file: the fairlead's peak speed", "0,0,0,0\n1e-9,1,0,0\n"),
    table("table-ramp", "motion.ramp: the fairlead's peak", "0,15,0,0\n10,15,0,0\n", ramp="ramp = 1e-9\n"),
    toml_case("table-folder", "motion.file: not a file", {"[solver]": '[motion]\nkind = "table"\nfile = "sub"\n[solver]'},
              files={"sub/x": ""}),
]

CASES = MOORDYN + SEABEDS + TABLES


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_file_is_refused_in_one_line(case, tmp_path, capsys):
    assert_refused(case, tmp_path, capsys)


def test_the_corpus_bases_are_valid(tmp_path):
    from cablefem.io import load_scene

    (tmp_path / "mooring.dat").write_text(BASE_MOORDYN)
    (tmp_path / "grid.txt").write_text(GRID_C)
    (tmp_path / "f.txt").write_text(grid_f())
    (tmp_path / "s.obj").write_text(_obj(SQUARE, ["1 2 3", "1 3 4"]))
    assert load_scene(tmp_path / "mooring.dat").lines[0].name == "line1+2"
    for kind, name in (("grid", "grid.txt"), ("grid", "f.txt"), ("mesh", "s.obj")):
        case = seabed("valid", "", kind, name, None)
        (tmp_path / "scene.toml").write_text(case.files["scene.toml"])
        assert load_scene(tmp_path / "scene.toml").seabed.describe().startswith("horizontal")
