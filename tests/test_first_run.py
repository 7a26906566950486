"""The first run after an install: numba compiles what the run uses and says so in one line on stderr,
once per process; from a warm cache nothing compiles and nothing is said (cablefem.compiled.progress).
Two small kernels stand for a run's (the message is the same whatever compiles): a child process
with an empty numba cache compiles both, a second child with that cache loads them."""

import os
import subprocess
import sys
from pathlib import Path

from cablefem.compiled.progress import NOTICE

ROOT = Path(__file__).resolve().parents[1]

#: two of the compiled steps' kernels called from Python, the copies they make checked
CODE = """
import numpy as np
from cablefem.compiled.line_ops import _copy_flat, _copy_rows
rows, flat = np.zeros((4, 3)), np.zeros(5)
_copy_rows(rows, np.arange(12.0).reshape(4, 3))
_copy_flat(flat, np.arange(5.0))
assert rows.sum() == 66.0 and flat.sum() == 10.0
print("copied")
"""


def child(cache):
    """CODE in a new process with numba's cache in ``cache``."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-c", CODE], env=env, capture_output=True, text=True, timeout=600)


def test_a_first_compilation_says_so_in_one_line_and_a_warm_cache_says_nothing(tmp_path):
    first = child(tmp_path / "numba")
    assert first.returncode == 0 and first.stdout == "copied\n", first.stderr
    assert first.stderr.splitlines() == [NOTICE]  # two kernels compiled, one line
    assert "once" in NOTICE and "numba" in NOTICE
    again = child(tmp_path / "numba")
    assert again.returncode == 0 and again.stdout == "copied\n", again.stderr
    assert again.stderr == ""  # loaded from the cache: nothing compiled, nothing said
