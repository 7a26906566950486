"""``cablefem plot`` on a sweep: one statistic of the table against one parameter, one curve per
value of another (matplotlib, imported here only)."""

import os

from cablefem.errors import InputError
from cablefem.sweeps.table import HEAD, read_table


def parameter_columns(table):
    """The tag and parameter columns of a sweep table (they stand between ``error`` and
    ``wall_time_s``), those taking more than one value first."""
    columns = list(table.columns)
    start = len(HEAD)
    stop = columns.index("wall_time_s") if "wall_time_s" in columns else start
    keys = columns[start:stop]
    return sorted(keys, key=lambda k: table[k].astype(str).nunique() <= 1)


def plot_sweep(path, png=None, y=None, x=None, by=None):
    """Draw column ``y`` of a sweep's table (folder or .parquet/.csv) against parameter ``x``, one
    curve per value of ``by``, for the cases with status ok; returns the PNG's path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    table = read_table(path)
    good = table[table["status"] == "ok"]
    keys = parameter_columns(table)
    y = y or next((c for c in table.columns if c.endswith((":fairlead_tension_max", ":fairlead_tension"))), None)
    x = x or (keys[0] if keys else None)
    by = by or (keys[1] if len(keys) > 1 and keys[1] != x and good[keys[1]].astype(str).nunique() > 1 else None)
    for flag, column in (("--y", y), ("--x", x), ("--by", by)):
        if column is not None and column not in table.columns:
            raise InputError(f"no column '{column}' in the table; parameters: {', '.join(keys) or 'none'}",
                             key=flag, file=path)
    if y is None or x is None:
        raise InputError("give --y and --x: the table has no fairlead tension or no parameter", file=path)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    groups = good.groupby(by, sort=True, dropna=False) if by else [(None, good)]
    for value, group in groups:
        group = group.sort_values(x)
        ax.plot(group[x], group[y], "o-", label=f"{by} = {value}" if by else None)
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.grid(True, alpha=0.3)
    if by:
        ax.legend(fontsize=8)
    failed = len(table) - len(good)
    ax.set_title(f"{len(good)} cases" + (f" ({failed} failed or lost, not drawn)" if failed else ""), fontsize=9)
    fig.tight_layout()
    folder = path if os.path.isdir(path) else os.path.dirname(os.path.abspath(path))
    png = png or os.path.join(folder, "sweep.png")
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return png
