"""Shared fixtures: the desire2023 Table 5 chain and small systems built from it; the toy catalog's
process (``tests/test_catalog_extension.py``), started beside the other tests."""

import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest

os.environ.setdefault("PYTHONBREAKPOINT", "0")  # MoorPy calls breakpoint() before some raises
os.environ.setdefault("MPLBACKEND", "Agg")

from cablefem import Line, LineType, Segment  # noqa: E402


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


class ToyCatalog:
    """The process that registers the toy loads (``tests/toy_loads.py``) and measures them. The
    kernels are compiled for one catalog, so it compiles every kernel once more in its own numba
    cache (~2-4 min on one core): started when its tests are collected, it runs on the machine's
    second core while the other tests run, and its tests are ordered last (``measured`` waits)."""

    def __init__(self):
        self.folder = Path(tempfile.mkdtemp(prefix="cablefem-toy-"))
        env = dict(os.environ, NUMBA_CACHE_DIR=str(self.folder / "numba"),
                   PYTHONPATH=os.pathsep.join([str(TESTS.parent), os.environ.get("PYTHONPATH", "")]))
        self.stdout, self.stderr = self.folder / "stdout", self.folder / "stderr"
        with open(self.stdout, "w") as out, open(self.stderr, "w") as err:
            self.process = subprocess.Popen([sys.executable, str(TESTS / "toy_loads.py"), str(self.folder)],
                                            stdout=out, stderr=err, env=env)
        self._measured = None

    def measured(self, timeout=1200):
        """The toy process's measurements (its JSON), once it has finished."""
        if self._measured is None:
            code = self.process.wait(timeout=timeout)
            assert code == 0, self.stderr.read_text()[-3000:]
            self._measured = json.loads(self.stdout.read_text())
        return self._measured

    def close(self):
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()
        shutil.rmtree(self.folder, ignore_errors=True)


_toy = []  # the session's ToyCatalog, if its tests were collected


def pytest_collection_modifyitems(session, config, items):
    """The toy catalog's tests last: their process then compiles while the others run."""
    items.sort(key=lambda item: item.path.name == TOY_TESTS)  # stable: the others keep their order


def pytest_collection_finish(session):
    if any(item.path.name == TOY_TESTS for item in session.items):
        _toy.append(ToyCatalog())


def pytest_sessionfinish(session, exitstatus):
    while _toy:
        _toy.pop().close()


@pytest.fixture(scope="session")
def toy_catalog():
    """The toy catalog's process (started at collection; here if it was not)."""
    if not _toy:
        _toy.append(ToyCatalog())
    return _toy[0]
