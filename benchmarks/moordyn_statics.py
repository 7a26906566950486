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
v2.7.1's tests/Mooring (links ``Mooring -> .`` in it and in 3D_seafloor/; 2 shared cores under the
load of other work, --repeats 3), the 32 files cablefem reads, 31 converged. tripod.txt's line types have EI > 0, so
its lines are on Hermite elements and its tether and float one string with a continuous tangent
through point 1, where MoorDyn's point is a hinge: as it stands its statics does not converge
(relative residual 14.8 after 1250 iterations; a hinge between lines that bend is not built); its row
is its lines with EI zeroed (tests/test_moordyn_files.py). BeamSimplySupported.txt and
lowe_and_langley_2006/line.txt are on Hermite elements with their EI:

| file | iters | time [s] | strategy |
|---|---|---|---|
| 3D_seafloor/hanging_lines.txt | 0 | 0.125 | newton x10 (ten chains on free ends: their hangs are the equilibrium) |
| BeamSimplySupported.txt | 5 | 0.011 | newton |
| WD0050_Chain.txt | 4 | 0.038 | newton |
| WD0200_Chain.txt | 3 | 0.029 | newton |
| WD0600_Chain.txt | 4 | 0.055 | newton |
| body_tests/bodyDrag.txt | 0 | 0.725 | network, 32 outer iterations (halving, then pseudo-transient): newton x2, predicted x43 (a one-element line: no unknowns of its own) |
| body_tests/rotatingBody.txt | 0 | 0.101 | network, 0 outer: newton x7 |
| lifting.txt | 0 | 0.027 | newton (its hang is the equilibrium) |
| lines.txt | 9 | 0.043 | newton x3 |
| local_euler/duplicated.txt | 8 | 0.048 | newton x2 |
| local_euler/hanging.txt | 2 | 0.030 | newton |
| lowe_and_langley_2006/line.txt | 4 | 0.006 | newton |
| pendulum.txt | 0 | 0.017 | newton |
| polyester/simple.txt | 1 | 0.025 | newton |
| seafloor.txt | 105 | 0.652 | axial continuation (Newton from the taut start first) |
| syrope/exp_wc/line.txt | 0 | 0.002 | newton |
| syrope/linear_wc/line.txt | 0 | 0.002 | newton |
| syrope/quadratic_wc/line.txt | 0 | 0.002 | newton |
| tripod.txt, EI zeroed | 1684 | 0.874 | network, 12 outer: axial continuation x4, predicted x48 |
| viv/viv.txt | 5 | 0.018 | newton |
| wave_surface/wave_surface.txt | 94 | 0.113 | newton x5 |
| wavekin_2/wavekin_2.txt | 5 | 0.018 | newton |
| wavekin_2/wavekin_2_curr2.txt | 5 | 0.018 | newton |
| wavekin_2/wavekin_2_curr5.txt | 5 | 0.020 | newton |
| wavekin_2/wavekin_3.txt | 5 | 0.022 | newton |
| wavekin_2/wavekin_3_curr2.txt | 5 | 0.018 | newton |
| wavekin_2/wavekin_3_curr5.txt | 5 | 0.016 | newton |
| wavekin_3/test_dynamic_currents.txt | 0 | 0.003 | newton |
| wavekin_4/hanging_lines.txt | 0 | 0.053 | newton x10 |
| wavekin_7/wavekin_7.txt | 3 | 0.014 | newton |
| wavekin_current_1.txt | 5 | 0.020 | newton |
| wavekin_wave_1.txt | 5 | 0.022 | newton |

The other 10 are refused while read, each with its reason: RODS (8), polyester/visco.txt's line, 1 m
between points 2 m apart (1), and time_schemes.txt's unexpanded template ``@DT@`` (1).
"""

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
