"""Reading a scene: the reader a file needs (TOML or a MoorDyn v2 input file), then the
scene-level checks both share (``cablefem.io.checks``)."""

import os

from cablefem.errors import InputError
from cablefem.io.checks import check_scene
from cablefem.io.moordyn_input import read_moordyn
from cablefem.io.toml_scene import TOP_LEVEL_KEYS, parse_toml, read_toml_scene


#: file extensions read as MoorDyn input files; anything else is tried as TOML first
MOORDYN_EXTENSIONS = (".dat", ".txt", ".inp", ".in", ".moordyn")

#: files that are never scenes: what a scene refers to (seabeds, motion tables) or a run writes
NOT_SCENES = {**dict.fromkeys((".vtu", ".vtk", ".vtp", ".stl", ".obj", ".ply", ".msh", ".xyz"),
                              "a mesh or point file: a scene names it in [seabed] file"),
              **dict.fromkeys((".csv", ".parquet"), "a table: a scene names a motion table in [motion] file"),
              **dict.fromkeys((".pvd", ".json", ".png", ".gif"), "an output of cablefem")}


def load_scene(path):
    """The Scene of a TOML scene or MoorDyn v2 input file at ``path`` (str or path-like).

    ``.toml`` is TOML and ``.dat``/``.txt``/``.inp``/``.in`` MoorDyn; any
    other file is TOML when it parses as TOML with a scene's tables, MoorDyn
    otherwise. Every error is an InputError naming the file, the key path and
    the reason on one line. The scene-level checks of ``cablefem.io.checks`` (names,
    problem size, ends against water and seabed, the motion's peak strain) run on
    either kind before the scene is returned.
    """
    path = os.fspath(path)
    try:
        return check_scene(_read_scene(path))
    except InputError as error:
        located = error.within(file=path)
        raise InputError(" ".join(located.reason.split()), key=located.key, file=located.file) from None
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror or error}", file=path) from None


def _read_scene(path):
    """The Scene in the file at ``path`` as its reader gives it (``load_scene`` picks the reader)."""
    if not os.path.exists(path):
        raise InputError("file not found")
    if not os.path.isfile(path):
        raise InputError("not a file")
    if not os.access(path, os.R_OK):
        raise InputError("file not readable")
    extension = os.path.splitext(path)[1].lower()
    if extension in NOT_SCENES:
        raise InputError(f"not a scene ({NOT_SCENES[extension]}); a scene is a TOML file or a MoorDyn v2 "
                         "input file (docs/scene.md)")
    if extension == ".toml":
        data = parse_toml(path)
        if "base" in data and not any(key in data for key in TOP_LEVEL_KEYS):
            raise InputError("a sweep file, not a scene: run it with `cablefem sweep` (docs/sweep.md)")
        return read_toml_scene(path, data)
    if extension in MOORDYN_EXTENSIONS:
        return read_moordyn(path)
    try:
        data = parse_toml(path)
    except InputError:
        data = None
    if data and any(key in data for key in TOP_LEVEL_KEYS):
        return read_toml_scene(path, data)
    return read_moordyn(path)


