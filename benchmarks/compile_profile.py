"""Where a first run's compilation goes: numba's compile events of one ``cablefem run``, per function.

Runs a scene (the built-in default, or a TOML or MoorDyn file) for ``--duration`` seconds in this
process with numba's cache in an empty temporary folder (NUMBA_CACHE_DIR, set before numba is
imported), so that everything the scene uses compiles, and prints each compiled function's time:
exclusive (its own typing, lowering and LLVM work, its callees' compilations left out), inclusive,
and the part spent holding LLVM's lock (optimising and emitting machine code, the linked callees'
code included), from numba's "numba:compile" and "numba:llvm_lock" events.

    python benchmarks/compile_profile.py [SCENE] [--duration 1.0] [--top 30]

``benchmarks/startup.py --first`` times the first run as a user meets it (a fresh process); this
says which functions make it up (``cablefem.compiled.calls``: why each is compiled once).
"""

import argparse
import collections
import os
import sys
import tempfile
import time


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", nargs="?", help="TOML scene or MoorDyn file (default: the built-in scene)")
    parser.add_argument("--duration", type=float, default=1.0, help="simulated time [s] (default 1)")
    parser.add_argument("--top", type=int, default=30, help="functions to list (default 30)")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="cablefem-compile-") as folder:
        os.environ["NUMBA_CACHE_DIR"] = os.path.join(folder, "numba")
        if "numba" in sys.modules:
            raise SystemExit("compile_profile: numba was imported before its cache folder was set")
        profile(args, os.path.join(folder, "out"))


def profile(args, out):
    """Run the scene with numba's compile events recorded; print the table."""
    from numba.core import event

    stack, exclusive, inclusive, llvm, count = [], collections.Counter(), collections.Counter(), collections.Counter(), \
        collections.Counter()

    class Compiles(event.Listener):
        def on_start(self, ev):
            function = getattr(ev.data.get("dispatcher"), "py_func", None)
            name = f"{function.__module__}.{function.__qualname__}" if function else str(ev.data.get("dispatcher"))
            stack.append([name, time.perf_counter(), 0.0])

        def on_end(self, ev):
            name, start, callees = stack.pop()
            spent = time.perf_counter() - start
            inclusive[name] += spent
            exclusive[name] += spent - callees
            count[name] += 1
            if stack:
                stack[-1][2] += spent

    class Lock(event.Listener):
        def on_start(self, ev):
            self.start = time.perf_counter()

        def on_end(self, ev):
            llvm[stack[-1][0] if stack else "(outside a compilation)"] += time.perf_counter() - self.start

    event.register("numba:compile", Compiles())
    event.register("numba:llvm_lock", Lock())
    from cablefem import cli

    wall, cpu = time.perf_counter(), time.process_time()
    status = cli.main(["run"] + ([args.scene] if args.scene else []) + ["--duration", str(args.duration), "--out", out])
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    print(f"\nthe run: {wall:.1f} s of wall, {cpu:.1f} s of CPU, {sum(exclusive.values()):.1f} s compiling "
          f"({len(exclusive)} functions, exit status {status or 0})")
    print(f"{'exclusive':>9} {'inclusive':>9} {'LLVM':>6} {'n':>3}  function [s]")
    for name, spent in exclusive.most_common(args.top):
        print(f"{spent:9.2f} {inclusive[name]:9.2f} {llvm[name]:6.2f} {count[name]:3d}  {name}")


if __name__ == "__main__":
    main()
