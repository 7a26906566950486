"""Hostile scene names, output locations that cannot be written and bad command-line values
(issue 14): each is refused before any work with exit status 2 and one line naming the file (or
the option) and the reason, without a traceback; nothing is written outside --out."""

import os
import subprocess
import sys

import pytest

from bad_input import BASE_TOML, Case, assert_refused, edit, run_case, toml_case

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NAME = 'name = "corpus"'


def named(name, reason, toml_name):
    """A Case loading BASE_TOML with ``name = <toml_name>`` (a TOML value, written as is)."""
    return toml_case(name, reason, {NAME: f"name = {toml_name}"})


def run(name, reason, *options, file="scene.toml", files=None):
    """A Case running ``cablefem run`` on the base scene with command-line ``options``."""
    return Case(name, reason, files={"scene.toml": BASE_TOML, "afile": "not a folder\n", **(files or {})},
                argv=("run", "{tmp}/scene.toml", *options), file=file)


NAMES = [
    named("name-empty", "name: must not be empty", '""'),
    named("name-blank", "name: must not be empty", '"   "'),
    named("name-slash", "must not hold a path separator '/'", '"a/b"'),
    named("name-escape", "must not hold a path separator '/'", '"../../escaped"'),
    named("name-dotdot", "must not start with '.'", '".."'),
    named("name-dot", "must not start with '.'", '"."'),
    named("name-hidden", "must not start with '.'", '".hidden"'),
    named("name-backslash", "must not hold a path separator '\\\\'", '"a\\\\b"'),
    named("name-nul", "must not hold control or invisible characters, got '\\x00'", '"a\\u0000b"'),
    named("name-newline", "got '\\n'", '"a\\nb"'),
    named("name-tab", "got '\\t'", '"a\\tb"'),
    named("name-nel", "got '\\x85'", '"a\\u0085b"'),
    named("name-bidi", "got '\\u202e'", '"abc\\u202Etxt.exe"'),
    named("name-zero-width", "got '\\u200b'", '"a\\u200Bb"'),
    named("name-300", "name: is 300 bytes long, at most 200", f'"{"n" * 300}"'),
    named("name-multibyte", "name: is 202 bytes long", f'"{"é" * 101}"'),
    named("name-number", "name: expected a string", "5"),
    named("name-array", "name: expected a string", "[]"),
    Case("stem-long", "name (from the file name): is 230 bytes long",
         files={"s" * 230 + ".toml": edit(BASE_TOML, {NAME + "\n": ""})},
         argv=("static", "{tmp}/" + "s" * 230 + ".toml"), file="s" * 230 + ".toml"),
    Case("stem-hidden", "name (from the file name): must not start with '.'",
         files={".scene.toml": edit(BASE_TOML, {NAME + "\n": ""})},
         argv=("static", "{tmp}/.scene.toml"), file=".scene.toml"),
    Case("name-escape-run", "name: must not hold a path separator",
         files={"scene.toml": edit(BASE_TOML, {NAME: 'name = "../../escaped"'})},
         argv=("run", "{tmp}/scene.toml", "--out", "{tmp}/out")),
]

OUTPUTS = [
    run("out-is-file", "exists and is not a folder", "--out", "{tmp}/afile", file="afile"),
    run("out-under-file", "lies under", "--out", "{tmp}/afile/sub", file="afile/sub"),
    run("out-deep-under-file", "which is not a folder", "--out", "{tmp}/afile/a/b/c", file="afile/a/b/c"),
    run("out-nul", "not a valid path: it holds a NUL character", "--out", "{tmp}/a\0b", file=None),
    run("out-name-too-long", "File name too long", "--out", "{tmp}/" + "d" * 300, file="d" * 300),
    toml_case("output-dir-is-file", "exists and is not a folder", {"every = 0.1": 'every = 0.1\ndir = "{tmp}/afile"'},
              files={"afile": "x"}, argv=("run", "{tmp}/scene.toml"), file="afile"),
    Case("json-under-file", "afile: exists and is not a folder", files={"scene.toml": BASE_TOML, "afile": "x"},
         argv=("static", "{tmp}/scene.toml", "--json", "{tmp}/afile/out.json"), file="afile"),
    Case("json-is-folder", "is a folder, not a file name", files={"scene.toml": BASE_TOML, "sub/x": ""},
         argv=("static", "{tmp}/scene.toml", "--json", "{tmp}/sub"), file="sub"),
    Case("json-nul", "NUL character", files={"scene.toml": BASE_TOML},
         argv=("static", "{tmp}/scene.toml", "--json", "{tmp}/a\0b/o.json"), file=None),
    Case("png-under-file", "afile: exists and is not a folder", files={"out/tensions.csv": "t,fairlead_tension\n0,1\n", "afile": "x"},
         argv=("plot", "{tmp}/out", "--png", "{tmp}/afile/t.png"), file="afile"),
    Case("plot-not-a-run", "no tensions.csv here", files={"empty/x": ""}, argv=("plot", "{tmp}/empty"),
         file="empty"),
    Case("plot-bad-table", "not a tensions table", files={"out/tensions.csv": "t,fairlead_tension\n0,abc\n"},
         argv=("plot", "{tmp}/out"), file="out/tensions.csv"),
    Case("plot-not-utf8", "not a tensions table", files={"out/tensions.csv": b"t,x\n\xff,\xfe\n"},
         argv=("plot", "{tmp}/out"), file="out/tensions.csv"),
    run("dt-zero", "--dt: must be a number > 0", "--dt", "0", file=None),
    run("dt-negative", "--dt: must be a number > 0", "--dt", "-1", file=None),
    run("dt-nan", "--dt: must be a number > 0", "--dt", "nan", file=None),
    run("dt-inf", "--dt: must be a number > 0", "--dt", "inf", file=None),
    run("dt-word", "argument --dt: invalid float value", "--dt", "abc", file=None),
    run("dt-tiny", "--dt: 10 s in steps of 1e-300 s", "--dt", "1e-300", file=None),
    run("duration-huge", "--duration: 1e+300 s in steps", "--duration", "1e300", file=None),
    Case("scene-missing", "file not found", argv=("static", "{tmp}/absent.toml"), file="absent.toml"),
    Case("scene-folder", "not a file", files={"sub/x": ""}, argv=("run", "{tmp}/sub"), file="sub"),
    Case("command-unknown", "invalid choice: 'simulate'", argv=("simulate",), file=None),
]

