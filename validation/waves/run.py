"""cablefem and MoorDyn-C in the same regular wave: a chain catenary and a chain with a buoy.

Run ``python -m validation.waves.run [--fast] [--out DIR]``; ``run(fast=True)`` returns the numbers
tests/test_validation_waves.py asserts (the chain on the file's mesh, a shorter window).

Both codes read the same MoorDyn file (``case.py``: WaveKin 7, wave_frequencies.txt), the fairlead
held still, friction off; each starts from its own equilibrium in still water, the wave at full
height from t = 0. The fairlead tension is compared over the window after the start's transient
(``WINDOW``): the RMS difference in % of the wave-driven standard deviation (MoorDyn's) and of the
mean tension, on the file's mesh (MoorDyn's NumSegs = cablefem's P1 elements) and on twice as fine
a mesh; switched: the buoy without the fluid inertia (1 + Ca) rho V a_w that MoorDyn-C's points
leave out (``runners.run_cablefem``).
"""

import argparse
import time
from pathlib import Path

from cablefem.study import package_version, provenance, stamp, write_json
from validation.waves.case import write_inputs
from validation.waves.runners import compare, run_cablefem, run_moordyn, scene_of

HERE = Path(__file__).resolve().parent
SWITCHED = "points without fluid inertia"  # the one switch: MoorDyn-C's points have none
DURATION, WINDOW = 90.0, 30.0  # s: the run and the start of the compared window


def run(fast=False):
    """The study's numbers (dict)."""
    started, clock = provenance(), time.perf_counter()
    paths = write_inputs()
    duration, window = (40.0, 20.0) if fast else (DURATION, WINDOW)
    plan = [("chain", 1, {})] if fast else [("chain", 1, {}), ("chain", 2, {}), ("buoy", 1, {}), ("buoy", 2, {}),
                                            ("buoy", 1, {"point_fluid_inertia": False})]
    moordyn, rows, series = {}, [], {}
    for case, factor, switches in plan:
        if (case, factor) not in moordyn:
            moordyn[case, factor] = run_moordyn(paths[case], duration, factor, dtM=2.5e-4 / factor)
        ours = run_cablefem(scene_of(paths[case], factor), duration, **switches)
        md = moordyn[case, factor]
        rows.append({"case": case, "mesh": factor, "segments": sum(md["segments"].values()),
                     "elements": ours["elements"], "switches": [SWITCHED] if switches else [],
                     **compare(md, ours, window),
                     "moordyn_wall_s": md["wall_time_s"], "cablefem_wall_s": ours["wall_time_s"]})
        series[case, factor, SWITCHED if switches else ""] = (md, ours)
    return {"duration_s": duration, "window_from_s": window, "rows": rows, "series": series,
            "moordyn_version": package_version("moordyn"), "wall_time_s": time.perf_counter() - clock,
            "provenance": stamp(started)}


def report(results):
    """The table, printed."""
    print(f"fairlead tension over t >= {results['window_from_s']:g} s (MoorDyn-C {results['moordyn_version']})")
    print(f"{'case':6s} {'mesh':>4s} {'switches':28s} {'mean [kN]':>9s} {'std [kN]':>8s} {'RMS/std':>8s} "
          f"{'RMS/mean':>9s} {'peak':>7s} {'trough':>7s}")
    for r in results["rows"]:
        print(f"{r['case']:6s} {r['segments']:4d} {','.join(r['switches']) or '-':28s} {r['mean_N'] / 1e3:9.2f} "
              f"{r['std_N'] / 1e3:8.3f} {100 * r['rms_of_std']:7.1f}% {100 * r['rms_of_mean']:8.3f}% "
              f"{100 * r['peak_difference']:+6.2f}% {100 * r['trough_difference']:+6.2f}%")


def figures(results, folder):
    """One PNG per case: both codes' fairlead tension over the window, on each mesh."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    for case in sorted({key[0] for key in results["series"]}):
        fig, ax = plt.subplots(figsize=(9, 4))
        for (name, factor, switched), (md, ours) in results["series"].items():
            if name != case:
                continue
            for label, run_ in (("MoorDyn-C", md), ("cablefem", ours)):
                if label == "MoorDyn-C" and switched:
                    continue  # the switched run shares MoorDyn's
                window = run_["t"] >= results["window_from_s"]
                mesh = f"{sum(md['segments'].values())} segments" if label == "MoorDyn-C" else f"{ours['elements']} P1"
                ax.plot(run_["t"][window], run_["tension"][window] / 1e3,
                        label=f"{label}, {mesh}{', ' + switched if switched else ''}")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("fairlead tension [kN]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(Path(folder) / f"{case}.png", dpi=110)
        plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="the chain on the file's mesh, 40 s (the tests)")
    parser.add_argument("--out", type=Path, default=HERE, help="folder for results.json and the figures")
    args = parser.parse_args(argv)
    results = run(fast=args.fast)
    report(results)
    figures(results, args.out)
    write_json(args.out / "results.json", {key: value for key, value in results.items() if key != "series"})


if __name__ == "__main__":
    main()
