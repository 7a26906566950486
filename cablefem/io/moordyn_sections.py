"""MoorDyn v2 input files cut into their sections and table rows (MoorDyn-C 2.x layout).

Headers are lines holding ``---``, matched by keyword as MoorDyn does; up to two
column-name/unit rows follow a table's header; rows before the first recognised
header are the title; a line ``END`` ends the file. ``cablefem.io.moordyn_input``
turns the rows into a Scene.
"""

from ..errors import InputError
from ..geometry.readers import is_number

#: header keywords (upper case) -> section, tried in this order as MoorDyn does
SECTION_KEYWORDS = (
    (("LINE DICTIONARY", "LINE TYPES"), "LINE TYPES"),
    (("ROD DICTIONARY", "ROD TYPES"), "ROD TYPES"),
    (("BODIES", "BODY LIST", "BODY PROPERTIES"), "BODIES"),
    (("RODS", "ROD LIST", "ROD PROPERTIES"), "RODS"),
    (("POINTS", "POINT LIST", "POINT PROPERTIES", "CONNECTION PROPERTIES", "NODE PROPERTIES"), "POINTS"),
    (("LINES", "LINE LIST", "LINE PROPERTIES"), "LINES"),
    (("FAILURE",), "FAILURE"),
    (("OPTIONS",), "OPTIONS"),
    (("OUTPUT",), "OUTPUTS"),
)
TABLE_COLUMNS = {
    "LINE TYPES": ("Name", "Diam", "MassDen", "EA", "BA/-zeta", "EI", "Cd", "Ca", "CdAx", "CaAx"),
    "POINTS": ("ID", "Attachment", "X", "Y", "Z", "M", "V", "CdA", "CA"),
    "LINES": ("ID", "LineType", "AttachA", "AttachB", "UnstrLen", "NumSegs"),
}
#: column names that only MoorDyn v1 tables have (their columns are in another order)
V1_COLUMNS = {"LINE TYPES": {"CAN", "CAT", "CDN", "CDT"}, "POINTS": {"FX", "FY", "FZ"},
              "LINES": {"NODEANCH", "NODEFAIR"}}


def at(number, key):
    """The key of a row: 'line <number>: <key>'."""
    return f"line {number}: {key}"


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


def _table_rows(section, rows):
    """Data rows of a table section: up to two leading column-name/unit rows are dropped."""
    skipped = 0
    while skipped < min(2, len(rows)) and not any(is_number(f) for f in rows[skipped][1]):
        number, fields = rows[skipped]
        if V1_COLUMNS[section] & {f.upper() for f in fields}:
            raise InputError(f"MoorDyn v1 columns ({' '.join(fields)}) are not supported; write the v2 "
                             f"columns {' '.join(TABLE_COLUMNS[section])}", key=at(number, section))
        skipped += 1
    columns = TABLE_COLUMNS[section]
    for number, fields in rows[skipped:]:
        if len(fields) < len(columns):
            raise InputError(f"expected {len(columns)} columns ({' '.join(columns)}), got {len(fields)}",
                             key=at(number, section))
    return rows[skipped:]


def parse_sections(sections):
    """Raw tables of a split file: (line types, points, lines, options, outputs)."""
    found = {"LINE TYPES": [], "POINTS": [], "LINES": [], "OPTIONS": [], "OUTPUTS": []}
    recognised = False
    for name, title, number, rows in sections:
        if name is None:
            data = [r for r in rows if sum(is_number(f) for f in r[1]) >= 2]
            if recognised and data:
                raise InputError("unrecognised section (cablefem reads LINE TYPES, POINTS, LINES, OPTIONS, "
                                 "OUTPUTS)", key=at(number, title))
            continue
        recognised = True
        if name in ("LINE TYPES", "POINTS", "LINES"):
            found[name] += _table_rows(name, rows)
        elif name in ("OPTIONS", "OUTPUTS"):
            found[name] += rows
        elif any(sum(is_number(f) for f in fields) >= 1 for _, fields in rows):
            raise InputError("not supported yet", key=at(number, name))
    return found
