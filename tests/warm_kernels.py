"""Compile the kernels most tests share into numba's on-disk cache, one integrator per process:
``python tests/warm_kernels.py bdf2`` (or ``generalized-alpha``). tests/conftest.py runs one process
per integrator side by side before pytest-xdist's workers start, so that the workers load these
kernels rather than both compiling them at once; what else a test needs, its worker compiles.

What compiles: a short run of the flat flume chain on the compiled kernel (its statics, the line's
steps with tension, weight, contact, friction, drag and added mass on a plane) with the integrator
given.
"""

import sys
import tempfile
from dataclasses import replace

from cablefem.model.builtin import flume_scene
from cablefem.runs.run import run_scene


def main(integrator):
    """Run the flat flume for a few steps with ``integrator``."""
    scene = flume_scene("flat", elements=10, duration=0.05)
    scene = replace(scene, solver=replace(scene.solver, integrator=integrator))
    with tempfile.TemporaryDirectory(prefix="cablefem-warm-") as folder:
        run_scene(scene, folder, progress=False)


if __name__ == "__main__":
    main(sys.argv[1])
