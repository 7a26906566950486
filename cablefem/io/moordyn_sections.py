"""MoorDyn v2 input files cut into their sections and table rows (MoorDyn-C 2.x layout).

Headers are lines holding ``---``, matched by keyword as MoorDyn does; up to two
column-name/unit rows follow a table's header; rows before the first recognised
header are the title; a line ``END`` ends the file. ``cablefem.io.moordyn_input``
turns the rows into a Scene. ``REFUSED`` is the one list of what cablefem does not read, each with
what to do instead (docs/scene.md has the same table).
"""

from cablefem.errors import InputError
from cablefem.geometry.readers import is_number, parse_number

#: header keywords (upper case) -> section, tried in this order as MoorDyn does
SECTION_KEYWORDS = (
    (("LINE DICTIONARY", "LINE TYPES"), "LINE TYPES"),
    (("ROD DICTIONARY", "ROD TYPES"), "ROD TYPES"),
    (("BODIES", "BODY LIST", "BODY PROPERTIES"), "BODIES"),
    (("RODS", "ROD LIST", "ROD PROPERTIES"), "RODS"),
    (("POINTS", "POINT LIST", "POINT PROPERTIES", "CONNECTION PROPERTIES", "NODE PROPERTIES"), "POINTS"),
    (("LINES", "LINE LIST", "LINE PROPERTIES"), "LINES"),
    (("FAILURE",), "FAILURE"),
    (("SYROPE IC",), "SYROPE IC"),
    (("OPTIONS",), "OPTIONS"),
    (("OUTPUT",), "OUTPUTS"),
)
TABLE_COLUMNS = {
    "LINE TYPES": ("Name", "Diam", "MassDen", "EA", "BA/-zeta", "EI", "Cd", "Ca", "CdAx", "CaAx"),
    "BODIES": ("ID", "Attachment", "X0", "Y0", "Z0", "r0", "p0", "y0", "Mass", "CG", "I", "Volume", "CdA", "Ca"),
    "POINTS": ("ID", "Attachment", "X", "Y", "Z", "M", "V", "CdA", "CA"),
    "LINES": ("ID", "LineType", "AttachA", "AttachB", "UnstrLen", "NumSegs"),
}
#: column names of the MoorDyn v1 LINE TYPES header (LineType Diam MassDenInAir EA BA/-zeta EI Can Cat
#: Cdn Cdt): MoorDyn-C reads that table by position (``readLineProps``: entries 6-9 are Cdn, Can,
#: Cdt, Cat whatever the header says), and so does cablefem, with a note
V1_LINE_TYPE_COLUMNS = {"CAN", "CAT", "CDN", "CDT"}
#: column names that only the MoorDyn v1 LINES table has: its columns are in another order
#: (Line LineType UnstrLen NumSegs NodeAnch NodeFair Flags), read as the header names them
V1_LINE_COLUMNS = {"NODEANCH", "NODEFAIR"}
V1_COLUMNS = {"LINE TYPES": V1_LINE_TYPE_COLUMNS, "LINES": V1_LINE_COLUMNS}

#: What cablefem refuses in a MoorDyn file: construct -> (what it is, what to do instead). The one
#: list; docs/scene.md ("What stays refused") has the same table.
REFUSED = {
    "RODS": ("RODS (rigid rods, and lines attached to rod ends R1A, R1B)",
             "model a rod as a short stiff line between two points, or fix its line ends to a body (BodyN points)"),
    "ROD TYPES": ("ROD TYPES (properties of RODS)",
                  "model a rod as a short stiff line between two points, or fix its line ends to a body"),
    "WaveKin": ("wave kinematics other than WaveKin 0, 1, 2, 3 and 7 (4 to 6: not implemented in MoorDyn-C "
                "either)",
                "give the waves as [waves] in a TOML that wraps the file, or write them as wave_frequencies.txt "
                "with WaveKin 7"),
    "Currents": ("MoorDyn-C's node approach to currents (Currents 3 and 4, for which MoorDyn-C 2.7 builds no "
                 "current)",
                 "give the current on a grid: Currents 1 (current_profile.txt), 2 (current_profile_dynamic.txt) or "
                 "5 (current_profile_4d.txt)"),
    "turbine": ("points on a FAST.Farm turbine (TurbineN, MoorDyn-F)",
                "attach them to a coupled body (BodyN) of BODIES, or make them Coupled points"),
}


