"""desire2023 Sec. 5 (irregular seabed, Figs. 18-20, Table 6) on the fast variant of
validation/irregular_seabed/run.py: 40 P1 elements, dt = 0.02 s, 24 s on three seeds.

validation/irregular_seabed/README.md has the full run's numbers and says which of the
paper's findings hold on every realisation (asserted here) and which depend on the seed
(asserted here to depend on it, from the static sweep over ten realisations).
Run times (Table 6) are measured and reported by the study, not asserted: they change
with the machine's load and with every optimisation of the projection or the step.
"""

import json

import numpy as np
import pytest

from validation.irregular_seabed import run as study


@pytest.fixture(scope="module")
def fast():
    """The fast variant's results (about 30-40 s on one core)."""
    return study.run(fast=True)


def _runs(results):
    return [(entry["seed"], m, entry["methods"][m]) for entry in results["seeds"] for m in study.METHODS]


def test_every_seed_and_seabed_model_runs_to_the_end(fast):
    failed = [(seed, m, r["error"] or r["status"]) for seed, m, r in _runs(fast) if not r.get("completed")]
    assert not failed
    assert len(fast["seeds"]) == len(study.SETTINGS["fast"]["seeds"])


@pytest.mark.parametrize("path", study.COST_PATHS)
def test_triangulated_horizontal_seabed_gives_the_horizontal_plane_tensions_to_1e8(fast, path):
    # The vertex normals of a level mesh are all (0, 0, 1) and the gap is z + 93.5 m, so the
    # general projection must reproduce the point-to-plane one to round-off (README: measured
    # difference); 1e-8 relative is the Newton tolerance, the loosest honest bound.
    rows = fast["table6"]["paths"][path]["rows"]
    assert len(rows) == 3
    for row in rows:
        assert row["horizontal"]["completed"] and row["general"]["completed"]
        assert row["horizontal"]["steps"] == row["general"]["steps"]
        assert row["max_relative_tension_difference"] <= 1e-8


def test_the_three_seabed_models_give_different_touchdown_points(fast):
    # primary seed: measured -142.9, -152.4 and -167.9 m at t = 6 s (pairwise >= 9.5 m);
    # 3 m is several times the touchdown's interpolation error (a fraction of a 16 m element)
    # and the fast-vs-full difference (<= 4 m, README)
    entry = next(e for e in fast["seeds"] if e["seed"] == study.PRIMARY_SEED)
    x = [entry["methods"][m]["touchdown_x_m"] for m in study.METHODS]
    assert all(np.isfinite(x))
    assert min(abs(a - b) for k, a in enumerate(x) for b in x[k + 1:]) > 3.0


def test_horizontal_mean_depth_plane_gives_higher_tension_than_inclined_plane_on_every_seed(fast):
    # desire2023 Sec. 5: z-bar lies deeper than the least-squares plane under the touchdown,
    # so more line hangs and the tension is higher, "in the whole temporal series". The
    # planes do not depend on the seed (diamond_square imposes them), so this holds on every
    # realisation; measured 2.435 vs 2.286 MN (peak), 2.109 vs 1.975 MN (mean): > 0.1 MN apart.
    for entry in fast["seeds"]:
        runs = entry["methods"]
        assert runs["horizontal"]["total_peak_N"] - runs["inclined"]["total_peak_N"] > 0.1e6
        assert runs["horizontal"]["mean_N"] - runs["inclined"]["mean_N"] > 0.1e6
        # ... and the inclined touchdown lies nearer the fairlead (Fig. 19); measured 15.5 m
        assert runs["inclined"]["touchdown_x_m"] - runs["horizontal"]["touchdown_x_m"] > 5.0


def test_plane_peaks_are_near_the_papers_2_4_and_2_2_mn(fast):
    # The anchor x was chosen for the horizontal peak (2.4 MN); the inclined one follows from
    # the chosen tilt. 10 % covers reading the text's one-digit values and the fast settings.
    runs = fast["seeds"][0]["methods"]
    assert runs["horizontal"]["total_peak_N"] == pytest.approx(2.4e6, rel=0.10)
    assert runs["inclined"]["total_peak_N"] == pytest.approx(2.2e6, rel=0.10)


def test_line_on_the_irregular_seabed_rests_on_less_of_it_than_on_either_plane(fast):
    # Robust on every seed tried (full run: 5 seeds, README): the line bridges the troughs of
    # the rough seabed, so less of it lies on the ground. Measured 148-168 m against 429-445 m
    # (fast); 0.8x is far from both.
    for entry in fast["seeds"]:
        runs = entry["methods"]
        planes = min(runs["inclined"]["grounded_length_m"], runs["horizontal"]["grounded_length_m"])
        assert runs["general"]["grounded_length_m"] < 0.8 * planes


def test_whether_the_irregular_seabed_raises_the_tension_depends_on_the_realisation(fast):
    # The paper's "general projection gives the highest tension" is one realisation: over ten
    # seeds the static tension at the largest surge falls on both sides of both planes
    # (measured: above the inclined plane on 6/10, above both on 3/10).
    row = fast["static_sweep"]["amplitudes"][0]
    assert not row["failures"]
    assert 0.0 < row["fraction_above_inclined"] < 1.0
    assert 0.0 < row["fraction_above_both"] < 1.0


def test_outputs_are_written(fast, tmp_path):
    written = study.write_outputs(fast, tmp_path)
    for name in ("fig19_positions.png", "fig20_tensions.png", "seeds.png", "results.json"):
        assert name in written and (tmp_path / name).stat().st_size > 1000
    results = json.loads((tmp_path / "results.json").read_text())
    assert results["table6"]["max_relative_tension_difference"] <= 1e-8
