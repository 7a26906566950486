"""Start-up (docs/architecture.md, "Start-up"): what a command loads, and that what it skips
changes no number. Times are measured by benchmarks/startup.py, not asserted here."""

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from cablefem.cli import NUMPY_STATICS_NODES, numpy_statics, static_network
from cablefem.io import load_scene
from cablefem.roots import brentq
from cablefem.scenes import default_scene, flume_scene

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"


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
    never initialised and scipy.optimize is not imported."""
    modules = _modules_after(["static"])
    assert "numba.np.arraymath" not in modules
    assert "scipy.optimize" not in modules


def test_run_on_a_plane_imports_neither_scipy_optimize_nor_scipy_spatial(tmp_path):
    modules = _modules_after(["run", str(BENCHMARKS / "flume_snap.toml"), "--out", str(tmp_path),
                              "--duration", "0.34"])
    assert "scipy.optimize" not in modules
    assert "scipy.spatial" not in modules


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


def _random_cases(count=600, seed=7):
    """(f, a, b, options) of scalar root problems over many scales, either orientation."""
    rng = np.random.default_rng(seed)
    options = [{}, {"xtol": 1e-300, "rtol": 1e-15}, {"xtol": 1e-300, "rtol": 1e-15, "maxiter": 500},
               {"xtol": 1e-12, "rtol": 1e-14}, {"maxiter": 4}]
    for k in range(count):
        c = rng.normal(size=4) * 10.0 ** rng.integers(-5, 5)
        family = [lambda x, c=c: float(np.polyval(c, x)), lambda x, c=c: math.sinh(c[0] * x) - c[1],
                  lambda x, c=c: math.atan(x - c[0]) + 1e-3 * c[1], lambda x, c=c: x ** 3 - c[0]]
        a, b = sorted(rng.normal(size=2) * 10.0 ** rng.integers(-3, 3))
        yield (family[k % 4], a, b, options[k % 5]) if k % 2 else (family[k % 4], b, a, options[k % 5])


def _outcome(solver, f, a, b, options):
    try:
        return solver(f, a, b, **options)
    except (ValueError, RuntimeError, OverflowError) as error:
        return type(error).__name__, str(error)


def test_brentq_gives_scipys_roots_bit_for_bit():
    """The port of scipy's C brentq: the same roots (==, not approx) and the same errors (no sign
    change, too few iterations, NaN) on random problems and on the catenary start's own."""
    from scipy.optimize import brentq as scipy_brentq

    cases = list(_random_cases())
    cases += [(lambda x: x, 0.0, 1.0, {}), (lambda x: x * x + 1.0, -1.0, 1.0, {}),
              (lambda x: math.nan, 0.0, 1.0, {}), (lambda x: -0.0 if x < 0.3 else 1.0, 0.0, 1.0, {}),
              (lambda x: -1e-200 if x < 0.5 else 1e-200, 0.0, 1.0, {}),
              (lambda x: math.cosh(x / 120.0) * 120.0 - 100.0 - x, 0.0, 900.0, {"xtol": 1e-300, "rtol": 1e-15})]
    for f, a, b, options in cases:
        assert _outcome(brentq, f, a, b, options) == _outcome(scipy_brentq, f, a, b, options), (a, b, options)
