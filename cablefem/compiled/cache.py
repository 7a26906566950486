"""Keep numba's on-disk cache of the compiled kernels in step with their sources.

numba keeps a cached function until its own source file changes; it does not see a change in
the functions it calls or the constants it reads from other files (numba's documentation,
"Cache invalidation"). The compiled step spans several files (``cablefem.compiled.steps`` calls
``cablefem.compiled.evaluator``, ``cablefem.compiled.banded`` and the seabed projections, and reads constants of the
loads), so after an edit of one of them another could keep running the old code. ``refresh``
hashes all of them and, when the hash changed, deletes their cached functions before anything
loads them; it runs when ``cablefem`` is imported. numba caches beside the sources
(``__pycache__``), or in NUMBA_CACHE_DIR where that is set, or, where ``__pycache__`` is not
writable (a read-only install), in its per-user cache (``~/.cache/numba`` on Linux): ``refresh``
looks after each, a stamp in each (the compiled functions call each other by address,
``cablefem.compiled.calls``: a stale caller must not meet a changed callee).
"""

import hashlib
import os
from pathlib import Path

#: the package's folder: the patterns are relative to it
PACKAGE = Path(__file__).parent.parent
#: the sources of the compiled kernels and of the constants compiled into them
PATTERNS = ("compiled/*.py", "dynamics/policy.py",
            "loads/*.py",  # every load of the catalog, whatever its file
            "geometry/_vertex_normal_jit.py", "geometry/_walk_jit.py", "geometry/grid.py",
            "geometry/_vertex_normal.py", "geometry/_search.py",  # INSIDE_TOLERANCE, WALK_STEPS
            "waves/compiled.py")
KERNEL_SOURCES = tuple(sorted(str(path.relative_to(PACKAGE)) for pattern in PATTERNS for path in PACKAGE.glob(pattern)))
STAMP = "kernels.sha256"


def numba_folder(base, folder):
    """Where numba keeps the cached functions of the sources in ``folder`` under a cache folder
    ``base`` (NUMBA_CACHE_DIR or its per-user cache): a folder named by the source folder's name and
    the SHA-1 of its absolute path (numba's ``_CacheLocator.get_suitable_cache_subpath``;
    tests/test_jit_cache.py holds them equal)."""
    path = os.path.abspath(folder)
    return Path(base) / f"{os.path.basename(path)}_{hashlib.sha1(path.encode()).hexdigest()}"


def user_cache():
    """numba's per-user cache folder on Linux (its appdirs' ``user_cache_dir``)."""
    return Path(os.getenv("XDG_CACHE_HOME", os.path.expanduser("~/.cache"))) / "numba"


def refresh(root=PACKAGE):
    """Delete the cached kernels of ``root``'s sources when ``KERNEL_SOURCES`` changed since the stamp
    was written, then write it, in each place numba caches them (``__pycache__`` beside them; the
    folders of NUMBA_CACHE_DIR, if set; numba's per-user cache, if ``__pycache__`` is not writable),
    each with its own stamp. Returns the number of cache files deleted."""
    sources = sorted(path for pattern in PATTERNS for path in root.glob(pattern))
    digest = hashlib.sha256(b"".join(path.read_bytes() for path in sources)).hexdigest()
    in_tree = _refresh(sources, digest, lambda folder: folder / "__pycache__", root)
    deleted = in_tree or 0
    if os.environ.get("NUMBA_CACHE_DIR"):
        deleted += _refresh(sources, digest, lambda folder: numba_folder(os.environ["NUMBA_CACHE_DIR"], folder),
                            root) or 0
    if in_tree is None:  # not writable: numba caches in its per-user folder
        deleted += _refresh(sources, digest, lambda folder: numba_folder(user_cache(), folder), root) or 0
    return deleted


def _refresh(sources, digest, place, root):
    """``refresh`` in one place (``place(source folder)``: its cache folder), the stamp in root's
    compiled/ folder's; the files deleted, or None where the place cannot be written."""
    stamp = place(root / "compiled") / STAMP
    try:
        if stamp.exists() and stamp.read_text() == digest:
            return 0
        stale = [cached for path in sources for pattern in ("*.nbi", "*.nbc")
                 for cached in place(path.parent).glob(f"{path.stem}.{pattern}")]
        for cached in stale:
            cached.unlink()
        stamp.parent.mkdir(parents=True, exist_ok=True)
        stamp.write_text(digest)
    except OSError:
        return None
    return len(stale)
