"""Sweeps of many runs on Dask (docs/sweep.md): ``cablefem sweep SWEEP.toml`` and, from Python,
``cablefem.sweep(base, axes)``.

A sweep is a base scene and the scene keys to vary (``cablefem.sweeps.spec``); each case runs as
one Dask task on a LocalCluster or an existing cluster (``cablefem.sweeps.engine``), writes its
own folder and comes back as one row of a table written as Parquet and CSV
(``cablefem.sweeps.table``). This package imports dask and pandas only when a sweep runs.
"""

import json
import os

from cablefem.sweeps.spec import build_sweep, read_sweep

__all__ = ["read_sweep", "build_sweep", "run", "run_sweep_file", "sweep"]


def run(spec, out=None, client=None, scheduler=None, workers=None, progress=None, retry_failed=False,
        on_row=None):
    """Run a ``Sweep`` (``read_sweep`` / ``build_sweep``) into ``out`` (default: its own ``out``);
    returns the table (pandas.DataFrame, one row per case; ``table.attrs["sweep"]``: how many
    cases ran, were skipped as done, failed or were lost, the wall time [s] and each worker's
    kernel load time [s]), also written to out/sweep.parquet, out/sweep.csv and out/sweep.json."""
    from cablefem.io.vtk import write_atomic
    from cablefem.sweeps.engine import execute
    from cablefem.sweeps.table import make_table, write_table

    out = os.path.abspath(out or spec.out)
    os.makedirs(out, exist_ok=True)
    rows, facts = execute(spec, out, client=client, scheduler=scheduler, workers=workers, progress=progress,
                          retry_failed=retry_failed, on_row=on_row)
    table = make_table(spec, rows)
    facts["failed"] = int((table["status"] == "failed").sum()) if len(table) else 0
    facts["source"], facts["base"] = spec.source, spec.base
    facts["tables"] = write_table(table, out)
    write_atomic(os.path.join(out, "sweep.json"), json.dumps(facts, indent=1))
    table.attrs["sweep"] = facts
    return table


def run_sweep_file(path, out=None, client=None, scheduler=None, workers=None, progress=None,
                   retry_failed=False, on_row=None):
    """Read, validate and run the sweep file at ``path`` (``run`` says what comes back)."""
    return run(read_sweep(path), out=out, client=client, scheduler=scheduler, workers=workers,
               progress=progress, retry_failed=retry_failed, on_row=on_row)


def sweep(base, axes=None, client=None, *, combine="product", zipped=None, cases=None, fixed=None,
          blocks=None, kind="dynamic", out="sweep-out", stats_from=0.0, fatigue=None, scheduler=None,
          workers=None, progress=None, retry_failed=False):
    """Run a sweep from Python: ``base`` a scene file (TOML or MoorDyn), ``axes`` {key path: list of
    values}; the other arguments are the sweep file's keys (``zipped`` is [[zip]], ``fixed`` is
    [set]; docs/sweep.md), relative paths resolve against the working directory. With no
    ``client`` (a ``distributed.Client``) nor ``scheduler`` address, a LocalCluster of
    ``workers`` processes. Returns the table as a pandas.DataFrame (``run``)."""
    spec = {"base": os.fspath(base), "kind": kind, "out": os.fspath(out), "stats_from": stats_from}
    given = {"axes": axes, "zip": zipped, "cases": cases, "set": fixed, "blocks": blocks, "fatigue": fatigue}
    spec.update({key: value for key, value in given.items() if value is not None})
    if blocks is None:
        spec["combine"] = combine
    built = build_sweep(spec, os.getcwd(), source=None)
    return run(built, client=client, scheduler=scheduler, workers=workers, progress=progress,
               retry_failed=retry_failed)
