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
load of three other jobs, load ~3.5, --repeats 3): cablefem reads 39 of its 42 files, and all 39
converge. Five are over 2 s, all networks whose coupling unknowns Newton cannot reach from where the
file puts them, so that pseudo-transient continuation (``cablefem.statics.network_relax``) takes
49-86 outer iterations, each re-solving every string to the tolerance:

- tripod.txt (8.7 s): its line types have EI > 0, its lines on Hermite elements and its free points
  hinges (eleven strings, eight junctions), the hinges far from where the file puts them;
- riser/riser.txt, riser_ic1.txt, riser_ic2.txt (2.8-3.2 s) and local_euler/complex_system.txt
  (3.1 s): a 29.5 kg free body held by a 7 m tether and hung with bending lines whose tensions
  (10-60 kN) are 40-200 times its weight, so that its place is where they balance, set by its
  tether, and their zero-length free rods (points).

Two levers cut them (against a run of the same files before them, at load ~6): the pseudo-time
step at least doubled by a step that lowers the residual (riser 83 outer iterations to 49), and
Newton with halving giving up when 8 steps have not halved the residual (complex_system's crawled
47 steps from 6 to 1.3 before its pseudo-transient: 246 outer iterations to 63, 14 s to 3.1 s).

| file | iters | time [s] | strategy |
|---|---|---|---|
| 3D_seafloor/hanging_lines.txt | 0 | 0.024 | newton x10 |
| BeamCantilevered.txt | 4 | 0.011 | newton |
| BeamSimplySupported.txt | 5 | 0.011 | newton |
| BodiesAndRods.dat | 1138 | 0.908 | network 6 outer: newton x3, predicted x24, axial continuation x1 |
| RodHanging.txt | 24 | 0.076 | network 5 outer: newton x2, predicted x10 |
| WD0050_Chain.txt | 5 | 0.008 | newton |
| WD0200_Chain.txt | 5 | 0.010 | newton |
| WD0600_Chain.txt | 5 | 0.007 | newton |
| body_tests/bodyDrag.txt | 42 | 0.178 | network 11 outer: newton x2, predicted x22 |
| body_tests/rotatingBody.txt | 0 | 0.084 | network 0 outer: newton x7 |
| lifting.txt | 0 | 0.015 | newton |
| lines.txt | 12 | 0.038 | newton x3 |
| local_euler/complex_system.txt | 2623 | 3.076 | network 63 outer: newton x15, predicted x594 |
| local_euler/duplicated.txt | 12 | 0.026 | newton x2 |
| local_euler/hanging.txt | 2 | 0.014 | newton |
| lowe_and_langley_2006/line.txt | 4 | 0.007 | newton |
| pendulum.txt | 0 | 0.006 | newton |
| polyester/simple.txt | 1 | 0.006 | newton |
| riser/riser.txt | 1875 | 2.795 | network 49 outer: newton x11, predicted x459 |
| riser/riser_ic1.txt | 1875 | 2.836 | network 49 outer: newton x11, predicted x459 |
| riser/riser_ic2.txt | 1875 | 3.215 | network 49 outer: newton x11, predicted x459 |
| seafloor.txt | 105 | 0.453 | axial continuation |
| syrope/exp_wc/line.txt | 1 | 0.009 | newton |
| syrope/linear_wc/line.txt | 0 | 0.008 | newton |
| syrope/quadratic_wc/line.txt | 1 | 0.008 | newton |
| tripod.txt | 5440 | 8.663 | network 86 outer: newton x24, predicted x1394, axial continuation x1 |
| viv/viv.txt | 5 | 0.016 | newton |
| wave_surface/wave_surface.txt | 19 | 0.040 | newton x5 |
| wavekin_2/wavekin_2.txt | 6 | 0.024 | newton |
| wavekin_2/wavekin_2_curr2.txt | 6 | 0.020 | newton |
| wavekin_2/wavekin_2_curr5.txt | 6 | 0.024 | newton |
| wavekin_2/wavekin_3.txt | 6 | 0.019 | newton |
| wavekin_2/wavekin_3_curr2.txt | 6 | 0.020 | newton |
| wavekin_2/wavekin_3_curr5.txt | 6 | 0.023 | newton |
| wavekin_3/test_dynamic_currents.txt | 1 | 0.008 | newton |
| wavekin_4/hanging_lines.txt | 0 | 0.047 | newton x10 |
| wavekin_7/wavekin_7.txt | 4 | 0.017 | newton |
| wavekin_current_1.txt | 6 | 0.023 | newton |
| wavekin_wave_1.txt | 6 | 0.021 | newton |

The other 3 are refused while read, each with its reason: body_tests/pinnedBody.txt's body
attachment ``CoupledPinned``, polyester/visco.txt's line, 1 m between points 2 m apart, and
time_schemes.txt's unexpanded template ``@DT@``.
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
