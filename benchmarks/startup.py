"""Start-up as a user meets it (issues 15 and 16): fresh processes, wall and CPU time, beside the
import floors and a fresh MoorDyn run of the same file.

Each command runs ``--repeats`` times in a new Python process, the commands alternating (the
machine is shared: a round of every command, then the next round), after one untimed warm-up
round (numba's cache, the OS's file cache). Reported: the median and the least wall time, and the
median CPU time (user + system of the child process).

- ``python``, ``numpy``, ``scipy.sparse``, ``skfem``, ``numba``: bare ``python -c "import X"``;
  ``compiled path imports``: numpy, scipy.sparse, skfem and numba together; ``+ numba target``:
  those and one trivial cached numba function called (numba's target initialised, the least
  that any compiled kernel costs a process).
- ``cablefem static``: the default scene (examples/flume_steep.toml).
- ``cablefem run``: ``benchmarks/flume_snap.toml``, the flume chain under the snap motion at
  MoorDyn's 20-segment error level (P1 x 14, dt 0.17 s, 36 s; verification/work_precision),
  on ``benchmarks/flume_snap_20.dat``.
- ``MoorDyn run``: a Python script running ``flume_snap_20.dat`` through MoorDyn-C (PyPI
  ``moordyn``), 20 segments, dtM 0.005 s, no initial-condition solve, the same motion coupled
  every 0.01 s (as validation/moordyn's peer does), if moordyn is installed.

Before timing, each checkout's modules are byte-compiled (``python -m compileall``), as ``pip
install`` does: with PYTHONDONTWRITEBYTECODE=1 (set in some environments, this one among them) a
checkout without ``__pycache__`` recompiles every cablefem module from source in every process,
~0.2-0.3 s of CPU that no installed copy pays (``--no-compile`` measures that case).

``python benchmarks/startup.py [--repeats N] [--compare DIR] [--no-compile] [--first]``: ``--compare``
runs the cablefem commands of another checkout too (e.g. a worktree of main), in the same rounds.
``--first`` times the first ``cablefem run`` after a fresh install instead: the default scene and
examples/flume_flat.toml, each in a new process with an empty numba cache (NUMBA_CACHE_DIR), so
that it compiles everything the scene uses.

First run after a fresh install (``python benchmarks/startup.py --first --repeats 1 --compare
DIR``, DIR a checkout of the code before the calls by address; one round, the 2-core machine):

| first ``cablefem run``, empty numba cache | wall [s] | CPU [s] |
|---|---|---|
| default scene, calls linked | 47.0 | 47.2 |
| default scene, calls by address | 27.5 | 27.7 |
| examples/flume_flat.toml, calls linked | 43.3 | 43.5 |
| examples/flume_flat.toml, calls by address | 23.3 | 23.5 |

The <= 30 s target is met. Nearly all of it is numba compiling, and numba links the code of every
callee into its caller and optimises and emits it there again: each layer of the policy (steps,
advance, attempt, newton) cost 4-9 s, its own code and again what it called, the element loop over
the whole catalog among it. Now the layers call each other by address (``cablefem.compiled.calls``;
``cablefem.compiled.steps``, "Compile time"), a string's evaluation calls the element loop, the
seabed's projection and the node loads by address, and the element loop calls the loads' point
kernels by address, each compiled where a scene has its load: every function is compiled once, and
only what the scene uses. The price is the arguments of a call by address: the ``Problem``'s ~900
words of array descriptors, once an attempt (``benchmarks/step_instructions.py``: the compiled steps
1.011x in instructions). Where the time goes now (``python benchmarks/compile_profile.py``: numba's
compile events, a 1 s run, an idle machine): newton 3.2 s,
attempt 2.3, the element loop 1.9, steps with advance 1.9, the triangulated walk 1.7, friction's
anisotropic branch 1.3 (compiled with the isotropic friction it shares a kernel with). Measured and
not kept before: LLVM's optnone on the layers (their loops then run unoptimised); NUMBA_OPT=0 for
everything (152 s against 88: unoptimised code is larger to emit); newton inlined into attempt
(three call sites: 153 s against 85); attempt inlined into advance, with advance into steps (the
crossings once an attempt gone, 0.35 % fewer instructions, the first run +4.3 s: LLVM optimises the
one large function more slowly than its parts).

Last measured (medians of 5 rounds, byte-compiled, numba's cache warm, the 2-core machine; the
code with its calls by address and the code before them alike, 0.80 and 0.81 s for the run):

- ``cablefem run`` of the snap case 0.80 s of wall against 0.062 s for the MoorDyn script: 13x,
  not the <= 2x target. The import floor is above 2x MoorDyn: numpy, scipy.sparse, scikit-fem and
  numba take 0.33 s together, 0.48 s with numba's target initialised; the other 0.32 s are
  cablefem's own imports, the kernels' loading from the cache and the run. The levers left
  are numba's kernels compiled ahead of time and one process for many runs (the studies,
  ``cablefem sweep``).
- ``cablefem static`` of the default scene 0.51 s of wall, not the <= 0.5 s target by 0.01 s:
  python, numpy, scipy.sparse and scikit-fem alone take 0.24 s; a scene this small is solved on the
  numpy path, without loading compiled kernels.
"""

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
#: the MoorDyn side: the snap motion (5 m surge, 6 s, smoothstep ramp over 6 s, as cablefem.model.motion),
#: the coupled point moved along the secant of the motion every 0.01 s for 36 s
MOORDYN_SCRIPT = """
import math, sys
import moordyn

AMPLITUDE, PERIOD, RAMP, DURATION, COUPLING = 5.0, 6.0, 6.0, 36.0, 0.01

def surge(t):
    u = min(max(t / RAMP, 0.0), 1.0)
    return (3 * u * u - 2 * u ** 3) * AMPLITUDE * math.sin(2 * math.pi * t / PERIOD)

system = moordyn.Create(sys.argv[1])
moordyn.Init(system, [surge(0.0), 0.0, 0.0], [0.0, 0.0, 0.0])
steps = round(DURATION / COUPLING)
peak = 0.0
for n in range(steps):
    t, x = n * COUPLING, surge(n * COUPLING)
    rate = (surge(t + COUPLING) - x) / COUPLING
    force = moordyn.Step(system, [x, 0.0, 0.0], [rate, 0.0, 0.0], t, COUPLING)
    peak = max(peak, math.sqrt(sum(f * f for f in force)))
moordyn.Close(system)
print(f"MoorDyn: {steps} coupling steps, fairlead tension up to {peak:.4e} N")
"""
NUMBA_KERNEL = "from numba import njit\n\n@njit(cache=True)\ndef one(x):\n    return x + 1.0\n"


