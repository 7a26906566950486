"""Shared fixtures: the desire2023 Table 5 chain and small systems built from it."""

import os

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
    """A one-segment line of ``line_type``."""
    return Line("line1", anchor, fairlead, [Segment(line_type, length, elements)], order)


@pytest.fixture(scope="session")
def dask_client():
    """One Dask LocalCluster for the tests that run sweeps: two worker processes of one thread,
    as ``cablefem sweep`` starts on this 2-core machine (closed after the session)."""
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, \
            Client(cluster) as client:
        yield client
