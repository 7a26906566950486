"""The work-precision study (verification/work_precision, issue 6) in its fast mode: errors that fall
with refinement at the rates the study reports, references converged to the stated level,
MoorDyn's stability search finding a limit, and the Pareto/ratio bookkeeping. No timings are
asserted (they vary with the machine's load; they go in the README tables). Numbers measured
with ``python -m verification.work_precision.run --fast`` are quoted beside the tolerances."""

import numpy as np
import pytest

from verification.work_precision import run as study


@pytest.fixture(scope="module")
def fast(dask_client):
    results, _ = study.run(fast=True, log=lambda *args: None, client=dask_client)
    return results


def _rows(entry, code, **settings):
    return [row for row in entry[code] if all(row["settings"][k] == v for k, v in settings.items())]


def test_slow_surge_time_error_converges_near_order_2(fast):
    # BDF2 on one mesh against the same mesh at dt 0.0025: 7.7e-4, 2.5e-4, 7.3e-5 (order 1.69,
    # rising towards 2 as dt falls: 1.64 then 1.75 between successive pairs)
    errors = fast["motions"]["slow-surge"]["time_order"]["errors"]
    assert errors[0] > errors[1] > errors[2]
    assert fast["motions"]["slow-surge"]["time_order"]["order"] >= 1.4


def test_snap_time_error_falls_about_first_order(fast):
    # snap loads: slack, touchdown and friction switches each step; measured 2.9e-2, 1.5e-2, 8.1e-3
    # (order 0.92). The README states this first order; the test keeps it from getting worse.
    t = fast["motions"]["snap"]["time_order"]
    assert t["errors"][0] > t["errors"][1] > t["errors"][2]
    assert 0.7 <= t["order"] <= 2.5


def test_cablefem_error_falls_with_elements(fast):
    # P1 at dt 0.02: 10, 20, 40 elements give 0.255, 0.192, 0.134 against the P3 x 40 reference
    errors = [_rows(fast["motions"]["snap"], "cablefem", order=1, elements=n, dt=0.02)[0]["error"]
              for n in (10, 20, 40)]
    assert errors[0] > errors[1] > errors[2]
    assert errors[0] / errors[2] > 1.5


def test_reference_is_time_converged_and_mesh_check_stated(fast):
    # the fast reference (P3 x 40, dt 0.0025) moves by 7.4e-3 when dt doubles and by 8.5e-2 when the
    # mesh halves: the fast mode resolves errors above ~0.1 only (the full study's references are
    # finer; README)
    checks = {c["label"]: c["change"] for c in fast["motions"]["snap"]["references"]["checks"]}
    assert checks["P3 x 40, BDF2, dt 0.005"] < 1.5e-2
    assert checks["P3 x 20, BDF2, dt 0.0025"] < 0.12


def test_moordyn_error_falls_with_segments_and_codes_agree_within_floor(fast):
    # MoorDyn at its largest stable dtM against 160 segments: 20 -> 0.198, 80 -> 0.100; the two
    # codes' finest fast runs differ by 0.102 (the coarse fast references; 1.7e-2 for the full ones)
    snap = fast["motions"]["snap"]
    first = {row["settings"]["segments"]: row["error"] for row in snap["moordyn"] if row["largest_stable_dtM"]}
    assert first[20] > first[80]
    assert snap["references"]["moordyn_vs_cablefem"] < 0.15


def test_moordyn_stability_search_finds_a_limit(fast):
    # the first dtM tried (0.01 s for 20 and 40 segments, 0.005 s for 80) blows up: the search
    # starts above the limit, so the largest stable dtM it reports is a measured one
    attempts = fast["motions"]["snap"]["moordyn_attempts"]
    for segments in (20, 40, 80):
        tried = [a for a in attempts if a["segments"] == segments]
        assert not tried[0]["stable"]
        assert any(a["stable"] for a in tried)


def test_every_moordyn_pareto_point_gets_a_ratio_row(fast):
    snap = fast["motions"]["snap"]
    front = study.pareto(snap["moordyn"])
    assert [row["moordyn"] for row in snap["ratios"]] == [row["label"] for row in front]
    for row in snap["ratios"]:
        if row["cablefem"] is not None:
            assert row["cablefem_error"] <= row["error"]
            assert row["ratio"] == pytest.approx(row["cablefem_s"] / row["moordyn_s"])


def test_pareto_keeps_only_undominated_rows():
    rows = [{"label": "a", "wall_time_s": 1.0, "error": 0.5}, {"label": "b", "wall_time_s": 2.0, "error": 0.6},
            {"label": "c", "wall_time_s": 3.0, "error": 0.1}, {"label": "d", "wall_time_s": 0.5, "error": 0.9}]
    assert [r["label"] for r in study.pareto(rows)] == ["d", "a", "c"]
    cablefem = [{"label": "x", "wall_time_s": 0.2, "error": 0.55}, {"label": "y", "wall_time_s": 0.7, "error": 0.05}]
    moordyn = [dict(r, peer_wall_time_s=r["wall_time_s"]) for r in rows]
    table = study.ratios(moordyn, cablefem)
    assert [r["cablefem"] for r in table] == ["x", "y", "y"]
    assert table[1]["ratio"] == pytest.approx(0.7 / 1.0)


def test_error_is_rms_over_the_window_relative_to_the_mean():
    t = np.linspace(0.0, 10.0, 1001)
    reference = {"t": t, "tension": 2.0 + np.sin(t)}
    shifted = {"t": t[::10], "tension": 2.0 + np.sin(t[::10]) + 0.02}
    assert study.error_against(reference, reference, 4.0) == 0.0
    assert study.error_against(shifted, reference, 4.0) == pytest.approx(
        0.02 / np.mean(2.0 + np.sin(t[::10][t[::10] >= 4.0])), rel=1e-12)


