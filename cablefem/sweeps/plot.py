"""``cablefem plot`` on a sweep: one statistic of the table against one parameter, one curve per
value of another (matplotlib, imported here only). Tensions are drawn in kN; each axis names its
unit, a parameter's as docs/scene.md gives it (``KEY_UNITS``), a statistic's as docs/sweep.md does
(``statistic_unit``)."""

import os
import re

from cablefem.errors import InputError
from cablefem.sweeps.table import HEAD, read_table

#: units of the scene keys a sweep may vary, (section, key) -> unit, as docs/scene.md's tables give
#: them (keys without a unit there have none here; tests/test_sweep_plot.py holds the two equal)
KEY_UNITS = {
    ("environment", "water_density"): "kg/m^3", ("environment", "gravity"): "m/s^2",
    ("environment", "current"): "m/s",
    ("line_types.NAME", "diameter"): "m", ("line_types.NAME", "mass"): "kg/m", ("line_types.NAME", "EA"): "N",
    ("line_types.NAME", "damping"): "s", ("line_types.NAME", "nominal_diameter"): "m",
    ("line_types.NAME", "EI"): "N m²",
    ("line_types.NAME", "BA"): "N s", ("line_types.NAME", "EA_dynamic"): "N", ("line_types.NAME", "BA_dynamic"): "N s",
    ("lines", "segments.syrope"): "N",
    ("lines", "anchor"): "m", ("lines", "fairlead"): "m", ("lines", "segments.length"): "m",
    ("seabed", "depth"): "m", ("seabed", "point"): "m", ("seabed", "slope_deg"): "deg",
    ("seabed", "azimuth_deg"): "deg", ("seabed", "stiffness"): "N/m^3", ("seabed", "damping"): "N s/m^3",
    ("friction", "v_threshold"): "m/s", ("friction", "saturation_damping"): "N s/m",
    ("points.NAME", "position"): "m", ("points.NAME", "mass"): "kg", ("points.NAME", "volume"): "m^3",
    ("points.NAME", "CdA"): "m^2", ("points.NAME", "force"): "N",
    ("bodies.NAME", "position"): "m", ("bodies.NAME", "rotation_deg"): "deg",
    ("bodies.NAME", "waterplane_area"): "m^2", ("bodies.NAME", "motion.period"): "s",
    ("bodies.NAME", "motion.ramp"): "s", ("bodies.NAME", "CdA"): "m^2 (m^5 for the rotations)",
    ("soil", "su_gradient"): "Pa/m", ("soil", "su_mudline"): "Pa", ("soil", "stiffness_normal"): "1/m",
    ("soil", "stiffness_tangential"): "1/m",
    ("motion", "amplitude"): "m", ("motion", "period"): "s", ("motion", "offset"): "m", ("motion", "radius"): "m",
    ("motion", "ramp"): "s",
    ("solver", "dt"): "s", ("solver", "duration"): "s",
    ("output", "every"): "s",
    ("failures", "time"): "s", ("failures", "tension"): "N",
    ("waves", "amplitude"): "m", ("waves", "period"): "s", ("waves", "direction"): "deg", ("waves", "phase"): "deg",
    ("waves", "Hs"): "m", ("waves", "Tp"): "s", ("waves", "frequency_band"): "rad/s", ("waves", "time_step"): "s",
    ("waves", "ramp"): "s", ("waves", "depth"): "m",
}

#: the sections whose tables are named (``[line_types.NAME]``, ...): a key path's second part is the name
NAMED = ("line_types", "points", "bodies")


def key_unit(path):
    """The unit (str, "" if none) of a sweep's key path, e.g. "motion.period" -> "s",
    "lines[*].segments[0].length" -> "m", "line_types.chain.EA" -> "N"."""
    parts = re.sub(r"\[[^\]]*\]", "", path).split(".")
    if parts[0] in NAMED and len(parts) > 2:
        section, key = f"{parts[0]}.NAME", ".".join(parts[2:])
    else:
        section, key = parts[0], ".".join(parts[1:])
    return KEY_UNITS.get((section, key), "")


def statistic_unit(column):
    """(unit, factor from the table's value) of a statistic column (docs/sweep.md): tensions in kN,
    times in s."""
    name = column.rpartition(":")[2]
    if name.endswith("_t") or name.endswith("time_s"):
        return "s", 1.0
    if "tension" in name:
        return "kN", 1e-3
    return {"touchdown_s": ("m", 1.0), "fatigue_damage_per_year": ("1/year", 1.0),
            "output_bytes": ("B", 1.0)}.get(name, ("", 1.0))


def parameter_columns(table):
    """The tag and parameter columns of a sweep table (they stand between ``error`` and
    ``wall_time_s``), those taking more than one value first."""
    columns = list(table.columns)
    start = len(HEAD)
    stop = columns.index("wall_time_s") if "wall_time_s" in columns else start
    keys = columns[start:stop]
    return sorted(keys, key=lambda k: table[k].astype(str).nunique() <= 1)


def statistic_columns(table):
    """The columns of what the cases gave (after the parameters, ``dir`` left out)."""
    columns = list(table.columns)
    start = columns.index("wall_time_s") if "wall_time_s" in columns else len(HEAD)
    return [c for c in columns[start:] if c != "dir"]


def pick_statistic(table, y, path):
    """The column ``y`` names: itself, or the one column ending in ``:y`` (a statistic without its
    line's name); InputError listing the statistics otherwise."""
    statistics = statistic_columns(table)
    if y in table.columns:
        return y
    matches = [c for c in statistics if c.endswith(f":{y}")]
    if len(matches) == 1:
        return matches[0]
    if matches:
        raise InputError(f"'{y}' is a statistic of several lines: give one of {', '.join(matches)}",
                         key="--y", file=path)
    raise InputError(f"no statistic '{y}' in the table; statistics: {', '.join(statistics) or 'none'}",
                     key="--y", file=path)


def plot_sweep(path, png=None, y=None, x=None, by=None):
    """Draw column ``y`` of a sweep's table (folder or .parquet/.csv) against parameter ``x``, one
    curve per value of ``by``, for the cases with status ok; returns the PNG's path. ``y`` may leave
    out its line's name when one line has that statistic."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    table = read_table(path)
    good = table[table["status"] == "ok"]
    keys = parameter_columns(table)
    y = pick_statistic(table, y, path) if y else next(
        (c for c in table.columns if c.endswith((":fairlead_tension_max", ":fairlead_tension"))), None)
    x = x or (keys[0] if keys else None)
    by = by or (keys[1] if len(keys) > 1 and keys[1] != x and good[keys[1]].astype(str).nunique() > 1 else None)
    for flag, column in (("--x", x), ("--by", by)):
        if column is not None and column not in table.columns:
            raise InputError(f"no parameter '{column}' in the table; parameters: {', '.join(keys) or 'none'}",
                             key=flag, file=path)
    if y is None or x is None:
        raise InputError("give --y and --x: the table has no fairlead tension or no parameter", file=path)
    unit, factor = statistic_unit(y)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    groups = good.groupby(by, sort=True, dropna=False) if by else [(None, good)]
    for value, group in groups:
        group = group.sort_values(x)
        ax.plot(group[x], group[y] * factor, "o-", label=_legend(by, value) if by else None)
    ax.set_xlabel(_with_unit(x, key_unit(x)))
    ax.set_ylabel(_with_unit(y, unit))
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


def _with_unit(name, unit):
    return f"{name} [{unit}]" if unit else name


def _legend(key, value):
    unit = key_unit(key)
    return f"{key} = {value}" + (f" {unit}" if unit else "")
