"""The statics of MoorDyn's own test inputs: for each input file, its Newton iterations, its wall
time, whether it converged (or why not) and the strategy that solved it.

    python benchmarks/moordyn_statics.py [FOLDER] [--only NAME ...] [--repeats 3]

FOLDER is MoorDyn's ``tests/Mooring`` (a checkout of FloatingArrayDesign/MoorDyn; default: the
copies in tests/data/moordyn). Every file under it with a LINES and an OPTIONS section is solved as
``cablefem static`` solves it, one after the other in one process (the compiled kernels loaded
first); the time is the solve's, as the JSON's ``wall_time_s``, the shortest of ``--repeats``.
``seafloor.txt`` names its seabed ``Mooring/3D_seafloor/...``, from the folder MoorDyn's tests run
in; cablefem reads a path from the input file's folder, so give FOLDER a link ``Mooring -> .``
(tests/data/moordyn holds the profile at that path).

Target (issue 33): lifting.txt <= 5 s, no input over 2 s unless it says why. Measured on MoorDyn
v2.7.1's tests/Mooring (2 shared cores, --repeats 3), the files cablefem reads:

| file | iters | time [s] | strategy |
|---|---|---|---|
| WD0050_Chain.txt | 4 | 0.018 | newton |
| WD0200_Chain.txt | 3 | 0.020 | newton |
| WD0600_Chain.txt | 4 | 0.030 | newton |
| lifting.txt | 0 | 0.028 | newton (the start, where the mass hangs, is the equilibrium) |
| lines.txt | 9 | 0.030 | newton x3 |
| local_euler/duplicated.txt | 8 | 0.027 | newton x2 |
| local_euler/hanging.txt | 2 | 0.014 | newton |
| pendulum.txt | 0 | 0.016 | newton |
| polyester/simple.txt | 1 | 0.010 | newton |
| seafloor.txt | 105 | 0.811 | axial continuation |
| tripod.txt | 1684 | 1.238 | network, 12 outer iterations: axial continuation x4, predicted x48 |
| viv/viv.txt | 5 | 0.025 | newton |
| body_tests/bodyDrag.txt | - | 0.139 | not converged: its free body (10 kg, no volume) hangs below the fixed point its spring is tied to, and is given above it; every load acts at its reference point, so its rotations are free |

The other 29 are refused while read, each with its reason: RODS (8), wave kinematics or
time-varying currents (14), SYROPE (3), a nonlinear or viscoelastic EA (1), a zero g (1), a point
above the surface (1), an unexpanded template (time_schemes.txt's ``@DT@``).
""""""

import argparse
import sys
import time
from pathlib import Path

from cablefem.errors import ConvergenceError, InputError
from cablefem.io import load_scene
from cablefem.statics.scene import numpy_statics, static_network, warm_imports

DATA = Path(__file__).resolve().parents[1] / "tests" / "data" / "moordyn"


def input_files(folder):
    """MoorDyn input files under ``folder``: a LINES section and an OPTIONS section, sorted."""
    found = []
    for path in sorted(folder.rglob("*")):
        if path.suffix not in (".txt", ".dat") or not path.is_file():
            continue
        heads = [row.upper() for row in path.read_text(errors="replace").splitlines() if row.startswith("--")]
        if any("LINES" in h or "LINE PROPERTIES" in h for h in heads) and any("OPTIONS" in h for h in heads):
            found.append(path)
    return found


def strategies(results, network):
    """How the lines were solved: each strategy and how many lines it solved ('newton x3'); for a
    network its outer iterations and how its strings' solves went, summed over the strings."""
    counts, solves = {}, {}
    for result in results:
        if not result.strategy.startswith("network"):
            counts[result.strategy] = counts.get(result.strategy, 0) + 1
    parts = [f"{name} x{n}" if n > 1 else name for name, n in counts.items()]
    if network is not None:
        for string in network.solves:
            for name, n in string.items():
                solves[name] = solves.get(name, 0) + n
        parts.append(f"network {len(network.history) - 1} outer: " + ", ".join(f"{name} x{n}" for name, n in solves.items()))
    return "; ".join(parts)


def solve(path, repeats):
    """(strategy, Newton iterations, wall time [s], outcome) of ``cablefem static`` on ``path``; the
    time the shortest of ``repeats`` solves."""
    try:
        scene = numpy_statics(load_scene(str(path)))
    except InputError as error:
        return "-", 0, 0.0, "not read: " + str(error).replace(f"{path}: ", "")
    warm_imports()
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        try:
            _, iterations, results, network = static_network(scene)
        except ConvergenceError as error:
            return "-", error.iterations or 0, time.perf_counter() - start, f"not converged: {str(error)[:90]}"
        times.append(time.perf_counter() - start)
    return strategies(results, network), iterations, min(times), "converged"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", nargs="?", default=str(DATA), help="MoorDyn's tests/Mooring")
    parser.add_argument("--only", nargs="*", default=(), help="files whose path contains one of these")
    parser.add_argument("--repeats", type=int, default=3, help="solves per file; the shortest time is printed")
    args = parser.parse_args(argv)
    folder = Path(args.folder)
    files = [p for p in input_files(folder) if not args.only or any(o in str(p) for o in args.only)]
    solve(DATA / "lines.txt", 1)  # load the compiled kernels before the clock matters
    print(f"{'file':<36} {'iters':>6} {'time [s]':>9}  {'outcome':<14} strategy")
    for path in files:
        strategy, iterations, wall, outcome = solve(path, args.repeats)
        print(f"{str(path.relative_to(folder)):<36} {iterations:6d} {wall:9.3f}  "
              + (f"{outcome:<14} {strategy}" if outcome == "converged" else outcome[:110]), flush=True)


if __name__ == "__main__":
    sys.exit(main())
