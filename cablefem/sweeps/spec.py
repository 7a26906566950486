"""The sweep file (docs/sweep.md): a base scene, the keys to vary and how they combine, expanded
into cases, each validated by the TOML scene reader before anything runs.

Every case is the base scene's TOML data with values set at key paths (``cablefem.sweeps.paths``):
first the sweep's [set], then its block's [set], then one value of every axis of the block. The
axes of a block are its [axes] keys (each its own axis, or all one axis with ``combine = "zip"``),
each [[zip]] group (keys varied together) and its [[cases]] list (one axis whose values are whole
assignments); a block's cases are the product of its axes in the order the block gives them (the
first varies slowest), and the sweep's cases are its blocks' cases one after the other. Two cases
that are the same run (the same identity, ``identity``) run once and share a folder. Three keys
are not scene keys: ``kind`` (static | dynamic | ``module:function``), ``alone`` (run with no
other case of the sweep at the same time) and ``tag.NAME`` (a label that becomes a column of the
table).
"""

import copy
import hashlib
import importlib
import itertools
import json
import os
from dataclasses import dataclass, field

from cablefem.errors import InputError
from cablefem.io import validate as v
from cablefem.sweeps.paths import absolute_value, get_path, is_file_path, parse_path, set_path

SWEEP_KEYS = ("base", "kind", "combine", "out", "stats_from", "set", "axes", "zip", "cases", "blocks",
              "fatigue")
BLOCK_KEYS = ("set", "axes", "combine", "zip", "cases")
COMBINE = ("product", "zip")
KINDS = ("static", "dynamic")
RUN_KEYS = ("kind", "alone")
#: DNV-OS-E301 S-N curve of studless chain: N = a_D * S^-m, S the stress range in MPa
DNV_STUDLESS = {"a_D": 6.0e10, "m": 3.0}
MOORDYN_EXTENSIONS = (".dat", ".txt", ".inp", ".in", ".moordyn")


@dataclass(frozen=True)
class Case:
    """One run of a sweep: its position, identity (a hash of kind and resolved scene data), kind,
    whether it runs alone, the scene's TOML data, its parameters (key path -> value, for the
    table) and tags (name -> label)."""

    index: int
    case_id: str
    kind: str
    alone: bool
    data: dict
    params: dict
    tags: dict
    label: str


@dataclass
class Sweep:
    """A sweep ready to run: where it came from (``source``: the sweep file, or None from Python),
    the base scene file, the default output folder, the cases, and the post-processing settings
    (``stats_from`` [s]; ``fatigue``: area [m^2] or {line type: area}, a_D, m; or None)."""

    source: str | None
    base: str
    out: str
    cases: list
    stats_from: float = 0.0
    fatigue: dict | None = None
    notes: list = field(default_factory=list)


def read_sweep(path):
    """The Sweep of the sweep file at ``path``: every case expanded and validated."""
    from cablefem.io.toml_scene import parse_toml

    path = os.path.abspath(path)
    try:
        if not os.path.isfile(path):
            raise InputError("file not found" if not os.path.exists(path) else "not a file")
        spec = parse_toml(path)
    except InputError as error:
        raise error.within(file=path) from None
    return build_sweep(spec, os.path.dirname(path), source=path)


def build_sweep(spec, folder, source=None):
    """The Sweep of a sweep specification (the sweep file's dict); relative paths (base, files set
    by the sweep) resolve against ``folder``; errors name ``source`` (the file, or None)."""
    try:
        v.check_keys(spec, SWEEP_KEYS, "", required=("base",))
        base = v.existing_file(spec["base"], "base", folder)
        kind = _kind(spec.get("kind", "dynamic"), "kind")
        combine = v.choice(COMBINE)(spec.get("combine", "product"), "combine")
        out = v.text(spec.get("out", "sweep-out"), "out")
        stats_from = v.non_negative(spec.get("stats_from", 0.0), "stats_from")
        fatigue = _fatigue(spec["fatigue"]) if "fatigue" in spec else None
        top_set = _assignments(spec.get("set", {}), "set", folder)
        if "blocks" in spec:
            for key in ("axes", "zip", "cases", "combine"):
                if key in spec:
                    raise InputError("cannot be combined with [[blocks]]: give it in each block", key=key)
            blocks = [(f"blocks[{k}]", v.table(block, f"blocks[{k}]"))
                      for k, block in enumerate(v.tables(spec["blocks"], "blocks"))]
        else:
            blocks = [("", {key: value for key, value in spec.items() if key in BLOCK_KEYS and key != "set"}
                       | {"combine": combine})]  # in the order written: the axes combine in it
        base_data = _base_data(base)
        plans = []
        for prefix, block in blocks:
            plans += [(top_set + block_set, values) for block_set, values in _block(block, prefix, folder)]
    except InputError as error:
        raise error.within(file=source) from None
    cases = [_case(k, base, base_data, kind, assignments, values, source, fatigue)
             for k, (assignments, values) in enumerate(plans)]
    keys = list(dict.fromkeys(path for assignments, values in plans for path, _ in assignments + values
                              if path not in RUN_KEYS and not path.startswith("tag.")))
    cases = [_with_params(case, keys, folder) for case in cases]
    return Sweep(source=source, base=base, out=out, cases=cases, stats_from=stats_from, fatigue=fatigue)


