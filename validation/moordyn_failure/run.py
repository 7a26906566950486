"""A line failure in cablefem and in MoorDyn-C (PyPI ``moordyn``) on one MoorDyn input file with a FAILURE
section: does MoorDyn-C let the line go, and what does each code's line do after it?

    python -m validation.moordyn_failure.run          # 20 s after the release (~30 s on the shared machine)
    python -m validation.moordyn_failure.run --fast   # 5 s: what tests/test_validation_moordyn_failure.py asserts

``pendulum_failure.dat``: a 31 m chain hanging from a fixed fairlead to an anchor 4 m aside and 30 m below,
its anchor letting go at 0.05 s (the first coupling step). MoorDyn-C runs the file as written and once
more without its FAILURE section; cablefem runs it through a TOML wrapper. Printed: the largest
difference between MoorDyn-C's fairlead forces with and without the failure, how far each code's
anchor end moved, and the horizontal fairlead force of each code at the end (the chain swinging to
hang below its fairlead: 0 at rest). Writes results.json next to itself (or to ``--out``).
"""

import argparse
import json
import os
import re
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
INPUT = os.path.join(HERE, "pendulum_failure.dat")
ANCHOR = np.array([-4.0, 0.0, -30.0])
DT_OUT = 0.05  # s, MoorDyn's coupling step and cablefem's step


def moordyn_runs(duration, folder):
    """MoorDyn-C on the file with and without its FAILURE section: (forces (n, 3) [N], anchor end (3,)
    [m] at the end) for each."""
    from validation.moordyn.peer import run_moordyn

    text = open(INPUT, encoding="utf-8").read()
    intact = os.path.join(folder, "intact.dat")
    with open(intact, "w", encoding="utf-8") as handle:
        handle.write(re.sub(r"-+ FAILURE -+\n.*?(?=-+ OPTIONS)", "", text, flags=re.S))
    fixed = lambda t: (np.zeros((1, 3)), np.zeros((1, 3)))  # noqa: E731  the fairlead stays in place
    out = {}
    for name, path in (("failing", INPUT), ("intact", intact)):
        result = run_moordyn(path, fixed, duration=duration, dt_out=DT_OUT, line_nodes=True)
        out[name] = (result["forces"][:, 0], result["line_nodes"][0][0])
    return out


def cablefem_run(duration, folder):
    """cablefem on the file: (fairlead force (3,) [N] at the end, anchor end (3,) [m] at the end, the
    failure as summary.json has it)."""
    import meshio

    from cablefem.io import load_scene
    from cablefem.runs.run import run_scene

    wrapper = os.path.join(folder, "failure.toml")
    with open(wrapper, "w", encoding="utf-8") as handle:
        handle.write(f'name = "failure"\n[moordyn]\nfile = "{INPUT}"\n[solver]\ndt = {DT_OUT}\nduration = {duration}\n'
                     f'[output]\nevery = {duration}\n')
    out = os.path.join(folder, "cablefem")
    summary = run_scene(load_scene(wrapper), out, progress=False)
    with open(os.path.join(out, "tensions.csv"), encoding="utf-8") as handle:
        last = handle.read().strip().splitlines()[-1].split(",")
    frame = sorted(f for f in os.listdir(out) if f.startswith("failure_") and f.endswith(".vtu"))[-1]
    return np.array([float(x) for x in last[3:6]]), meshio.read(os.path.join(out, frame)).points[0], \
        summary["failures"][0]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="5 s instead of 20 s")
    parser.add_argument("--out", default=HERE, help="folder of results.json")
    args = parser.parse_args(argv)
    duration = 5.0 if args.fast else 20.0
    with tempfile.TemporaryDirectory(prefix="failure-") as folder:
        md = moordyn_runs(duration, folder)
        force, anchor, failure = cablefem_run(duration, folder)
    results = {
        "duration_s": duration,
        "moordyn_failing_minus_intact_N": float(np.max(np.abs(md["failing"][0] - md["intact"][0]))),
        "moordyn_anchor_moved_m": float(np.linalg.norm(md["failing"][1] - ANCHOR)),
        "moordyn_fairlead_fx_N": float(md["failing"][0][-1, 0]),
        "cablefem_anchor_moved_m": float(np.linalg.norm(anchor - ANCHOR)),
        "cablefem_fairlead_fx_N": float(force[0]),
        "cablefem_failure": failure,
    }
    print(f"after {duration:g} s, the anchor letting go at {failure['released_at']:g} s:")
    print(f"{'':34s} {'MoorDyn-C 2.7':>14s} {'cablefem':>10s}")
    print(f"{'anchor end moved [m]':34s} {results['moordyn_anchor_moved_m']:14.4g} {results['cablefem_anchor_moved_m']:10.4g}")
    print(f"{'fairlead fx at the end [N]':34s} {results['moordyn_fairlead_fx_N']:14.4g} {results['cablefem_fairlead_fx_N']:10.4g}")
    print(f"MoorDyn-C with FAILURE against without: largest force difference "
          f"{results['moordyn_failing_minus_intact_N']:.3g} N")
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "results.json"), "w", encoding="utf-8") as handle:
        json.dump(results, handle, indent=1)
    return results


if __name__ == "__main__":
    main()
