"""README, "Problems found" item 5: the down-slope case with MoorDyn's vertical contact at the file's
25 m elements (P1 x NumSegs), cablefem's BDF2 at fixed steps without the study's reruns at dt / 2,
with the seabed damper engaging over a depth (``cablefem.loads.contact.ramp_depth``) and switched on
in full at the surface (that depth zeroed: desire2023 Eq. 11 as MoorDyn's B_z). Prints, per damper
and step, whether the ramp-up and three periods pass, the rejected steps and the CPU time, or where
Newton stops.

    python -m validation.moordyn.damper_ramp [--dt 0.05 0.02 0.01]
"""

import argparse
import contextlib
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from cablefem.errors import ConvergenceError
from cablefem.io import load_scene
import cablefem.loads.contact as contact

from validation.moordyn.runners import run_cablefem_case
from validation.moordyn.switches import VerticalSeabed

SCENE = Path(__file__).resolve().with_name("inputs") / "housner-downslope.toml"
PERIODS = 3  # after the one-period ramp, as the study's housner cases


@contextlib.contextmanager
def damper_in_full():
    """Inside the block, contacts built anew switch their damper on in full at the surface (delta = 0)."""
    ramp_depth = contact.ramp_depth
    contact.ramp_depth = lambda setting, props, environment: np.zeros_like(np.asarray(props["mass"], dtype=float))
    try:
        yield
    finally:
        contact.ramp_depth = ramp_depth


def run(dt, ramp):
    """One run at step ``dt`` [s], the damper ramped or not: a line of text."""
    scene = load_scene(str(SCENE))
    scene = replace(scene, seabed=VerticalSeabed(scene.seabed))
    duration = scene.motion.ramp + PERIODS * scene.motion.period
    begin = time.process_time()
    with contextlib.nullcontext() if ramp else damper_in_full():
        try:
            result = run_cablefem_case(scene, duration, dt, retries=0)
        except ConvergenceError as error:
            return f"stops: {error}"
    return (f"passes {duration:g} s: {result['steps']} steps, {result['rejected_steps']} rejected, "
            f"{time.process_time() - begin:.1f} s CPU")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dt", type=float, nargs="+", default=[0.05, 0.02, 0.01], help="fixed steps [s]")
    args = parser.parse_args(argv)
    for ramp, name in ((True, "damper over a depth"), (False, "damper in full at the surface")):
        for dt in args.dt:
            print(f"{name}, dt {dt:g} s: {run(dt, ramp)}", flush=True)


if __name__ == "__main__":
    main()
