"""What a sweep's table holds for each run: tension statistics and fatigue damage.

Statistics of a tension series over t >= t_from: largest and smallest value with their times,
and the time average and standard deviation (trapezoidal rule, so steps of different length,
adaptive or landing on output times, count by the time they cover). Fatigue: the series is
rainflow-counted (ASTM E1049-85, half cycles count 1/2; the ``rainflow`` package), each range
divided by a nominal area into a stress range in MPa, and Miner's sum taken over the S-N curve
N(S) = a_D S^-m (DNV-OS-E301's studless chain: a_D = 6.0e10, m = 3).
"""

import numpy as np

#: seconds in a (Julian) year, for damage per year
YEAR_S = 365.25 * 86400.0
_trapezoid = getattr(np, "trapezoid", None) or np.trapz  # numpy < 2 names it trapz


def window(t, values, t_from):
    """The samples at t >= t_from [s] (1e-9 s of slack): (t (k,), values (k,))."""
    keep = t >= t_from - 1e-9
    return t[keep], values[keep]


def tension_statistics(t, tension, t_from=0.0):
    """max, min [N], their times [s], time average and standard deviation [N] of a tension series
    (t (n,) [s], tension (n,) [N]) over t >= t_from: a dict ``max``, ``max_t``, ``min``,
    ``min_t``, ``mean``, ``std`` (NaN when no sample is in the window)."""
    t, tension = window(np.asarray(t, float), np.asarray(tension, float), t_from)
    if t.size == 0:
        return dict.fromkeys(("max", "max_t", "min", "min_t", "mean", "std"), float("nan"))
    i_max, i_min = int(np.argmax(tension)), int(np.argmin(tension))
    span = t[-1] - t[0]
    if span > 0:
        mean = _trapezoid(tension, t) / span
        std = np.sqrt(max(_trapezoid((tension - mean) ** 2, t) / span, 0.0))
    else:
        mean, std = tension.mean(), 0.0
    return {"max": float(tension[i_max]), "max_t": float(t[i_max]), "min": float(tension[i_min]),
            "min_t": float(t[i_min]), "mean": float(mean), "std": float(std)}


def rainflow_ranges(series):
    """Rainflow-counted cycles of a series (n,): ranges (k,) in its unit and counts (k,) (1 or 1/2)."""
    import rainflow

    cycles = np.array([(rng, count) for rng, _, count, _, _ in rainflow.extract_cycles(np.asarray(series, float))])
    if cycles.size == 0:
        return np.zeros(0), np.zeros(0)
    return cycles[:, 0], cycles[:, 1]


def fatigue_damage(t, tension, area, a_D, m, t_from=0.0):
    """Miner's sum D [-] of a tension series (t (n,) [s], tension (n,) [N]) over t >= t_from, with
    stress ranges S = range / area / 1e6 [MPa] (area [m^2]) on N(S) = a_D S^-m, and D per year
    (D scaled by a year over the window's length: the window taken as representative): a dict
    ``damage``, ``damage_per_year``, ``cycles`` (the counted cycles, half cycles as 1/2)."""
    t, tension = window(np.asarray(t, float), np.asarray(tension, float), t_from)
    ranges, counts = rainflow_ranges(tension)
    damage = float(np.sum(counts * (ranges / area / 1e6) ** m) / a_D)
    span = t[-1] - t[0] if t.size > 1 else 0.0
    return {"damage": damage, "damage_per_year": damage * YEAR_S / span if span > 0 else float("nan"),
            "cycles": float(counts.sum())}


def fatigue_area(fatigue, line):
    """The nominal area [m^2] of a line's fairlead segment: ``fatigue["area"]`` as a number, or
    looked up by the line type of the segment at the fairlead (None when the table lacks it)."""
    area = fatigue["area"]
    if isinstance(area, dict):
        return area.get(line.segments[-1].type.name)
    return area
