"""Instructions of the compiled steps, counted by valgrind's callgrind (docs/architecture.md, "What
holds the layout").

Times of a run vary by ±10 % between rounds on a shared VM; instruction counts do not. This runs
one flume case (``cablefem.model.builtin.flume_scene``, as ``benchmarks.flume_cost`` does) in a child
process under ``valgrind --tool=callgrind`` and counts only the instructions inside the calls of
the compiled steps (the policy's ``steps`` that ``cablefem.compiled.problem.Packer.run`` calls),
switched on and off around each call by callgrind's client requests (a two-function C library
built here with gcc and valgrind's headers). The kernels are compiled for a generic x86-64 (``NUMBA_CPU_NAME=generic``): numba keys
its cache on the CPU, and valgrind's emulated CPU differs from the host's, so without it the
child would compile every kernel under valgrind (hours). The first call compiles that generic
variant natively (~1-2 min), then the child runs (~1 min). To compare commits, run it in a
worktree of each (``PYTHONPATH=<worktree> python -m benchmarks.step_instructions``).

    python -m benchmarks.step_instructions [--case steep dynamic 1 40 0.01] [--duration 1.0] [--keep FILE]

Last measured (the default case, 1 s: 100 steps): 47.89 M instructions, 0.856x the 55.93 M of
the code before the load catalog (the target: no slower than it), 0.996x the 48.07 M of the code
before one stepping path, 1.011x the 47.35 M of the code before the calls by address
(``cablefem.compiled.calls``: their arguments).
"""

import argparse
import ctypes
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

TOGGLE_C = """#include <valgrind/callgrind.h>
void cg_start(void) { CALLGRIND_START_INSTRUMENTATION; }
void cg_toggle(void) { CALLGRIND_TOGGLE_COLLECT; }
"""


def run_case(case, seconds):
    """One run of the flume ``case`` (seabed, motion, order, elements, dt) for ``seconds``, as
    ``cablefem run`` does it (frames in a temporary folder)."""
    from cablefem.runs.run import run_scene
    from cablefem.model.builtin import flume_scene

    seabed, motion, order, elements, dt = case
    scene = flume_scene(seabed, motion, elements=int(elements), order=int(order), duration=seconds, dt=float(dt))
    with tempfile.TemporaryDirectory(prefix="cablefem-instructions-") as out:
        run_scene(scene, out, progress=False)


def child(library, case, duration):
    """Inside valgrind: warm up, then count the steps' instructions of one run of ``case``."""
    from cablefem.compiled.problem import Packer

    lib = ctypes.CDLL(library)
    run = Packer.run

    def counted_run(packer, times, forces):
        """``Packer.run`` with its one compiled call (the policy's ``steps``, through ``entry``) counted."""
        functions, inner = packer.functions, packer.functions["entry"]

        def counted(*args):
            lib.cg_toggle()
            try:
                return inner(*args)
            finally:
                lib.cg_toggle()

        packer.functions = dict(functions, entry=counted)
        try:
            return run(packer, times, forces)
        finally:
            packer.functions = functions

    run_case(case, 0.05)  # kernels loaded, every path taken once
    Packer.run = counted_run
    lib.cg_start()
    run_case(case, duration)


def count(case, duration, keep=None):
    """Compile the generic kernels, then run ``child`` under callgrind: instructions (int). ``keep``:
    a path to copy callgrind's output to (for ``callgrind_annotate``)."""
    env = dict(os.environ, NUMBA_CPU_NAME="generic")
    with tempfile.TemporaryDirectory(prefix="cablefem-callgrind-") as work:
        library = Path(work) / "libtoggle.so"
        (Path(work) / "toggle.c").write_text(TOGGLE_C)
        subprocess.run(["gcc", "-O1", "-shared", "-fPIC", "-o", str(library), str(Path(work) / "toggle.c")], check=True)
        me, the_case = [sys.executable, "-m", "benchmarks.step_instructions"], ["--case", *case]
        subprocess.run(me + ["--warm"] + the_case, env=env, check=True)
        done = subprocess.run(["valgrind", "--tool=callgrind", "--instr-atstart=no", "--collect-atstart=no",
                               f"--callgrind-out-file={work}/out"] + me
                              + ["--child", str(library), "--duration", str(duration)] + the_case,
                              env=env, capture_output=True, text=True)
        found = re.search(r"Collected : (\d+)", done.stderr)
        if keep:
            shutil.copyfile(f"{work}/out", keep)
        if done.returncode != 0 or not found:
            raise SystemExit(f"callgrind failed ({done.returncode}): {done.stderr[-2000:]}")
        return int(found.group(1))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", nargs=5, default=["steep", "dynamic", "1", "40", "0.01"],
                        metavar=("SEABED", "MOTION", "ORDER", "ELEMENTS", "DT"))
    parser.add_argument("--duration", type=float, default=1.0, help="simulated seconds counted")
    parser.add_argument("--keep", help="copy callgrind's output here (read it with callgrind_annotate)")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    parser.add_argument("--warm", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.warm:  # natively, with the generic CPU: one short run compiles (or loads) the kernels
        return run_case(args.case, 0.05)
    if args.child:
        return child(args.child, args.case, args.duration)
    import cablefem

    instructions = count(args.case, args.duration, args.keep)
    print(f"{' '.join(args.case)}, {args.duration:g} s: {instructions:,} instructions in the compiled steps "
          f"({Path(cablefem.__file__).parent})")


if __name__ == "__main__":
    main()