def refuse(construct, key, detail=""):
    """The InputError of a ``REFUSED`` construct at ``key``: what it is and what to do instead."""
    what, instead = REFUSED[construct]
    raise InputError(f"{what}{': ' + detail if detail else ''} is not supported: {instead}", key=key)


def at(number, key):
    """The key of a row: 'line <number>: <key>'."""
    return f"line {number}: {key}"


def value(token, number, key, check):
    """A checked number from a file token; the error names the file line and the column."""
    parsed = parse_number(token)
    if parsed is None:
        raise InputError(f"expected a number, got '{token}'", key=at(number, key))
    return check(parsed, at(number, key))


def split_sections(text):
    """[(section or None, header text, line number, [(line number, fields)])] of a MoorDyn file."""
    sections, current = [], None
    for number, raw in enumerate(text.splitlines(), start=1):
        row = raw.strip()
        if not row:
            continue
        if "---" in row:
            title = " ".join(row.replace("-", " ").split()).upper()
            name = next((section for keys, section in SECTION_KEYWORDS
                         if any(key in title for key in keys)), None)
            current = (name, title, number, [])
            sections.append(current)
        elif row.upper() == "END":
            break
        elif current is not None:
            current[3].append((number, row.split()))
    return sections


def _table_rows(section, rows, v1):
    """Data rows of a table section: up to two leading column-name/unit rows are dropped (a v1
    LINE TYPES or LINES header's row number is added to ``v1[section]``)."""
    skipped = 0
    while skipped < min(2, len(rows)) and not any(is_number(f) for f in rows[skipped][1]):
        number, fields = rows[skipped]
        names = {f.upper() for f in fields}
        if names & V1_COLUMNS.get(section, set()):
            v1.setdefault(section, []).append(number)
        skipped += 1
    columns = TABLE_COLUMNS[section]
    for number, fields in rows[skipped:]:
        if len(fields) < len(columns):
            raise InputError(f"expected {len(columns)} columns ({' '.join(columns)}), got {len(fields)}",
                             key=at(number, section))
    return rows[skipped:]


def parse_sections(sections):
    """Raw tables of a split file by section (LINE TYPES, BODIES, POINTS, LINES: rows of fields;
    OPTIONS, OUTPUTS, SYROPE IC, FAILURE: rows) and "v1": {section: the rows of its v1 headers} (LINE TYPES, LINES)."""
    found = {"LINE TYPES": [], "BODIES": [], "POINTS": [], "LINES": [], "OPTIONS": [], "OUTPUTS": [], "v1": {},
             "SYROPE IC": [], "FAILURE": []}
    recognised = False
    for name, title, number, rows in sections:
        if name is None:
            data = [r for r in rows if sum(is_number(f) for f in r[1]) >= 2]
            if recognised and data:
                raise InputError("unrecognised section (cablefem reads LINE TYPES, BODIES, POINTS, LINES, "
                                 "OPTIONS, OUTPUTS)", key=at(number, title))
            continue
        recognised = True
        if name in TABLE_COLUMNS:
            found[name] += _table_rows(name, rows, found["v1"])
        elif name in ("OPTIONS", "OUTPUTS"):
            found[name] += rows
        elif name == "FAILURE":  # two rows of column names and units, then FailureID Point Line(s) FailTime FailTen
            found[name] += [(n, f) for n, f in rows if sum(is_number(x) for x in f) >= 2]
        elif name == "SYROPE IC":  # up to two rows of column names and units, then 'Line(s) Tmax0 Tmean0'
            found[name] += [(n, f) for n, f in rows if len(f) >= 2 and is_number(f[1])]
        elif any(sum(is_number(f) for f in fields) >= 1 for _, fields in rows):
            refuse(name, at(number, name))
    return found