def test_common_study_row_runs_its_integrator_and_rho_inf():
    # verification/work_precision/common: a row's integrator, rho_inf and Newton reach the run. The
    # generalised-alpha row equals, to the bit, a run of the aligned scene (with MoorDyn-C's seabed
    # damper, as the study's rows) with [solver] integrator "generalized-alpha" and rho_inf 0.9, and
    # differs from the BDF2 row, from the row at rho_inf 0.8 and from the scene with Eq. 11's damper
    # (deterministic runs: any difference is the setting, not noise).
    from dataclasses import replace

    from validation.moordyn_aligned.run import aligned_scene
    from verification.work_precision.common import SEABED_DAMPER_OPENING, Row, cablefem_row
    from verification.work_precision.runs import run_cablefem_scene

    bdf2, alpha, other = Row(1, 14, 0.17), Row(1, 14, 0.17, 1e-4, "generalized-alpha", 0.9), \
        Row(1, 14, 0.17, 1e-4, "generalized-alpha", 0.8)
    assert (bdf2.label(), alpha.label()) == ("P1 x 14, dt 0.17", "P1 x 14, gen-a 0.9, dt 0.17")
    assert SEABED_DAMPER_OPENING
    scene = aligned_scene("slow", 1, 14, 0.17, tolerance=1e-4, damping_when_opening=True)
    scene.solver = replace(scene.solver, integrator="generalized-alpha", rho_inf=0.9)
    direct = run_cablefem_scene(scene)
    closing = replace(scene, contact=replace(scene.contact, damping_when_opening=False))
    auto = Row(1, 14, 0.17, 1e-4, "generalized-alpha", 0.9, "auto")
    assert auto.label() == "P1 x 14, gen-a 0.9, dt 0.17, auto Newton"
    runs = {row: cablefem_row("slow", row)[0]["tension"] for row in (bdf2, alpha, other, auto)}
    assert np.array_equal(runs[alpha], direct["tension"])
    mean = np.mean(direct["tension"])
    assert np.max(np.abs(runs[bdf2] - runs[alpha])) > 1e-4 * mean
    assert np.max(np.abs(runs[other] - runs[alpha])) > 1e-6 * mean
    assert np.max(np.abs(run_cablefem_scene(closing)["tension"] - runs[alpha])) > 1e-6 * mean
    # the row's Newton reaches the run too ("full" unless it says; "auto" keeps LU factors)
    scene.solver = replace(scene.solver, newton="auto")
    assert np.array_equal(runs[auto], run_cablefem_scene(scene)["tension"])
    assert not np.array_equal(runs[auto], runs[alpha])


def test_time_error_split_puts_a_ringing_in_its_band():
    # verification/work_precision/time_error: a run that differs from the fine one by a 1.5 Hz
    # ringing of 1 % of the mean has an RMS difference of 1 % / sqrt(2) over the window, all of
    # it in the 1-2 Hz band; the two candidate frequencies are their closed forms, the contact's
    # sqrt(k d / (m + m_a)) / 2 pi and the whole line's first axial mode sqrt(EA / m) / 2 L
    from cablefem.model.builtin import table5_chain
    from verification.work_precision.time_error import axial_frequency, contact_frequency, split

    t = np.arange(0.0, 40.0, 0.01)
    fine = {"t": t, "tension": np.full_like(t, 2.0e6)}
    ringing = {"t": t[::2], "tension": 2.0e6 * (1.0 + 0.01 * np.sin(2 * np.pi * 1.5 * t[::2]))}
    found = split(ringing, fine, 20.0)
    assert found["rms"] == pytest.approx(0.01 / np.sqrt(2), rel=1e-3)
    shares = {tuple(b["band_Hz"]): b["share"] for b in found["bands"]}
    assert shares[(1.0, 2.0)] == pytest.approx(1.0, abs=1e-6)
    chain = table5_chain()
    mass = chain.mass + chain.Ca_normal * 1025.0 * np.pi * chain.diameter ** 2 / 4
    assert contact_frequency() == pytest.approx(np.sqrt(3.0e5 * chain.diameter / mass) / (2 * np.pi), rel=1e-12)
    assert contact_frequency(stiffness_factor=4.0) == pytest.approx(2.0 * contact_frequency(), rel=1e-12)
    assert axial_frequency() == pytest.approx(np.sqrt(3.15e9 / 835.4) / (2 * 635.0), rel=1e-12)
    assert axial_frequency(4.0) == pytest.approx(2.0 * axial_frequency(), rel=1e-12)


def test_common_study_repeats_rows_in_passes_over_all_of_them():
    # verification/work_precision/common: each row runs once, then its repeats (REPEATS by its first
    # time) come in passes over every row, so a slow minute of the machine meets all rows alike;
    # the least CPU time is kept with the first run's result
    from verification.work_precision.common import REPEATS, interleaved_least_cpu, repeats

    calls, times = [], {"a": [0.1, 0.05, 0.3, 0.2, 0.08], "b": [2.0, 1.5], "c": [5.0]}

    def row(name):
        def run():
            calls.append(name)
            return f"result {name}", times[name][sum(1 for c in calls if c == name) - 1]
        return run

    found = interleaved_least_cpu([row("a"), row("b"), row("c")])
    assert [repeats(0.1), repeats(2.0), repeats(5.0)] == [5, 2, 1] and REPEATS[0] == (0.2, 5)
    assert calls == ["a", "b", "c", "a", "b", "a", "a", "a"]
    assert found == [("result a", 0.05), ("result b", 1.5), ("result c", 5.0)]
