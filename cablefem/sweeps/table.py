"""A sweep's table: one row per case, written as Parquet and CSV (pandas + pyarrow).

Columns, in this order: ``case`` (its number in the sweep), ``case_id`` (its identity, also the
name of its folder ``cases/<case_id>``), ``kind``, ``status`` (ok | failed | lost), ``error``
(one line, or empty), the ``tag.*`` labels, the parameters (one column per key path the sweep
sets, e.g. ``motion.period``; arrays as JSON text), ``wall_time_s``, ``cpu_time_s`` and
``output_bytes``, then
what the run gave (docs/sweep.md: per line ``<line>:fairlead_tension_max`` ... for dynamic runs,
``<line>:fairlead_tension`` ... for static ones), and ``dir``.
"""

import json
import os

HEAD = ("case", "case_id", "kind", "status", "error")


def make_table(sweep, rows):
    """The DataFrame of ``sweep`` from its rows (dict case index -> row dict), in case order; a
    case without a row (interrupted before it ran) is left out."""
    import pandas as pd

    records = []
    for case in sweep.cases:
        if case.index not in rows:
            continue
        row = dict(rows[case.index])
        record = {"case": case.index, "case_id": case.case_id, "kind": case.kind,
                  "status": row.pop("status"), "error": row.pop("error", None)}
        record.update(case.tags)
        record.update({path: _cell(value) for path, value in case.params.items()})
        record.update({key: row.pop(key, None) for key in ("wall_time_s", "cpu_time_s", "output_bytes")})
        record.update(row)
        record["dir"] = f"cases/{case.case_id}"
        records.append(record)
    table = pd.DataFrame.from_records(records)
    for column in table.columns:
        kinds = {type(x) for x in table[column] if x is not None and x == x}
        if str in kinds and len(kinds) > 1:  # mixed text and numbers: one type for Parquet
            table[column] = [None if x is None else str(x) for x in table[column]]
    return table


def _cell(value):
    """A parameter as a table cell: numbers, text and booleans as they are, arrays as JSON."""
    return json.dumps(value) if isinstance(value, (list, dict)) else value


def write_table(table, out, name="sweep"):
    """Write ``table`` as ``out/<name>.parquet`` and ``out/<name>.csv`` (each through a temporary
    file renamed into place); returns the two paths."""
    os.makedirs(out, exist_ok=True)
    paths = []
    for extension, write in (("parquet", lambda t, p: t.to_parquet(p, index=False)),
                             ("csv", lambda t, p: t.to_csv(p, index=False))):
        path = os.path.join(out, f"{name}.{extension}")
        tmp = os.path.join(out, f".{name}.{extension}.tmp")
        write(table, tmp)
        os.replace(tmp, path)
        paths.append(path)
    return paths


def read_table(path):
    """A sweep's table from its folder (``sweep.parquet`` in it) or a .parquet / .csv file."""
    import pandas as pd

    from cablefem.errors import InputError

    if os.path.isdir(path):
        path = os.path.join(path, "sweep.parquet")
    if not os.path.isfile(path):
        raise InputError("no sweep table here (sweep.parquet): is this the output folder of "
                         "`cablefem sweep`?", file=path)
    if path.endswith(".csv"):
        return pd.read_csv(path)
    return pd.read_parquet(path)