CASES = NAMES + OUTPUTS


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_name_or_output_is_refused_in_one_line(case, tmp_path, capsys):
    assert_refused(case, tmp_path, capsys)
    assert not os.path.exists(tmp_path / "afile.pvd") and not os.path.exists(tmp_path / "out" / "corpus.pvd")


def test_an_escaping_name_writes_nothing_anywhere(tmp_path, capsys):
    """``name = "../../escaped"`` once made ``run`` write frames two folders above --out."""
    out = tmp_path / "a" / "b" / "out"
    case = NAMES[[c.name for c in NAMES].index("name-escape-run")]
    status, _ = run_case(case, tmp_path / "a" / "b", capsys)
    assert status == 2
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["a", "b", "scene.toml"]
    assert not out.exists()


def test_run_scene_refuses_a_name_that_would_leave_the_folder(tmp_path):
    """Scenes built in Python are checked by ``run_scene`` itself, before it writes anything."""
    from dataclasses import replace

    from cablefem.errors import InputError
    from cablefem.runs.run import run_scene
    from cablefem.model.builtin import flume_scene

    scene = replace(flume_scene("flat"), name="../escaped")
    with pytest.raises(InputError, match="path separator"):
        run_scene(scene, str(tmp_path / "out"), duration=0.1)
    assert list(tmp_path.iterdir()) == []


def test_output_paths_never_resolve_outside_the_folder(tmp_path):
    from cablefem.errors import OutputError
    from cablefem.io.output import inside

    (tmp_path / "out").mkdir()
    (tmp_path / "elsewhere").mkdir()
    os.symlink(tmp_path / "elsewhere", tmp_path / "out" / "link")
    assert inside(str(tmp_path / "out"), "x.pvd") == str(tmp_path / "out" / "x.pvd")
    for name in ("../x.pvd", "link/x.pvd", "..", "", "a/b.vtu"):
        with pytest.raises(OutputError, match="outside the output folder"):
            inside(str(tmp_path / "out"), name)


SUBPROCESS = [
    ("escaping name", {NAME: 'name = "../../escaped"'}, ["--out", "{tmp}/o"], "path separator"),
    ("EA 1e308", {"EA = 3.15e9": "EA = 1e308"}, ["--out", "{tmp}/o"], "line_types.chain.EA"),
    ("out is a file", {}, ["--out", "{tmp}/scene.toml"], "exists and is not a folder"),
    ("EI on Lagrange elements", {"EA = 3.15e9": "EA = 3.15e9\nEI = 1.0e4"}, [], 'lines[0].element: line type \'chain\' has EI > 0'),
    ("anchor below the seabed", {"anchor = [-560.0, 0.0, -150.0]": "anchor = [-560.0, 0.0, -350.0]"}, [],
     "lines[0].anchor"),
]


@pytest.mark.parametrize("edits, options, reason", [c[1:] for c in SUBPROCESS], ids=[c[0] for c in SUBPROCESS])
def test_bad_input_through_the_real_command(tmp_path, edits, options, reason):
    """The same contract from a real ``python -m cablefem.cli run`` process, run from the repository."""
    (tmp_path / "scene.toml").write_text(edit(BASE_TOML, edits))
    argv = [sys.executable, "-m", "cablefem.cli", "run", str(tmp_path / "scene.toml")]
    argv += [option.replace("{tmp}", str(tmp_path)) for option in options]
    done = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=300)
    lines = done.stderr.splitlines()
    assert done.returncode == 2, done.stderr
    assert "Traceback" not in done.stderr + done.stdout
    assert len(lines) == 1 and str(tmp_path / "scene.toml") in lines[0] and reason in lines[0], lines
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.toml"]  # nothing written, not even seabed.vtu
