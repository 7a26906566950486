"""Start-up (docs/architecture.md, "Start-up"): what a command loads, and that what it skips
changes no number. Times are measured by benchmarks/startup.py, not asserted here."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from cablefem.statics.scene import NUMPY_STATICS_NODES, numpy_statics, static_network
from cablefem.io import load_scene
from cablefem.model.builtin import default_scene, flume_scene



def _modules_after(command):
    """The modules a fresh ``cablefem`` process holds after running ``command`` (a list of args)."""
    code = ("import sys; from cablefem.cli import main; status = main(%r); "
            "print(status); print(' '.join(sorted(sys.modules)))" % (command,))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    status, modules = done.stdout.strip().splitlines()[-2:]
    assert status == "0", done.stdout
    return set(modules.split())


def test_static_on_the_default_scene_loads_no_compiled_kernel():
    """41 nodes: solved on the numpy path, numba's target (which imports numba.np.arraymath) is
    never initialised."""
    modules = _modules_after(["static"])
    assert "numba.np.arraymath" not in modules


@pytest.mark.parametrize("seabed", ["steep", "flat"])
def test_numpy_statics_equal_the_compiled_statics_to_round_off(seabed):
    """``cablefem static`` on a small scene gives the compiled path's numbers: the same Newton
    iterations and touchdown, the nodes to round-off (2e-17 of the line's extent measured on the
    steep flume case; 1e-13 leaves room for other BLAS builds)."""
    scene = flume_scene(seabed)
    reference = static_network(scene)
    numpy_path = static_network(numpy_statics(scene))
    assert numpy_statics(scene).solver.assembly == "numpy"
    assert numpy_path[1] == reference[1]
    (a,), (b,) = reference[0], numpy_path[0]
    assert a.touchdown_s == pytest.approx(b.touchdown_s, rel=1e-12)
    np.testing.assert_allclose(b.nodes, a.nodes, rtol=0, atol=1e-13 * 635.0)
    np.testing.assert_allclose(b.fairlead_force, a.fairlead_force, rtol=1e-12)


def test_numpy_statics_only_for_one_small_line():
    scene = default_scene()
    assert scene.seabed.compiled and not numpy_statics(scene).seabed.compiled
    assert scene.seabed.compiled  # the scene's own seabed is left as it was
    big = flume_scene("flat", elements=NUMPY_STATICS_NODES)
    assert numpy_statics(big).solver.assembly == "kernel"
    three = load_scene(Path(__file__).resolve().parent / "data" / "moordyn" / "lines.txt")
    assert len(three.lines) == 3 and numpy_statics(three) is three


