"""Shared fixtures: the desire2023 Table 5 chain and small systems built from it; the toy catalog's
process (``tests/test_catalog_extension.py``), started beside the other tests."""

import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import pytest

os.environ.setdefault("PYTHONBREAKPOINT", "0")  # MoorPy calls breakpoint() before some raises
os.environ.setdefault("MPLBACKEND", "Agg")

from cablefem import Line, LineType, Segment  # noqa: E402
from cablefem.compiled import progress  # noqa: E402

# the test processes do not announce their compilations: tests read their own stderr line by line
# (commands run in a child process still do: tests/test_first_run.py)
progress.ANNOUNCE.said = True

# pytest-xdist's workers start with SIGINT ignored, and a child process inherits an ignored signal:
# the tests that interrupt a run (tests/test_signals.py, tests/test_output.py) need Python's handler
signal.signal(signal.SIGINT, signal.default_int_handler)


@pytest.fixture
def chain():
    """The Table 5 chain of desire2023 (prototype scale)."""
    return LineType("chain", diameter=0.3539, mass=835.4, EA=3.15e9, damping=0.001,
                    Cd_normal=2.5, Cd_tangential=0.5, Ca_normal=3.8, Ca_tangential=0.0)


@pytest.fixture
def rng():
    return np.random.default_rng(20261123)


def make_line(line_type, order=1, elements=20, anchor=(-600.0, 0.0, -100.0), fairlead=(0.0, 0.0, 0.0),
              length=635.0):
    """A one-segment line of ``line_type``; ``order`` "hermite": on Hermite elements."""
    if order == "hermite":
        return Line("line1", anchor, fairlead, [Segment(line_type, length, elements)], element="hermite")
    return Line("line1", anchor, fairlead, [Segment(line_type, length, elements)], order)


@pytest.fixture(scope="session")
def dask_client():
    """One Dask LocalCluster for the tests that run sweeps: two worker processes of one thread,
    as ``cablefem sweep`` starts on this 2-core machine (closed after the session)."""
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, \
            Client(cluster) as client:
        yield client


TESTS = Path(__file__).resolve().parent
TOY_TESTS = "test_catalog_extension.py"
#: where pytest-xdist's workers find the toy catalog's process, which their controller started
TOY_FOLDER = "CABLEFEM_TOY_FOLDER"


class ToyCatalog:
    """The process that registers the toy loads (``tests/toy_loads.py``) and measures them. The
    kernels are compiled for one catalog, so it compiles every kernel once more in its own numba
    cache (~2-4 min on one core): started when its tests are collected (under pytest-xdist, by the
    controller before the workers start), it runs on the machine's second core while the other tests
    run, and its tests are ordered last (``measured`` waits). ``folder``: attach to the process
    another pytest process started there."""

    def __init__(self, folder=None):
        self.owner = folder is None
        self.folder = Path(folder or tempfile.mkdtemp(prefix="cablefem-toy-"))
        self.stdout, self.stderr, self.returncode = (self.folder / name for name in ("stdout", "stderr", "returncode"))
        self._measured = None
        if not self.owner:
            return
        env = dict(os.environ, NUMBA_CACHE_DIR=str(self.folder / "numba"),
                   PYTHONPATH=os.pathsep.join([str(TESTS.parent), os.environ.get("PYTHONPATH", "")]))
        with open(self.stdout, "w") as out, open(self.stderr, "w") as err:
            self.process = subprocess.Popen([sys.executable, str(TESTS / "toy_loads.py"), str(self.folder)],
                                            stdout=out, stderr=err, env=env)
        threading.Thread(target=self._record_exit, daemon=True).start()

    def _record_exit(self):
        """The process's exit status into a file, for whichever pytest process runs the toy tests."""
        code = self.process.wait()
        try:
            self.returncode.write_text(str(code))
        except OSError:  # closed: the folder is gone
            pass

    def measured(self, timeout=1200):
        """The toy process's measurements (its JSON), once it has finished."""
        if self._measured is None:
            deadline = time.monotonic() + timeout
            while not self.returncode.exists() or not self.returncode.read_text():
                assert time.monotonic() < deadline, f"the toy catalog's process took over {timeout} s"
                time.sleep(0.5)
            assert self.returncode.read_text() == "0", self.stderr.read_text()[-3000:]
            self._measured = json.loads(self.stdout.read_text())
        return self._measured

    def close(self):
        if not self.owner:
            return
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()
        shutil.rmtree(self.folder, ignore_errors=True)


_toy = []  # the session's ToyCatalog, if its tests were collected (or, under xdist, may be)


def _xdist_controller(config):
    """True in the process that hands tests to pytest-xdist's workers (``-n 2``; not with ``-n 0``)."""
    return not hasattr(config, "workerinput") and bool(getattr(config.option, "numprocesses", None))


def _may_collect(config, name):
    """True if the command line's paths may collect the test file ``name``."""
    paths = [Path(arg.split("::")[0]).resolve() for arg in config.args] or [Path(config.rootpath, "tests")]
    return any(path == TESTS / name or path in (TESTS / name).parents for path in paths)


def pytest_configure(config):
    """Under pytest-xdist, before the workers start: the toy catalog's process (if its tests may run)
    and the kernels most tests share, one integrator per process side by side (``tests/warm_kernels.py``)."""
    if not _xdist_controller(config):
        return
    if _may_collect(config, TOY_TESTS):
        _toy.append(ToyCatalog())
        os.environ[TOY_FOLDER] = str(_toy[0].folder)  # the workers inherit it
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(TESTS.parent), os.environ.get("PYTHONPATH", "")]))
    start = time.perf_counter()
    warming = [subprocess.Popen([sys.executable, str(TESTS / "warm_kernels.py"), integrator], env=env,
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
               for integrator in WARM]
    for integrator, process in zip(WARM, warming):
        stderr = process.communicate()[1]
        if process.returncode:  # not an error of its own: the tests that compile these will fail
            print(f"tests/warm_kernels.py {integrator} failed:\n{stderr[-2000:]}", file=sys.stderr)
    config.warm_seconds = time.perf_counter() - start


def pytest_report_header(config):
    if hasattr(config, "warm_seconds"):
        return f"cablefem: the kernels most tests share compiled before the workers started in {config.warm_seconds:.0f} s"


#: the integrators whose kernels ``pytest_configure`` compiles, one process each
WARM = ("bdf2", "generalized-alpha")


def pytest_collection_modifyitems(session, config, items):
    """The toy catalog's tests last: their process then compiles while the others run."""
    items.sort(key=lambda item: item.path.name == TOY_TESTS)  # stable: the others keep their order


def pytest_collection_finish(session):
    if not _toy and os.environ.get(TOY_FOLDER) is None and any(item.path.name == TOY_TESTS for item in session.items):
        _toy.append(ToyCatalog())


def pytest_unconfigure(config):
    while _toy:
        _toy.pop().close()


@pytest.fixture(scope="session")
def toy_catalog():
    """The toy catalog's process (started at collection, or by xdist's controller; here if it was not)."""
    if not _toy:
        _toy.append(ToyCatalog(os.environ.get(TOY_FOLDER)))
    return _toy[0]
