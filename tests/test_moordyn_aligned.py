"""cablefem and MoorDyn-C with aligned physics on the frictionless flume chain (``validation/moordyn_aligned``,
fast variant: the ramp and one period; ~10 s).

Tolerances, from the full study (validation/moordyn_aligned/README.md) plus what the coarse settings add:

- slow surge: the finest runs agree to 0.02 % RMS and 0.01 % in the mean. At the fast settings
  MoorDyn's 80 segments are 0.23 % RMS and +0.64 % in the peak from its 640-segment run, cablefem's
  P2 x 40 (dt 0.01 s) 0.11 % and -0.03 %: RMS 0.4 %, peak 1 % (measured 0.27 %, -0.67 %). The mean
  is what the weight, buoyancy, EA and the seabed decide, and it agrees at any resolution: 0.02 %
  (measured 0.00 %).
- snap, MoorDyn's coupling step: moving the fairlead along the secant of the motion every 0.01 s
  instead of every 0.001 s changes MoorDyn's snap tension by 0.46 % RMS at 40 segments (0.95 % at
  320): the switch must remove a difference that is there, > 0.2 %.
- ``damping_when_opening``: MoorDyn-C's seabed damping acts on a penetrating point moving out too.
- a wrapped load (the study's switches) has its load's spec (``catalog.spec_of``, ``.wrapped``).
"""

import numpy as np
import pytest

pytest.importorskip("moordyn")

from cablefem.geometry import Plane  # noqa: E402
from cablefem.loads import State  # noqa: E402
from cablefem.loads.contact import SeabedContact  # noqa: E402

from validation.moordyn_aligned import run as study  # noqa: E402


@pytest.fixture(scope="module")
def results():
    return study.run(fast=True, log=lambda *args: None)


def test_frictionless_slow_surge_agrees_with_moordyn_at_coarse_settings(results):
    d = results["slow"]["finest"]["cablefem_vs_moordyn"]
    assert d["rms"] < 4e-3
    assert abs(d["mean"]) < 2e-4
    assert abs(d["peak"]) < 1e-2


def test_moordyn_coupling_step_changes_its_snap_tension(results):
    assert results["snap"]["switches"]["coupling"]["difference"]["rms"] > 2e-3


def test_the_opening_damper_pulls_a_penetrating_point_moving_out_and_leaves_a_closing_one():
    # ``[seabed] damping_when_opening`` (MoorDyn-C's law), the switch of this study
    seabed = Plane((0.0, 0.0, -100.0), (0.0, 0.0, 1.0))
    contact, opening = SeabedContact(seabed, [1e5], [2e4]), SeabedContact(seabed, [1e5], [2e4], opening=True)
    r = np.array([0.0, 0.0, -100.01]).reshape(3, 1, 1)
    dr = np.array([1.0, 0.0, 0.0]).reshape(3, 1, 1)
    for vz, extra in ((-0.1, 0.0), (0.1, -2e4 * 0.1)):
        state = State(r=r, dr=dr, v=np.array([0.0, 0.0, vz]).reshape(3, 1, 1))
        plain, both = contact.evaluate(state), opening.evaluate(state)
        assert both.force[2, 0, 0] - plain.force[2, 0, 0] == pytest.approx(extra, rel=1e-12, abs=1e-12)
        h = 1e-7
        moved = State(r=r, dr=dr, v=np.array([0.0, 0.0, vz + h]).reshape(3, 1, 1))
        slope = (opening.evaluate(moved, jacobian=False).force[2, 0, 0] - both.force[2, 0, 0]) / h
        assert both.force_v[2, 2, 0, 0] == pytest.approx(slope, rel=1e-6)


def test_friction_variant_acts_alike_in_both_codes():
    # verification/work_precision/common_friction: the flume's friction (mu 0.3 to 0.01 m/s) in both
    # codes, MoorDyn's FricDamp scaled with its segments. Slow surge, 20 s, window 10-20 s: MoorDyn
    # at 40 segments and cablefem P1 x 40 (dt 0.02 s) agree to 0.60 % RMS with friction; MoorDyn's
    # own run without friction is 2.4 % away from its run with it, so the friction does act.
    from verification.work_precision.common_friction import (cablefem_friction_series, friction_scene,
                                                             moordyn_friction_series)

    scene = friction_scene("slow", 1, 40, 0.02, duration=20.0)
    assert scene.friction.model == "isotropic" and scene.friction.mu == 0.3
    assert all(s.type.damping_when_slack for s in scene.lines[0].segments)
    with_friction = moordyn_friction_series("slow", 40, 2.5e-3, duration=20.0)
    without = study.moordyn("slow", 40, 2.5e-3, coupling=0.01, duration=20.0)
    cablefem = cablefem_friction_series("slow", 1, 40, 0.02, duration=20.0)
    assert study.compare(cablefem, with_friction, 10.0)["rms"] < 0.01
    assert study.compare(without, with_friction, 10.0)["rms"] > 0.015


def test_a_run_with_a_wrapped_load_steps_and_commits():
    # PerUnstretchedLength wraps drag and added mass (``.wrapped``) and runs on the numpy path,
    # which commits the history of the loads' specs: a wrapper must have its load's spec (it had
    # none before the ``wrapped`` protocol, and every wrapped run stopped at its first step).
    # Drag and added mass per unstretched length are over |r'| = 1 + e, e < 1e-3 here: the
    # tension changes by less than 1e-3 of the hydrodynamic loads' share (measured 1.1e-5 of the mean)
    from validation.moordyn.runners import run_cablefem_case

    scene = study.aligned_scene("slow", 1, 20, 0.05, duration=3.0)
    aligned = run_cablefem_case(scene, 3.0, 0.05)["tensions"][:, 0]
    hydro = run_cablefem_case(scene, 3.0, 0.05, hydro_per_unstretched=True)["tensions"][:, 0]
    assert 0.0 < np.max(np.abs(hydro - aligned)) < 1e-3 * aligned.mean()