def _kind(value, key):
    """A run kind: "static", "dynamic" or an importable ``module:function``."""
    value = v.text(value, key)
    if value in KINDS:
        return value
    if ":" not in value:
        raise InputError(f"unknown kind '{value}'{v.suggest(value, KINDS)}; valid: static | dynamic | "
                         "module:function (a function(scene, out_dir) -> dict of columns)", key=key)
    module, _, name = value.partition(":")
    try:
        function = getattr(importlib.import_module(module), name)
    except (ImportError, AttributeError) as error:
        raise InputError(f"cannot import run kind '{value}': {v.one_line(error)}", key=key) from None
    if not callable(function):
        raise InputError(f"run kind '{value}' is not a function", key=key)
    return value


def _fatigue(raw):
    """The [fatigue] table: area [m^2] (or a table line type -> area), S-N a_D and m (stress in MPa)."""
    raw = v.table(raw, "fatigue")
    values = v.pick(raw, "fatigue", {"area": lambda x, k: x, "a_D": v.positive, "m": v.positive},
                    required=("area",))
    area = values["area"]
    if isinstance(area, dict):
        area = {name: v.positive(a, f"fatigue.area.{name}") for name, a in area.items()}
        if not area:
            raise InputError("must name at least one line type", key="fatigue.area")
    else:
        area = v.positive(area, "fatigue.area")
    return {"area": area, "a_D": values.get("a_D", DNV_STUDLESS["a_D"]), "m": values.get("m", DNV_STUDLESS["m"])}


def _flatten(table, prefix):
    """A TOML table as (key path, value) pairs: nested tables are paths (``[set.motion] period``
    is ``motion.period``), arrays and scalars are values."""
    pairs = []
    for key, value in table.items():
        path = f"{prefix}.{key}" if prefix else key
        pairs += _flatten(value, path) if isinstance(value, dict) else [(path, value)]
    return pairs


def _assignments(table, where, folder):
    """(path, value) pairs of a table of key paths, run keys checked and file names absolute."""
    return [_pair(path, value, v.join(where, path), folder) for path, value in _flatten(v.table(table, where), "")]


def _pair(path, value, key, folder):
    """(path, value) with a run key's or tag's value checked, a scene value's file names absolute."""
    return path, (_run_value(path, value, key) if _reserved(path, key) else absolute_value(path, value, folder))


def _reserved(path, key):
    """Whether ``path`` is a run key or a tag (checked), not a scene key."""
    if path in RUN_KEYS:
        return True
    if path.startswith("tag."):
        if path.count(".") != 1 or not path[4:]:
            raise InputError("a tag is tag.NAME with a plain NAME", key=key)
        return True
    parse_path(path)  # a malformed path is an error here, before any case is built
    return False


def _run_value(path, value, key):
    if path == "kind":
        return _kind(value, key)
    if path == "alone":
        return v.boolean(value, key)
    if isinstance(value, (list, dict)):
        raise InputError(f"a tag must be a string, number or boolean, got {v.describe_type(value)}", key=key)
    return value


def _block(block, prefix, folder):
    """Per case of one block: (the block's [set] pairs, the case's axis pairs)."""
    v.check_keys(block, BLOCK_KEYS, prefix)
    where = lambda name: v.join(prefix, name)  # noqa: E731
    block_set = _assignments(block.get("set", {}), where("set"), folder)
    combine = v.choice(COMBINE)(block.get("combine", "product"), where("combine"))
    axes = []  # in the order the block gives them: the first varies slowest
    for key in block:
        if key == "cases":
            entries = v.tables(block["cases"], where("cases"))
            axes.append([_assignments(entry, f"{where('cases')}[{k}]", folder) for k, entry in enumerate(entries)])
        elif key == "axes":
            named = _flatten(v.table(block["axes"], where("axes")), "")
            if combine == "zip" and named:
                axes.append(_zipped(dict(named), where("axes"), folder))
            else:
                axes += [_zipped({path: values}, where("axes"), folder) for path, values in named]
        elif key == "zip":
            for k, group in enumerate(v.tables(block["zip"], where("zip"))):
                axes.append(_zipped(v.table(group, f"{where('zip')}[{k}]"), f"{where('zip')}[{k}]", folder))
    seen = {}
    for axis_number, axis in enumerate(axes):
        for path, _ in (pair for values in axis for pair in values):
            if seen.setdefault(path, axis_number) != axis_number:
                raise InputError("is varied by two axes of the same block", key=v.join(prefix, path))
    return [(block_set, [pair for values in combination for pair in values])
            for combination in itertools.product(*axes)]


