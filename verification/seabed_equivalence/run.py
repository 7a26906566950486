"""One plane, five descriptions: the same static answer, and what the general projection costs.

desire2023 Sec. 2.2.2 (point-to-plane against vertex-normal projection), Sec. 5
and Table 6 (the general projection made a 120 s dynamic run 20 % slower on
the same flat seabed); issue 3's targets. Run
``python -m verification.seabed_equivalence.run [--fast] [--out DIR]``.

(a) equality: a 10 deg slope rising towards azimuth 60 deg (more across the
    line than along it, so the line rests on it sagging sideways) given as a
    plane, an STL mesh, a MoorDyn-C grid, a MoorDyn-F grid, scattered x y z
    soundings and a MoorDyn file with a SeafloorFile; the Table 5 chain
    anchored on it. Every scene is loaded as ``cablefem static`` loads it,
    with ``[seabed] simplify`` on (the planar file becomes the plane) and off
    (the grid's bilinear or the mesh's vertex-normal projection is used as
    is), and solved; fairlead and anchor forces and node positions are
    compared with the plane's (solved on the same mesh: statics fits a vertex
    to the touchdown on planes only).
(b) static cost: the solve over the planar mesh with detection on (it is the
    plane; plus the detection itself) and off (the general projection), in
    CPU time relative to the plane's, interleaved repeats.
(c) dynamic cost: the desire2023 flume flat case (Table 5 chain, 5 m / 6 s
    surge, friction, drag, added mass, BDF2 at dt = 0.01 s) over its 100 m
    floor as ``Horizontal`` and as triangulated horizontal surfaces taken as
    is (simplify off): the time steps with modified (the default) and full
    Newton, and the whole ``run_scene``, in CPU time relative to the
    horizontal's; and the cost of one ``project`` call inside the run on the
    flat mesh and on the non-planar steep flume step (the same code path, so
    the flat mesh stands for a non-planar one).

The parts: ``files.py`` (the plane and its descriptions), ``equality.py`` (a), ``cost.py`` (b, c),
``report.py`` (the tables).
"""

import argparse
import json
import sys
import tempfile
from pathlib import Path

if __package__ in (None, ""):  # python verification/seabed_equivalence/run.py
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from verification.seabed_equivalence.cost import dynamic_cost, dynamic_run, flat_meshes, static_cost  # noqa: E402,F401
from verification.seabed_equivalence.equality import equivalence  # noqa: E402
from verification.seabed_equivalence.files import MOORDYN  # noqa: E402,F401
from verification.seabed_equivalence.report import print_tables  # noqa: E402

HERE = Path(__file__).resolve().parent


def run(fast=False, folder=None):
    """All three parts; ``fast`` shortens the timings (for tests and CI). A dict of results."""
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(folder or scratch)
        results = {"equivalence": equivalence(folder)}
        results["static_cost"] = static_cost(folder, repeats=2 if fast else 7)
    results["dynamic_cost"] = dynamic_cost(duration=2.0 if fast else 4.0, repeats=1 if fast else 7,
                                           fast=fast, scene_duration=2.0 if fast else 30.0)
    return results


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="short timings (seconds, not minutes)")
    parser.add_argument("--out", type=Path, default=HERE, help="folder for results.json")
    args = parser.parse_args(argv)
    results = run(fast=args.fast)
    print_tables(results)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "results.json").write_text(json.dumps({"fast": args.fast, **results}, indent=1))


if __name__ == "__main__":
    main()
