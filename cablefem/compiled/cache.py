"""Keep numba's on-disk cache of the compiled kernels in step with their sources.

numba keeps a cached function until its own source file changes; it does not see a change in
the functions it calls or the constants it reads from other files (numba's documentation,
"Cache invalidation"). The compiled step spans several files (``cablefem.compiled.steps`` calls
``cablefem.compiled.evaluator``, ``cablefem.compiled.banded`` and the seabed projections, and reads constants of the
loads), so after an edit of one of them another could keep running the old code. ``refresh``
hashes all of them and, when the hash changed, deletes their cached functions before anything
loads them; it runs when ``cablefem`` is imported. It looks after numba's default cache
(``__pycache__`` next to the sources), not a NUMBA_CACHE_DIR elsewhere.
"""

import hashlib
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


def refresh(root=PACKAGE):
    """Delete the cached kernels under ``root`` when ``KERNEL_SOURCES`` changed since the stamp
    ``root/__pycache__/kernels.sha256`` was written, then write it. Returns the number of cache
    files deleted. A read-only install is left alone (numba cannot cache there either)."""
    sources = sorted(path for pattern in PATTERNS for path in root.glob(pattern))
    digest = hashlib.sha256(b"".join(path.read_bytes() for path in sources)).hexdigest()
    stamp = root / "__pycache__" / STAMP
    try:
        if stamp.exists() and stamp.read_text() == digest:
            return 0
        stale = [cached for path in sources for pattern in ("*.nbi", "*.nbc")
                 for cached in (path.parent / "__pycache__").glob(f"{path.stem}.{pattern}")]
        for cached in stale:
            cached.unlink()
        stamp.parent.mkdir(exist_ok=True)
        stamp.write_text(digest)
    except OSError:
        return 0
    return len(stale)
