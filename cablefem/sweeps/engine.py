"""Running a sweep's cases on Dask: a LocalCluster of processes (one per core, one thread each)
or an existing cluster by its scheduler's address.

Order of work: cases whose folder holds a done-marker are read back, not run; the others are
submitted as Dask tasks (``cablefem.sweeps.tasks.run_task``), at most a few per worker thread
at a time, so that neither the scheduler nor the client holds 10,000 of them and the table grows
row by row as they finish; cases marked ``alone`` run afterwards one at a time. Before the first
case, every worker loads the compiled kernels (``tasks.warm``): the first worker alone, so that
a cold numba cache is compiled once and the other workers load what it wrote.
"""

import contextlib
import os
import sys
import time

from cablefem.errors import InputError
from cablefem.sweeps.paths import get_path
from cablefem.sweeps.tasks import read_marker, run_task, task_of, warm

#: tasks in flight per worker thread: enough to keep every thread busy between results
IN_FLIGHT_PER_THREAD = 2


def execute(sweep, out, client=None, scheduler=None, workers=None, progress=None, retry_failed=False,
            on_row=None):
    """Run the cases of ``sweep`` not done in ``out``; returns (rows by case index, facts) where
    facts says how many cases and distinct runs there are, how many ran, were skipped or lost,
    the wall time [s], the time to start or reach the cluster [s], each worker's kernel load
    time [s] and the time from the first case submitted to the last row [s]. ``on_row(row)`` is
    called as each row arrives (rows of skipped cases too)."""
    start = time.perf_counter()
    tasks = {}  # one task per identity: a case that repeats another runs once
    for case in sweep.cases:
        tasks.setdefault(case.case_id, task_of(case, sweep, os.path.join(out, "cases", case.case_id)))
    done, todo = {}, []
    for case_id, task in tasks.items():
        row = read_marker(task)
        if row is not None and (row["status"] == "ok" or not retry_failed):
            done[case_id] = row
        else:
            todo.append(task)
    facts = {"cases": len(sweep.cases), "runs": len(tasks), "skipped": len(done), "ran": 0, "lost": 0,
             "warm_up_s": {}}
    bar = _progress(progress, len(tasks), len(done))
    try:
        for row in done.values():
            if on_row:
                on_row(row)
        if todo:
            begin = time.perf_counter()
            with connect(client, scheduler, workers) as dask_client:
                facts["scheduler"] = dask_client.scheduler.address
                facts["connect_s"] = time.perf_counter() - begin
                facts["warm_up_s"] = warm_workers(dask_client, todo)
                begin = time.perf_counter()
                for task, row in submit_all(dask_client, todo):
                    done[task["case_id"]] = row
                    facts["ran"] += 1
                    facts["lost"] += row["status"] == "lost"
                    if bar is not None:
                        bar.update(1)
                    if on_row:
                        on_row(row)
                facts["run_s"] = time.perf_counter() - begin
    finally:
        if bar is not None:
            bar.close()
    facts["wall_time_s"] = time.perf_counter() - start
    return {case.index: done[case.case_id] for case in sweep.cases if case.case_id in done}, facts


@contextlib.contextmanager
def connect(client=None, scheduler=None, workers=None):
    """A Dask client: ``client`` as given (left open), one connected to ``scheduler`` (an address
    such as tcp://host:8786), or a new LocalCluster of ``workers`` processes (default: one per
    core) with one thread each; the ones made here are closed on leaving."""
    if client is not None:
        yield client
        return
    from distributed import Client, LocalCluster

    check_cluster_options(scheduler, workers)
    if scheduler is not None:
        try:
            made = Client(scheduler, timeout="10s")
        except (OSError, TimeoutError, ValueError) as error:
            raise InputError(f"cannot connect to the Dask scheduler at {scheduler}: {error}",
                             key="--scheduler") from None
        with made:
            yield made
        return
    # dashboard on any free port: never in the way of another cluster
    with LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                      dashboard_address=":0") as cluster, Client(cluster) as made:
        yield made


def check_cluster_options(scheduler, workers):
    """Refuse a worker count that is not a whole number >= 1, or one given with a scheduler."""
    if workers is None:
        return
    if scheduler is not None:
        raise InputError("applies to the local cluster only: a cluster given by --scheduler has its "
                         "own workers", key="--workers")
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise InputError(f"must be a whole number >= 1, got {workers!r}", key="--workers")


def warm_workers(client, tasks):
    """Load the kernels on every worker before any case (``tasks.warm`` with one task per distinct
    seabed kind, friction, integrator, element order and run kind): the first worker first, the
    others then in parallel. Returns {worker address: seconds}."""
    client.wait_for_workers(1)
    samples = {}
    for task in tasks:
        signature = (task["kind"] == "static",) + tuple(
            str(get_path(task["data"], key)) for key in (
                "seabed.kind", "friction.model", "solver.integrator", "solver.adaptive", "solver.assembly",
                "lines[*].order", "moordyn.file", "moordyn.order"))
        samples.setdefault(signature, task)
    samples = list(samples.values())
    addresses = sorted(client.scheduler_info()["workers"])
    first = client.submit(warm, samples, workers=[addresses[0]], allow_other_workers=False, pure=False)
    seconds = {addresses[0]: first.result()}
    rest = {a: client.submit(warm, samples, workers=[a], allow_other_workers=False, pure=False)
            for a in addresses[1:]}
    seconds.update({a: future.result() for a, future in rest.items()})
    return seconds


def submit_all(client, tasks):
    """Yield (task, row) as the cases finish: the shared cases with a bounded number in flight, then
    the ``alone`` cases one at a time. A task that Dask loses (its worker died, ...) gives a row
    with status "lost" and no done-marker, so that a re-run tries it again."""
    from distributed import as_completed

    threads = sum(w["nthreads"] for w in client.scheduler_info()["workers"].values()) or 1
    shared = [t for t in tasks if not t["alone"]]
    alone = [t for t in tasks if t["alone"]]
    for group, width in ((shared, IN_FLIGHT_PER_THREAD * threads), (alone, 1)):
        waiting = iter(group)
        running = {}
        finished = as_completed()

        def submit():
            task = next(waiting, None)
            if task is not None:
                future = client.submit(run_task, task, key=f"cablefem-case-{task['case_id']}", pure=False)
                running[future.key] = (task, future)
                finished.add(future)

        for _ in range(width):
            submit()
        try:
            for future in finished:
                task, _ = running.pop(future.key)
                try:
                    row = future.result()
                except Exception as error:  # noqa: BLE001 - lost to Dask, not failed by the case
                    row = {"status": "lost", "error": f"{type(error).__name__}: {' '.join(str(error).split())}"}
                future.release()
                submit()
                yield task, row
        finally:
            if running:  # interrupted: what has not finished is not wanted any more
                client.cancel([future for _, future in running.values()])


def _progress(progress, total, done):
    show = sys.stderr.isatty() if progress is None else progress
    if not show:
        return None
    from tqdm import tqdm

    return tqdm(total=total, initial=done, unit="case", desc="cablefem sweep")