def _zipped(table, where, folder):
    """One axis from a table of key path -> array, the arrays read in step: a list of the axis's
    values, each a list of (path, value) pairs."""
    pairs = _flatten(table, "")
    length = None
    for path, values in pairs:
        key = v.join(where, path)
        if not isinstance(values, list) or not values:
            raise InputError(f"expected a non-empty array of values, got {v.describe_type(values)} {values!r}",
                             key=key)
        if length is not None and len(values) != length:
            raise InputError(f"has {len(values)} values where the keys it is zipped with have {length}", key=key)
        length = len(values)
    return [[_pair(path, values[k], v.join(where, path), folder) for path, values in pairs]
            for k in range(length or 0)]


def _base_data(base):
    """The base scene as TOML data: a TOML file parsed, a MoorDyn file wrapped as ``[moordyn] file``."""
    from cablefem.io.toml_scene import TOP_LEVEL_KEYS, parse_toml

    extension = os.path.splitext(base)[1].lower()
    if extension in MOORDYN_EXTENSIONS:
        return {"moordyn": {"file": base}}
    try:
        data = parse_toml(base)
    except InputError:
        if extension == ".toml":
            raise
        return {"moordyn": {"file": base}}
    if extension != ".toml" and not any(key in data for key in TOP_LEVEL_KEYS):
        return {"moordyn": {"file": base}}
    return data


def _case(index, base, base_data, kind, assignments, values, source, fatigue=None):
    """The validated Case number ``index``: the base data with the assignments and the axis values
    set, read by the TOML scene reader (an InputError names the sweep file, the case and the key)."""
    from cablefem.io.toml_scene import read_toml_scene

    data = copy.deepcopy(base_data)
    run = {"kind": kind, "alone": False}
    tags = {}
    label = ", ".join(f"{path} = {_short(value)}" for path, value in values) or "the base scene"
    try:
        for path, value in assignments + values:
            if path in RUN_KEYS:
                run[path] = value
            elif path.startswith("tag."):
                tags[path] = value
            else:
                set_path(data, path, value)
        scene = read_toml_scene(base, data)
        if fatigue is not None and isinstance(fatigue["area"], dict):
            for line in scene.lines:
                if line.segments[-1].type.name not in fatigue["area"]:
                    raise InputError(f"no nominal area for line type '{line.segments[-1].type.name}' "
                                     f"at the fairlead of line {line.name}", key="fatigue.area")
    except InputError as error:
        raise InputError(error.message(), key=f"case {index} ({label})", file=source) from None
    case_id = identity(run["kind"], data, os.path.dirname(base))
    return Case(index, case_id, run["kind"], run["alone"], data, {}, tags, label)


def _with_params(case, keys, folder):
    """The case with its value of every parameter key (None where the scene leaves the default;
    a file set by the sweep relative to the sweep's folder)."""
    params = {key: get_path(case.data, key) for key in keys}
    for key, value in params.items():
        if isinstance(value, str) and os.path.isabs(value) and is_file_path(key):
            params[key] = os.path.relpath(value, folder)
    return Case(case.index, case.case_id, case.kind, case.alone, case.data, params, case.tags, case.label)


def _short(value, limit=40):
    text = json.dumps(value) if not isinstance(value, str) else repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


def identity(kind, data, folder):
    """A case's identity: sha256 (first 16 hex digits) of its kind and scene data, with every
    file the data names (a key ``file``) replaced by the SHA-256 of the file's content."""
    text = json.dumps({"kind": kind, "scene": _content(data, folder)}, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _content(value, folder):
    if isinstance(value, dict):
        return {k: (_file_digest(os.path.join(folder, x)) if k == "file" and isinstance(x, str)
                    else _content(x, folder)) for k, x in value.items()}
    if isinstance(value, list):
        return [_content(x, folder) for x in value]
    return value


_DIGESTS = {}


def _file_digest(path):
    """SHA-256 of a file's bytes, remembered per (path, size, mtime)."""
    path = os.path.normpath(path)
    try:
        stat = os.stat(path)
    except OSError:
        return f"missing:{path}"
    key = (path, stat.st_size, stat.st_mtime_ns)
    if key not in _DIGESTS:
        with open(path, "rb") as handle:
            _DIGESTS[key] = "sha256:" + hashlib.sha256(handle.read()).hexdigest()
    return _DIGESTS[key]
