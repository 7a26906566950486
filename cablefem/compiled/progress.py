"""One line on stderr when numba compiles cablefem's kernels: what compiles, and that it happens once.

The first run after an install (or after an edit of a kernel source, ``cablefem.compiled.cache``)
compiles the element loop, the seabed's projection and the integrator's steps the scene uses; numba
keeps them in its on-disk cache, and later runs load them. numba announces a compilation only when
its cache has no copy of the function (its "numba:compile" event), so a process that loads
everything from the cache says nothing. Imported by ``cablefem.compiled.kernels``, which every
compiled path imports.
"""

import sys

from numba.core import event

NOTICE = ("cablefem: compiling the kernels this scene uses with numba (half a minute to a minute), once: "
          "later runs load them from numba's cache")


class _Announce(event.Listener):
    """Prints ``NOTICE`` at the first compilation of a cablefem function in this process."""

    said = False

    def on_start(self, ev):
        if self.said or not getattr(ev.data["dispatcher"].py_func, "__module__", "").startswith("cablefem."):
            return
        self.said = True
        print(NOTICE, file=sys.stderr, flush=True)

    def on_end(self, ev):
        pass


#: the listener; ``ANNOUNCE.said = True`` keeps a process quiet (tests/conftest.py: the test processes
#: assert their stderr line by line)
ANNOUNCE = _Announce()
event.register("numba:compile", ANNOUNCE)
