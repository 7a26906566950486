"""The sweep file without a cluster: key paths, how axes combine, tension statistics and the
rainflow fatigue damage (cablefem.sweeps.paths, .spec, .stats)."""

import math
from pathlib import Path

import numpy as np
import pytest

from cablefem.errors import InputError
from cablefem.sweeps import build_sweep
from cablefem.sweeps.paths import get_path, parse_path, set_path
from cablefem.sweeps.stats import YEAR_S, fatigue_damage, tension_statistics

ROOT = Path(__file__).resolve().parents[1]
FLAT = str(ROOT / "examples" / "flume_flat.toml")


def test_key_paths_reach_tables_arrays_and_every_entry():
    data = {"lines": [{"segments": [{"elements": 4}, {"elements": 5}]}, {"segments": [{"elements": 6}]}]}
    set_path(data, "lines[*].segments[*].elements", 9)
    assert get_path(data, "lines[*].segments[*].elements") == 9
    set_path(data, "lines[1].segments[0].elements", 3)
    assert get_path(data, "lines[*].segments[*].elements") == [9, 9, 3]
    set_path(data, "solver.dt", 0.02)  # a table the data lacks is made
    assert data["solver"] == {"dt": 0.02} and get_path(data, "motion.period") is None
    set_path(data, "soil.su_gradient", 1500.0)  # any key: the scene reader decides what is valid
    assert data["soil"]["su_gradient"] == 1500.0
    assert parse_path("lines[0].order")[:2] == ["lines", 0]
    for bad in ("lines[x].order", "motion..period", "", "lines[-1]"):
        with pytest.raises(InputError):
            parse_path(bad)


def sweep_of(**spec):
    return build_sweep({"base": FLAT, **spec}, str(ROOT))


def test_product_zip_and_cases_combine_in_the_order_written():
    product = sweep_of(axes={"motion.period": [6.0, 8.0], "solver.dt": [0.01, 0.02, 0.04]})
    assert [(c.params["motion.period"], c.params["solver.dt"]) for c in product.cases][:4] == [
        (6.0, 0.01), (6.0, 0.02), (6.0, 0.04), (8.0, 0.01)]
    zipped = sweep_of(combine="zip", axes={"motion.period": [6.0, 8.0], "solver.dt": [0.01, 0.02]})
    assert [(c.params["motion.period"], c.params["solver.dt"]) for c in zipped.cases] == [(6.0, 0.01), (8.0, 0.02)]
    listed = sweep_of(cases=[{"tag.name": "a", "motion": {"period": 7.0}}, {"tag.name": "b", "solver.dt": 0.03}],
                      axes={"lines[*].order": [1, 2]})
    assert [(c.tags["tag.name"], c.params["lines[*].order"]) for c in listed.cases] == [
        ("a", 1), ("a", 2), ("b", 1), ("b", 2)]
    assert listed.cases[2].params["motion.period"] == 6.0  # the base's value where a case sets none


def test_same_run_twice_has_one_identity_and_kinds_differ():
    spec = sweep_of(blocks=[{"axes": {"solver.dt": [0.01, 0.02]}}, {"axes": {"solver.dt": [0.02]}},
                            {"set": {"kind": "static"}, "axes": {"solver.dt": [0.02]}}])
    ids = [c.case_id for c in spec.cases]
    assert ids[1] == ids[2] and len(set(ids)) == 3


def test_axis_key_varied_twice_in_a_block_is_refused():
    with pytest.raises(InputError, match="varied by two axes"):
        sweep_of(axes={"solver.dt": [0.01]}, zip=[{"solver.dt": [0.02]}])


def test_statistics_are_time_averages_over_the_window():
    t = np.array([0.0, 1.0, 2.0, 4.0])  # an uneven step counts by the time it covers
    tension = np.array([1.0, 3.0, 1.0, 1.0])
    stats = tension_statistics(t, tension)
    assert stats["max"] == 3.0 and stats["max_t"] == 1.0 and stats["min_t"] == 0.0
    assert stats["mean"] == pytest.approx((2.0 + 2.0 + 2.0) / 4.0, rel=1e-15)
    # (T - 1.5)^2 is 0.25, 2.25, 0.25, 0.25 at the samples; trapezoids of widths 1, 1, 2: 1.25 + 1.25 + 0.5
    assert stats["std"] == pytest.approx(math.sqrt(3.0 / 4.0), rel=1e-15)
    late = tension_statistics(t, tension, t_from=2.0)
    assert (late["max"], late["mean"], late["std"]) == (1.0, 1.0, 0.0)


def test_fatigue_damage_of_a_sine_is_miners_sum_of_its_cycles():
    # 10 periods of range 2 MN from trough to trough on 0.061 m^2: S = 32.8 MPa; ASTM E1049 counts
    # them as 20 half cycles (an alternating series closes no cycle), 10 cycles in all:
    # D = 10 S^3 / 6e10 on DNV's studless chain curve
    t = np.linspace(0.0, 100.0, 4001)
    tension = 3e6 - 1e6 * np.cos(2 * np.pi * t / 10.0)
    damage = fatigue_damage(t, tension, 0.061, 6.0e10, 3.0)
    stress = 2e6 / 0.061 / 1e6
    assert damage["cycles"] == 10.0
    assert damage["damage"] == pytest.approx(10 * stress ** 3 / 6.0e10, rel=1e-9)
    assert damage["damage_per_year"] == pytest.approx(damage["damage"] * YEAR_S / 100.0, rel=1e-12)
    # a fourth of the window: a fourth of the damage
    assert fatigue_damage(t, tension, 0.061, 6.0e10, 3.0, t_from=75.0)["damage"] == pytest.approx(
        damage["damage"] / 4, rel=1e-9)


SHIPPED = sorted([*ROOT.glob("examples/sweeps/*.toml"), *ROOT.glob("verification/*/sweep*.toml"),
                  *(p for p in ROOT.glob("validation/flume/*.toml") if p.name != "flume.toml")])


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: str(p.relative_to(ROOT)))
def test_shipped_sweep_files_are_valid(path):
    from cablefem.sweeps import read_sweep

    spec = read_sweep(path)
    assert spec.cases and len({c.case_id for c in spec.cases}) <= len(spec.cases)
