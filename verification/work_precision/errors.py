"""The errors of verification/work_precision: a run against a reference over the last periods, the
Pareto front of error against wall time, the ratio table of the two codes, the observed time order."""

import numpy as np

from cablefem.model.builtin import FLUME_MOTIONS

from validation.moordyn.comparison import differences
from verification.work_precision.runners import MOTIONS

WINDOW_PERIODS = 2


def window_start(motion, duration):
    """Start [s] of the error window: the last two periods."""
    return duration - WINDOW_PERIODS * FLUME_MOTIONS[MOTIONS[motion]].period


def error_against(run, reference, t_from):
    """RMS of run - reference over t >= t_from at the run's times, relative to the reference's mean."""
    t = run["t"]
    on_run = np.interp(t, reference["t"], reference["tension"])
    return differences(t, on_run, run["tension"], t_from)["rms"]


def pareto(rows, gain=0.02):
    """The rows no other row beats in both wall time and error, cheapest first; a row joins only
    when its error is below the last one's by more than ``gain`` (a 1 % better error at twice
    the cost is no new error level). Failed runs (error None) are left out."""
    front, best = [], np.inf
    for row in sorted((r for r in rows if r["error"] is not None), key=lambda r: (r["wall_time_s"], r["error"])):
        if row["error"] < best * (1.0 - gain):
            front.append(row)
            best = row["error"]
    return front


def ratios(moordyn_rows, cablefem_rows):
    """For every MoorDyn Pareto point: the cheapest cablefem run at least as accurate, and the
    ratio of wall times (cablefem / MoorDyn); None where cablefem has no run that accurate."""
    table = []
    for md in pareto(moordyn_rows):
        good = [r for r in cablefem_rows if r["error"] is not None and r["error"] <= md["error"]]
        cf = min(good, key=lambda r: r["wall_time_s"]) if good else None
        table.append({"error": md["error"], "moordyn": md["label"], "moordyn_s": md["wall_time_s"],
                      "moordyn_peer_s": md["peer_wall_time_s"],
                      "cablefem": cf["label"] if cf else None, "cablefem_error": cf["error"] if cf else None,
                      "cablefem_s": cf["wall_time_s"] if cf else None,
                      "ratio": cf["wall_time_s"] / md["wall_time_s"] if cf else None})
    return table


def observed_order(steps, errors):
    """Least-squares slope of log(error) against log(step)."""
    return float(np.polyfit(np.log(steps), np.log(errors), 1)[0])
