"""Line failures as a scene gives them: TOML's [[failures]] and MoorDyn-F's FAILURE section
(docs/scene.md, "Failures"), each resolved to the end of one of the scene's lines that lets go
(``cablefem.model.failure``).

A failure names a line and its end as the scene file wrote them: in a TOML network the line's own
name and its own anchor or fairlead, whichever string of the network (``cablefem.model.network``)
holds it and whichever way round; in a TOML that wraps a MoorDyn file, a line as cablefem reports it
(``line1``, ``line1+2``); in MoorDyn-F's FAILURE a point and the line attached there. An end that is
not held in place (a free end, a junction, a free point between two lines) cannot let go.
"""

import numpy as np

from cablefem.errors import InputError
from cablefem.io import validate as v
from cablefem.model.failure import ENDS, Failure, releasable

FAILURE_KEYS = {"line": v.text, "end": v.choice(ENDS), "time": v.non_negative,
                "tension": v.limited(v.positive, "force")}


def _string_of(strings, name, point, position, key, prefix=""):
    """(index, end) of the end of a string holding line ``name`` (a string named ``prefix`` + the names
    of its lines joined by '+') at point ``point`` (None: the line's own end, found by its ``position``
    (3,) [m]); an InputError if the line's end is inside its string (a free point joining two lines)."""
    for k, string in enumerate(strings):
        if name in string.name[len(prefix):].split("+"):
            for end, (at, where) in enumerate(zip(string.ends, (string.anchor, string.fairlead))):
                if at == point and (point is not None or np.array_equal(where, position)):
                    return k, end
            raise InputError(f"line '{name}' ends at free point '{point}', which joins it to the next line of "
                             f"'{string.name}': that end is not held and cannot let go", key=key)
    raise InputError(f"line '{name}' is not in the scene", key=key)


def read_toml_failures(raw, strings, lines=None):
    """The [[failures]] array as ``Failure`` objects. ``strings``: the scene's lines; ``lines``: the
    [[lines]] as written (before a network joins them into strings), None when the lines come from
    a MoorDyn file (then a failure names one of ``strings`` and its end as cablefem reports it)."""
    failures = []
    named = lines if lines is not None else strings
    names = [line.name for line in named]
    for i, entry in enumerate(v.tables(raw, "failures")):
        prefix = f"failures[{i}]"
        values = v.pick(v.table(entry, prefix), prefix, FAILURE_KEYS, required=("line", "end"))
        if ("time" in values) == ("tension" in values):
            raise InputError("give either time (s) or tension (N), not both and not neither", key=prefix)
        name, end = values["line"], ENDS.index(values["end"])
        if name not in names:
            raise InputError(f"no line '{name}'{v.suggest(name, names)} in the scene; its lines: "
                             f"{', '.join(names)}", key=f"{prefix}.line")
        line = named[names.index(name)]
        if lines is None:
            k, string_end = names.index(name), end
        else:
            k, string_end = _string_of(strings, name, line.ends[end], (line.anchor, line.fairlead)[end],
                                       f"{prefix}.end")
        releasable(strings[k], string_end, name, f"{prefix}.end")
        failures.append(Failure(name, values["end"], values.get("time"), values.get("tension"), k, string_end,
                                prefix))
    _distinct(failures)
    return tuple(failures)


def _distinct(failures):
    """InputError if two failures let go of the same end."""
    seen = {}
    for failure in failures:
        where = (failure.string, failure.string_end)
        if where in seen:
            raise InputError(f"the same end lets go twice (also at {seen[where]}): give one failure per end",
                             key=failure.key)
        seen[where] = failure.key


def read_moordyn_failures(rows, raw_lines, points, strings, at):
    """MoorDyn-F's FAILURE rows (number, fields: FailureID Point Line(s) FailTime FailTen, a time or a
    tension of 0 unused, whichever of the others comes first) as ``Failure`` objects. ``raw_lines``: the
    LINES rows as read ({"id", "ends", ...}); ``points``: point ID -> (row, Point); ``strings``: the
    scene's lines named ``line<ids>``; ``at(number, key)``: a row's key. What cablefem cannot honour is
    refused with one line: a rod end, several lines failing together (MoorDyn-F leaves them joined by a
    new free point), neither a time nor a tension."""
    from cablefem.io.moordyn_sections import refuse, value

    by_id = {raw["id"]: raw for raw in raw_lines}
    failures = []
    for number, fields in rows:
        key = at(number, f"FAILURE.{fields[0]}")
        if len(fields) < 5:
            raise InputError(f"expected 5 columns (FailureID Point Line(s) FailTime FailTen), got {len(fields)}",
                             key=key)
        point, listed = fields[1], [item for item in fields[2].split(",") if item]
        if point.upper().startswith("R"):
            refuse("RODS", at(number, f"FAILURE.{fields[0]}.Point"), f"a failure at rod end '{point}'")
        if len(listed) != 1:
            raise InputError(f"lines {fields[2]} fail together at point {point}: cablefem lets go of one line "
                             "end per failure (MoorDyn-F leaves several lines joined by a new free point); give "
                             "one row per line", key=at(number, f"FAILURE.{fields[0]}.Line(s)"))
        time = value(fields[3], number, f"FAILURE.{fields[0]}.FailTime", v.non_negative)
        tension = value(fields[4], number, f"FAILURE.{fields[0]}.FailTen", v.limited(v.non_negative, "force"))
        if time == 0.0 and tension == 0.0:
            raise InputError("FailTime and FailTen are both 0: give the time or the tension at which the line "
                             "lets go", key=key)
        pid, lid = _whole(point), listed[0]
        if pid not in points:
            raise InputError(f"no point {point} in POINTS", key=at(number, f"FAILURE.{fields[0]}.Point"))
        if lid not in by_id:
            raise InputError(f"no line {lid} in LINES", key=at(number, f"FAILURE.{fields[0]}.Line(s)"))
        name = points[pid][1].name
        ends = [e for e, end in enumerate(by_id[lid]["ends"]) if end == name]
        if not ends:
            raise InputError(f"line {lid} is not attached to point {point}", key=key)
        k, string_end = _string_of(strings, lid, name, None, key, prefix="line")
        releasable(strings[k], string_end, f"line{lid}", key)
        failures.append(Failure(f"line{lid}", ENDS[ends[0]], time or None, tension or None, k, string_end, key))
    _distinct(failures)
    return tuple(failures)


def _whole(token):
    """A point ID from a FAILURE row's token (a whole number), else the token itself."""
    try:
        return int(token)
    except ValueError:
        return token
