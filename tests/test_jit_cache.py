"""numba's cache of the compiled kernels follows every source they span (cablefem.compiled.cache)."""

import shutil
from pathlib import Path

import numba
from numba.core import caching

from cablefem.compiled import cache
from cablefem.compiled.cache import KERNEL_SOURCES, STAMP, refresh

PACKAGE = Path(__file__).resolve().parents[1] / "cablefem"


def cached_files(root, name, place=lambda folder: folder / "__pycache__"):
    """A fake numba index and data file of one function of ``name`` (a kernel source), in the cache
    folder ``place`` gives for its source folder."""
    path = root / name
    folder = place(path.parent)
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
    assert (tmp_path / "compiled" / "__pycache__" / STAMP).exists()
    # compiled again; the sources unchanged: kept
    cached = [f for name in KERNEL_SOURCES for f in cached_files(tmp_path, name)]
    assert refresh(tmp_path) == 0 and all(f.exists() for f in cached)
    # a constant edited in a file that holds no cached function of march: all go
    tension = tmp_path / "loads" / "tension.py"
    tension.write_text(tension.read_text().replace("SLACK_STIFFNESS = 1e-6", "SLACK_STIFFNESS = 1e-5"))
    assert refresh(tmp_path) == len(cached)
    assert not any(f.exists() for f in cached)


def test_numba_s_own_cache_folders_are_those_refresh_looks_after(tmp_path, monkeypatch):
    """``cache.numba_folder`` names a source folder's cache as numba's locators do, in NUMBA_CACHE_DIR and
    in numba's per-user cache (the folders ``refresh`` clears where numba caches there)."""
    from cablefem.compiled import kernels

    function, source = kernels.assemble.py_func, kernels.__file__
    monkeypatch.setattr(numba.config, "CACHE_DIR", str(tmp_path))
    provided = caching.UserProvidedCacheLocator(function, source).get_cache_path()
    assert Path(provided) == cache.numba_folder(tmp_path, Path(source).parent)
    user_wide = caching.UserWideCacheLocator(function, source).get_cache_path()
    assert Path(user_wide) == cache.numba_folder(cache.user_cache(), Path(source).parent)


def test_an_edit_clears_the_kernels_cached_in_numba_cache_dir_too(tmp_path, monkeypatch):
    root, elsewhere = tmp_path / "package", tmp_path / "numba"
    for name in KERNEL_SOURCES:
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(PACKAGE / name, root / name)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(elsewhere))
    place = lambda folder: cache.numba_folder(elsewhere, folder)  # noqa: E731
    assert refresh(root) == 0  # nothing cached yet: the stamps written
    cached = [f for name in KERNEL_SOURCES for f in cached_files(root, name, place)]
    assert refresh(root) == 0 and all(f.exists() for f in cached)  # warm: kept
    tension = root / "loads" / "tension.py"
    tension.write_text(tension.read_text().replace("SLACK_STIFFNESS = 1e-6", "SLACK_STIFFNESS = 1e-5"))
    assert refresh(root) == len(cached) and not any(f.exists() for f in cached)
