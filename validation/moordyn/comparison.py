"""How validation/moordyn compares two runs: tension statistics over a window, on a common time grid,
a run against itself, and how periodic a run is."""

import numpy as np


def differences(t, reference, other, t_from):
    """Statistics of two tension series (n,) [N] over t >= t_from [s], relative to the
    reference's mean: RMS and largest difference, difference of the means and of the peaks."""
    window = t >= t_from - 1e-9
    a, b = reference[window], other[window]
    mean = float(a.mean())
    return {"reference_mean_N": mean, "other_mean_N": float(b.mean()),
            "reference_max_N": float(a.max()), "other_max_N": float(b.max()),
            "reference_min_N": float(a.min()), "other_min_N": float(b.min()),
            "rms": float(np.sqrt(np.mean((b - a) ** 2)) / mean),
            "max": float(np.max(np.abs(b - a)) / mean),
            "mean": float((b.mean() - a.mean()) / mean),
            "peak": float((b.max() - a.max()) / mean),
            "trough": float((b.min() - a.min()) / mean)}


def on_grid(t, series, grid):
    """Series (n, ...) sampled at times t (n,) interpolated to times grid (m,)."""
    flat = series.reshape(len(t), -1)
    return np.column_stack([np.interp(grid, t, column) for column in flat.T]).reshape((len(grid),) + series.shape[1:])


def compare_runs(moordyn, cablefem, order, t_from, use_point_force=False):
    """Per line (MoorDyn point order): ``differences`` of cablefem against MoorDyn on cablefem's times
    (or MoorDyn's, whichever is coarser)."""
    grid = cablefem["t"] if len(cablefem["t"]) <= len(moordyn["t"]) else moordyn["t"]
    md_forces = moordyn["forces_on_point"] if use_point_force else moordyn["forces"]
    md = np.linalg.norm(on_grid(moordyn["t"], md_forces, grid), axis=2)
    cf = on_grid(cablefem["t"], cablefem["tensions"], grid)
    return [differences(grid, md[:, k], cf[:, line], t_from) for k, line in enumerate(order)]


def self_differences(first, second, t_from, key="tensions"):
    """Per column: ``differences`` of two runs of one code (second against first) on the coarser grid."""
    grid = first["t"] if len(first["t"]) <= len(second["t"]) else second["t"]
    a = on_grid(first["t"], first[key], grid)
    b = on_grid(second["t"], second[key], grid)
    return [differences(grid, a[:, k], b[:, k], t_from) for k in range(a.shape[1])]


def periodicity(run, columns, t_end, period, scales):
    """Per column of run["tensions"]: change of the mean, max and min from the second-to-last period
    before t_end [s] to the last one, over scales (k,) [N]: how far the window is from periodic."""
    t = run["t"]
    last = (t >= t_end - period - 1e-9) & (t <= t_end + 1e-9)
    before = (t >= t_end - 2 * period - 1e-9) & (t <= t_end - period + 1e-9)
    rows = []
    for column, scale in zip(columns, scales):
        a, b = run["tensions"][before, column], run["tensions"][last, column]
        rows.append({"mean": float((b.mean() - a.mean()) / scale), "max": float((b.max() - a.max()) / scale),
                     "min": float((b.min() - a.min()) / scale)})
    return rows


def worst(rows, key):
    """Largest |value| of ``key`` over rows (lines)."""
    return float(max(abs(r[key]) for r in rows))
