"""numba's cache of the compiled kernels follows every source they span (cablefem.compiled.cache)."""

import shutil
from pathlib import Path

from cablefem.compiled.cache import KERNEL_SOURCES, STAMP, refresh

PACKAGE = Path(__file__).resolve().parents[1] / "cablefem"


def cached_files(root, name):
    """A fake numba index and data file of one function of ``name`` (a kernel source)."""
    path = root / name
    folder = path.parent / "__pycache__"
    folder.mkdir(parents=True, exist_ok=True)
    files = [folder / f"{path.stem}.kernel-12.py311.nbi", folder / f"{path.stem}.kernel-12.py311.1.nbc"]
    for file in files:
        file.write_bytes(b"compiled")
    return files


def test_an_edit_of_any_kernel_source_clears_every_cached_kernel(tmp_path):
    for name in KERNEL_SOURCES:
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(PACKAGE / name, tmp_path / name)
    other = tmp_path / "__pycache__" / "cli.cpython-311.pyc"  # not numba's: kept
    other.parent.mkdir(exist_ok=True)
    cached = [f for name in KERNEL_SOURCES for f in cached_files(tmp_path, name)]
    other.write_bytes(b"bytecode")
    assert refresh(tmp_path) == len(cached)  # no stamp yet: whatever is cached may be stale
    assert not any(f.exists() for f in cached) and other.exists()
    assert (tmp_path / "__pycache__" / STAMP).exists()
    # compiled again; the sources unchanged: kept
    cached = [f for name in KERNEL_SOURCES for f in cached_files(tmp_path, name)]
    assert refresh(tmp_path) == 0 and all(f.exists() for f in cached)
    # a constant edited in a file that holds no cached function of march: all go
    tension = tmp_path / "loads" / "tension.py"
    tension.write_text(tension.read_text().replace("SLACK_STIFFNESS = 1e-6", "SLACK_STIFFNESS = 1e-5"))
    assert refresh(tmp_path) == len(cached)
    assert not any(f.exists() for f in cached)