def commands(folder, roots, with_moordyn):
    """(label, argv, PYTHONPATH or None) of every timed command."""
    py = sys.executable
    rows = [("python", [py, "-c", "pass"], None)]
    for module in ("numpy", "scipy.sparse", "skfem", "numba"):
        rows.append((module, [py, "-c", f"import {module}"], None))
    rows.append(("compiled path imports", [py, "-c", "import numpy, scipy.sparse, skfem, numba"], None))
    rows.append(("+ numba target (one cached kernel)",
                 [py, "-c", "import numpy, scipy.sparse, skfem, numba_one; numba_one.one(1.0)"], str(folder)))
    for name, root in roots:
        rows.append((f"cablefem static ({name})", [py, "-m", "cablefem.cli", "static"], str(root)))
        rows.append((f"cablefem run ({name})", [py, "-m", "cablefem.cli", "run", str(folder / "flume_snap.toml"),
                                                "--out", str(folder / f"out-{name}")], str(root)))
    if with_moordyn:
        rows.append(("MoorDyn run", [py, str(folder / "moordyn_run.py"), str(folder / "flume_snap_20.dat")], None))
    return rows


def timed(argv, pythonpath, cwd, cache=None):
    """(wall [s], CPU [s]) of one fresh process running argv, with numba's cache in ``cache`` if given;
    raises if it fails."""
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    if pythonpath:
        env["PYTHONPATH"] = pythonpath
    if cache:
        env["NUMBA_CACHE_DIR"] = str(cache)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(argv, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)} failed ({done.returncode}): {done.stderr.strip()[-500:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def have_moordyn():
    """Whether the moordyn package can be imported by this Python."""
    return subprocess.run([sys.executable, "-c", "import moordyn"], capture_output=True).returncode == 0


def first_runs(roots, repeats):
    """The first ``cablefem run`` after a fresh install (``--first``): the default scene and
    examples/flume_flat.toml, each in a new process with an empty numba cache (NUMBA_CACHE_DIR), the
    checkouts alternating; prints wall and CPU time of each and the ratios of their medians."""
    scenes = [("default scene", []), ("flume_flat.toml", [str(ROOT / "examples" / "flume_flat.toml")])]
    times = {(scene, name): [] for scene, _ in scenes for name, _ in roots}
    with tempfile.TemporaryDirectory(prefix="cablefem-first-") as tmp:
        folder = Path(tmp)
        for round_ in range(repeats):
            for scene, extra in scenes:
                for name, root in roots:
                    cache = folder / f"numba-{round_}-{len(times[scene, name])}-{name}-{scene[:5]}"
                    argv = [sys.executable, "-m", "cablefem.cli", "run", *extra, "--out", str(folder / "out")]
                    times[scene, name].append(timed(argv, str(root), folder, cache))
                    shutil.rmtree(cache, ignore_errors=True)
    print(f"{'first run, empty numba cache':<40} {'wall median':>11} {'wall least':>10} {'CPU median':>10}   [s], "
          f"{repeats} alternating rounds")
    for scene, _ in scenes:
        for name, _ in roots:
            walls, cpus = zip(*times[scene, name])
            print(f"{scene + ' (' + name + ')':<40} {statistics.median(walls):11.1f} {min(walls):10.1f} "
                  f"{statistics.median(cpus):10.1f}")
        if len(roots) > 1:
            this, other = (statistics.median(c for _, c in times[scene, n]) for n, _ in roots)
            print(f"{scene}: this / compare, medians of CPU time: {this / other:.2f}")


def main(argv=None):
    """Measure and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, help="timed rounds (default 7; 3 with --first)")
    parser.add_argument("--compare", metavar="DIR", help="another checkout whose cablefem runs in the same rounds")
    parser.add_argument("--no-compile", action="store_true", help="do not byte-compile the checkouts first")
    parser.add_argument("--first", action="store_true",
                        help="time the first run after a fresh install instead (empty numba cache; --repeats 3)")
    args = parser.parse_args(argv)
    roots = [("this", ROOT)] + ([("compare", Path(args.compare).resolve())] if args.compare else [])
    if not args.no_compile:
        for _, root in roots:
            subprocess.run([sys.executable, "-m", "compileall", "-q", str(root / "cablefem")], check=True)
    if args.first:
        first_runs(roots, args.repeats or 3)
        return
    args.repeats = args.repeats or 7
    with tempfile.TemporaryDirectory(prefix="cablefem-startup-") as tmp:
        folder = Path(tmp)
        for name in ("flume_snap.toml", "flume_snap_20.dat"):
            shutil.copy(HERE / name, folder / name)
        (folder / "moordyn_run.py").write_text(MOORDYN_SCRIPT)
        (folder / "numba_one.py").write_text(NUMBA_KERNEL)
        rows = commands(folder, roots, have_moordyn())
        times = {label: [] for label, _, _ in rows}
        for round_ in range(args.repeats + 1):  # round 0: the warm-up, not kept
            for label, command, path in rows:
                wall, cpu = timed(command, path, folder)
                if round_:
                    times[label].append((wall, cpu))
    print(f"{'fresh process':<38} {'wall median':>11} {'wall least':>10} {'CPU median':>10}   [s], "
          f"{args.repeats} alternating rounds, {'no bytecode compiled' if args.no_compile else 'bytecode compiled'}")
    for label, _, _ in rows:
        walls, cpus = zip(*times[label])
        print(f"{label:<38} {statistics.median(walls):11.3f} {min(walls):10.3f} {statistics.median(cpus):10.3f}")
    if "MoorDyn run" in times:
        moordyn = statistics.median(w for w, _ in times["MoorDyn run"])
        for name, _ in roots:
            run = statistics.median(w for w, _ in times[f"cablefem run ({name})"])
            print(f"cablefem run ({name}) / MoorDyn run, medians of wall time: {run / moordyn:.2f}")


if __name__ == "__main__":
    main()
