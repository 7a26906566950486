"""Scene keys by their documented path (docs/scene.md, docs/sweep.md): ``motion.period``,
``lines[0].segments[0].elements``, ``lines[*].order``, ``line_types.chain.EA``.

A path is a dotted chain of table keys, each optionally followed by array indices ``[k]``
or ``[*]`` (every entry of the array). Paths act on a scene's TOML data (the dict
``cablefem.io.toml_scene.parse_toml`` returns) before it goes through the TOML reader, so a
value set here is checked exactly as if it were written in the scene file. Nothing here knows
the schema: a key the reader does not know yet is set all the same and the reader refuses it.
"""

import copy
import os
import re

from cablefem.errors import InputError

_PART = re.compile(r"([A-Za-z_][A-Za-z0-9_\-]*)((?:\[(?:\d+|\*)\])*)$")
_INDEX = re.compile(r"\[(\d+|\*)\]")
#: the step of ``[*]``: every entry of an array
ALL = Ellipsis


def parse_path(path):
    """The steps of ``path``: a list of str (table keys), int (array indices) and ``ALL`` ([*]).

    ``lines[0].segments[*].elements`` -> ["lines", 0, "segments", ALL, "elements"].
    """
    if not isinstance(path, str) or not path:
        raise InputError(f"a key path must be a non-empty string, got {path!r}", key=str(path))
    steps = []
    for part in path.split("."):
        match = _PART.match(part)
        if not match:
            raise InputError(f"not a key path: '{part}' is not a key with optional [index] or [*]; "
                             "e.g. motion.period, lines[0].segments[*].elements", key=path)
        steps.append(match.group(1))
        steps += [int(k) if k != "*" else ALL for k in _INDEX.findall(match.group(2))]
    return steps


def set_path(data, path, value):
    """Set ``value`` (deep-copied) at ``path`` in the nested dict ``data``, in place.

    Missing tables on the way are created (``solver.dt`` on a scene without [solver]); array
    indices must exist in ``data``; ``[*]`` sets the value in every entry of the array.
    """
    _set(data, parse_path(path), value, path, [])


def _set(node, steps, value, path, done):
    step, rest = steps[0], steps[1:]
    where = _render(done) or "the scene"
    if isinstance(step, str):
        if not isinstance(node, dict):
            raise InputError(f"{where} is not a table, cannot hold key '{step}'", key=path)
        if not rest:
            node[step] = copy.deepcopy(value)
            return
        if step not in node:
            if not isinstance(rest[0], str):
                raise InputError(f"{_hint(node, step)}the base scene has no array '{_render(done + [step])}'",
                                 key=path)
            node[step] = {}
        _set(node[step], rest, value, path, done + [step])
        return
    if not isinstance(node, list):
        raise InputError(f"{where} is not an array, cannot take an index", key=path)
    indices = range(len(node)) if step is ALL else [step]
    if step is not ALL and step >= len(node):
        raise InputError(f"index {step} out of range: {where} has {len(node)} entries", key=path)
    if not node:
        raise InputError(f"{where} is empty: [*] matches nothing", key=path)
    for k in indices:
        if rest:
            _set(node[k], rest, value, path, done + [k])
        else:
            node[k] = copy.deepcopy(value)


def _hint(node, step):
    """A pointer to [moordyn] for a path into [[lines]] or [line_types] of a MoorDyn base."""
    if "moordyn" in node and step in ("lines", "line_types"):
        return ("lines and line types come from the MoorDyn file of [moordyn] (use moordyn.order, "
                "moordyn.elements or scene keys such as solver.dt); ")
    return ""


def get_path(data, path):
    """The value at ``path`` in ``data``; with ``[*]``, the list of the matched values, or the
    one value when they are all equal. None when the path is not there (a default applies)."""
    values = _get(data, parse_path(path))
    if values is None:
        return None
    if len(values) == 1 or all(v == values[0] for v in values[1:]):
        return values[0] if values else None
    return values


def _get(node, steps):
    """Values at ``steps`` below ``node`` (a list, several with [*]); None if missing."""
    if not steps:
        return [node]
    step, rest = steps[0], steps[1:]
    if isinstance(step, str):
        return _get(node[step], rest) if isinstance(node, dict) and step in node else None
    if not isinstance(node, list):
        return None
    if step is not ALL:
        return _get(node[step], rest) if step < len(node) else None
    found = [_get(item, rest) for item in node]
    return None if any(f is None for f in found) else [v for f in found for v in f]


def _render(steps):
    """Steps back to a path string."""
    text = ""
    for step in steps:
        if isinstance(step, str):
            text += f".{step}" if text else step
        else:
            text += "[*]" if step is ALL else f"[{step}]"
    return text


def absolute_files(value, folder):
    """``value`` with every string under a key named ``file`` made absolute against ``folder``
    (a value for ``seabed.file`` given in a sweep file is relative to the sweep file)."""
    if isinstance(value, dict):
        return {k: (_absolute(v, folder) if k == "file" and isinstance(v, str) else absolute_files(v, folder))
                for k, v in value.items()}
    if isinstance(value, list):
        return [absolute_files(v, folder) for v in value]
    return value


def _absolute(name, folder):
    return os.path.normpath(os.path.join(folder, os.path.expanduser(name)))


def is_file_path(path):
    """Whether the key path names a file (its last key is ``file``)."""
    steps = parse_path(path)
    return steps[-1] == "file"


def absolute_value(path, value, folder):
    """The value a sweep sets at ``path``, with its file names made absolute against ``folder``."""
    if is_file_path(path) and isinstance(value, str):
        return _absolute(value, folder)
    return absolute_files(value, folder)
