"""The bad-input corpus's common parts: a valid TOML scene and MoorDyn file to break, and the
one-line contract every refusal must keep (exit status 2, one line on stderr naming the file
and the reason, no traceback), checked through ``cablefem.cli.main`` as the command runs it."""

import os
from dataclasses import dataclass, field

from cablefem.cli import main

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "examples")

#: a valid scene (loads; not solved by the corpus): every case edits it or adds files beside it
BASE_TOML = """\
name = "corpus"
[environment]
water_density = 1025.0
gravity = 9.81
current = [0.0, 0.0, 0.0]
[line_types.chain]
diameter = 0.3539
mass = 835.4
EA = 3.15e9
damping = 0.001
Cd_normal = 2.5
[[lines]]
name = "line1"
anchor = [-560.0, 0.0, -150.0]
fairlead = [0.0, 0.0, 0.0]
segments = [{ type = "chain", length = 635.0, elements = 40 }]
order = 1
[seabed]
kind = "horizontal"
depth = 150.0
stiffness = 3.0e5
[friction]
model = "isotropic"
mu = 0.3
[solver]
integrator = "bdf2"
dt = 0.01
duration = 10.0
[output]
every = 0.1
"""

with open(os.path.join(EXAMPLES, "chain_polyester.dat"), encoding="utf-8") as handle:
    #: a valid MoorDyn v2 file: chain + polyester joined by a free point, 850 m of water
    BASE_MOORDYN = handle.read()

#: a valid MoorDyn-C seafloor grid 150 m deep (3 x 2 nodes), a level one
GRID_C = "3 2\n-1000 0 1000\n-100 100\n" + "".join(
    f"{x} {y} -150\n" for y in (-100, 100) for x in (-1000, 0, 1000))


def edit(text, edits):
    """``text`` with each ``old -> new`` of ``edits`` (a dict) replaced once; each old must be there."""
    for old, new in edits.items():
        if old not in text:
            raise KeyError(f"not in the base text: {old!r}")
        text = text.replace(old, new, 1)
    return text


@dataclass
class Case:
    """One bad input: files to write in a folder, the command (``{tmp}`` is the folder), the file
    the one line must name (relative to the folder; None: a command-line option) and a piece of
    the reason it must give."""

    name: str
    reason: str
    files: dict = field(default_factory=dict)
    argv: tuple = ("static", "{tmp}/scene.toml")
    file: str | None = "scene.toml"

    def __str__(self):
        return self.name


def toml_case(name, reason, edits=None, text=None, files=None, **more):
    """A Case whose scene.toml is BASE_TOML with ``edits`` (or ``text``), and other files beside it."""
    scene = edit(BASE_TOML, edits or {}) if text is None else text
    return Case(name, reason, files={"scene.toml": scene, **(files or {})}, **more)


def write_files(folder, files):
    """Write the files {relative name: str or bytes} into folder (a pathlib.Path); ``{tmp}`` in a
    text is the folder."""
    for relative, content in files.items():
        path = folder / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, bytes):
            path.write_bytes(content)
        else:
            path.write_text(content.replace("{tmp}", str(folder)), encoding="utf-8")


def run_case(case, folder, capsys):
    """Write the case's files into folder, run ``cablefem`` in this process: (status, stderr lines)."""
    write_files(folder, case.files)
    argv = [arg.replace("{tmp}", str(folder)) for arg in case.argv]
    capsys.readouterr()
    try:
        status = main(argv)
    except SystemExit as stop:  # argparse's own errors
        status = stop.code
    captured = capsys.readouterr()
    assert "Traceback" not in captured.out + captured.err, captured.err
    return status, captured.err.splitlines()


def assert_one_line(case, folder, status, lines):
    """Exit status 2, exactly one line on stderr, naming the case's file, giving its reason."""
    assert status == 2, (status, lines)
    assert len(lines) == 1, lines
    line = lines[0]
    assert line.startswith("cablefem: error: "), line
    if case.file is not None:
        assert str(folder / case.file) in line, line
    assert case.reason in line, line


def assert_refused(case, folder, capsys):
    """Run the case in folder and assert the one-line contract (``assert_one_line``)."""
    status, lines = run_case(case, folder, capsys)
    assert_one_line(case, folder, status, lines)
