"""Compile the kernels most tests share into numba's on-disk cache, one integrator per process:
``python tests/warm_kernels.py bdf2`` (or ``generalized-alpha``). tests/conftest.py runs one process
per integrator side by side before pytest-xdist's workers start, so that the workers load these
kernels rather than both compiling them at once; what else a test needs, its worker compiles.

What compiles: a short run of the flat flume chain on the compiled kernel (its statics, the line's
steps with tension, weight, contact, friction, drag and added mass on a plane) with the integrator
given, and a short run of benchmarks/crowfoot.toml: the steps of strings that meet at a junction,
compiled once for every network (a typed List of strings), which several test files would otherwise
compile at once on both workers.
"""

import sys
import tempfile
from dataclasses import replace
from pathlib import Path

from cablefem.io import load_scene
from cablefem.model.builtin import flume_scene
from cablefem.runs.run import run_scene

CROWFOOT = Path(__file__).resolve().parents[1] / "benchmarks" / "crowfoot.toml"


def main(integrator):
    """Run the flat flume and the crowfoot for a few steps with ``integrator``."""
    flume = flume_scene("flat", elements=10, duration=0.05)
    for scene, duration in ((flume, None), (load_scene(str(CROWFOOT)), 0.1)):
        scene = replace(scene, solver=replace(scene.solver, integrator=integrator))
        with tempfile.TemporaryDirectory(prefix="cablefem-warm-") as folder:
            run_scene(scene, folder, duration=duration, progress=False)


if __name__ == "__main__":
    main(sys.argv[1])
