"""cablefem's mooring networks against MoorDyn-C and MoorPy (``validation/networks``, fast variant:
the shared line between two coupled platforms at half the file's segments (50 m chain, 40 m
polyester), MoorDyn dtM 1e-3 s, cablefem dt 0.05 s, one period after the ramp; the semi-taut
system's statics in P2 elements at the file's mesh, platform fixed and free; ~1 min in all).

Tolerances: the converged comparison (validation/networks/README.md) plus what the coarse settings
add, each measured at the fast settings:

- bodies: each platform's six force and moment components differ by at most 0.21 % RMS (of the
  mean force's magnitude, of the largest moment) at the fast settings: 1 %.
- mooring chains' fairlead tensions: at most 0.30 % RMS, 0.02 % in the mean: 1 % and 0.2 %.
- the shared polyester line (at its fairleads and at the clump): 1.55-1.80 % RMS, peaks 1.9-2.8 %
  apart, means 0.03 % at 40 m segments and dt 0.05 s (0.46-0.53 % RMS at 20 m and 0.02 s, the
  README's coarse run): RMS 3 %, mean 0.2 %.
- the clump's position: 0.4 % of its motion range RMS: 2 %.
- statics, platform fixed, P2 at the file's mesh: 4.1e-4 largest relative end-tension difference
  from MoorPy over the 18 line ends, 2.2e-4 m for the clumps and buoys (the mesh convergence
  reaches 1e-4 at twice the elements and 2.5e-5 at four times: README): 1e-3 and 1e-3 m.
- statics, platform free under a 0.2 MN steady load: offset 23.5 m; cablefem's is 0.10 m from
  MoorPy's, its rotation matrix 7e-5 and its tensions 2.6e-3 apart at this mesh (the network
  statics fit no vertex to the touchdown, so they converge more slowly: README): 0.2 m, 2e-4, 5e-3.
"""

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("moordyn")
pytest.importorskip("moorpy")

from validation.networks import run as study  # noqa: E402

COMMITTED = Path(study.__file__).resolve().parent / "inputs"


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    out = tmp_path_factory.mktemp("networks")
    found, _ = study.run(fast=True, out_dir=out, log=lambda *args: None)
    found["out"] = out
    return found


def _rows(results, kind):
    return [r for r in results["dynamics"]["shared"]["rows"] if kind(r["what"])]


def test_each_platforms_six_component_mooring_load_agrees_with_moordyn(results):
    rows = _rows(results, lambda what: what.split()[0] in ("A", "B"))
    assert len(rows) == 12
    assert max(r["rms"] for r in rows) <= 0.01
    forces = [r for r in rows if r["what"].endswith("Fx")]
    assert all(abs(r["reference_mean"]) > 5e5 for r in forces)  # the shared line and the chains pull


def test_mooring_fairlead_tensions_agree_with_moordyn(results):
    rows = _rows(results, lambda what: what.startswith("fairlead"))
    assert len(rows) == 4
    assert max(r["rms"] for r in rows) <= 0.01
    assert max(abs(r["mean"]) for r in rows) <= 2e-3


def test_shared_line_tensions_at_its_ends_and_at_the_clump_agree_with_moordyn(results):
    rows = _rows(results, lambda what: what.startswith("share"))
    assert len(rows) == 4
    assert max(r["rms"] for r in rows) <= 0.03
    assert max(abs(r["mean"]) for r in rows) <= 2e-3
    (clump,) = _rows(results, lambda what: what == "clump position")
    assert clump["range_m"] > 3.0 and clump["rms"] <= 0.02


def test_fixed_platform_statics_agree_with_moorpy(results):
    (mesh,) = results["statics_fixed"]["meshes"]
    assert mesh["largest_relative"] <= 1e-3
    assert mesh["largest_distance_m"] <= 1e-3


def test_free_platform_offset_and_tensions_agree_with_moorpy(results):
    free = results["statics_free"]
    assert np.linalg.norm(free["moorpy"]["offset"][:2]) > 20.0  # a real offset
    (mesh,) = free["meshes"]
    assert mesh["offset_difference_m"] <= 0.2
    assert mesh["rotation_difference"] <= 2e-4
    assert mesh["largest_relative"] <= 5e-3


def test_committed_inputs_are_what_the_script_writes(results):
    written = results["out"] / "inputs"
    names = sorted(p.name for p in COMMITTED.iterdir())
    assert names == sorted(p.name for p in written.iterdir())
    for name in names:
        assert (COMMITTED / name).read_text() == (written / name).read_text(), name
