"""The lazy-wave power cable of validation/cables in this study's regular wave, in both codes.

    python -m validation.waves.lazy_wave [--out DIR]   # lazy_wave.json and lazy_wave.png here

The cable (``validation.cables.case``: 260 m, EI 2e4 N m^2, a 40 m buoyancy section, clamped vertical
at a hang-off 20 m below the surface) with its hang-off held still, in the wave of ``case``
(``WaveKin 7``, 4 m, 10 s, along +x: the cable's plane). MoorDyn-C runs the file with Rods (its
zero-length free Rods pass the bending moment through the joints, a Coupled Rod clamps the top;
``validation.cables.moordyn_side``), its relaxation in still water started from cablefem's static
shape; cablefem reads the same file with points for the Rods (one string on Hermite elements, its top
clamped: ``validation.cables.cablefem_side``), BDF2 at 0.01 s as validation/cables. Compared every
``SAMPLE`` s as the chain is: the hang-off tension |F| (the force the cable exerts on the hang-off,
shear included) and the curvature peak away from the hang-off (``moordyn_side.CLEAR``).
"""

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from cablefem.study import package_version, provenance, stamp, write_json
from validation.cables import cablefem_side, case as cable, moordyn_side
from validation.cables.comparison import static_start
from validation.waves.case import FREQUENCIES
from validation.waves.runners import SAMPLE, compare
from validation.waves.run import DURATION, WINDOW

HERE = Path(__file__).resolve().parent
MESHES = (1, 2)  # about 5 m and 2.5 m segments (``segments``)

WAVES = {"WaveKin": 7}  # the OPTIONS row both codes read, wave_frequencies.txt beside the file
DTM = 1e-4  # s: MoorDyn-C's step (validation/cables: 1e-4 s down to 1.25 m segments)
DT, INTEGRATOR = 0.01, "bdf2"  # cablefem's (validation/cables.comparison)


def segments(factor):
    """NumSegs (MoorDyn) = Hermite elements (cablefem) per section: about 5 m segments, times ``factor``."""
    return tuple(n * factor for n in cable.segments_for(5.0))


def run_both(factor, duration):
    """Both codes on the cable in the wave at ``segments(factor)``: {"moordyn": ..., "cablefem": ...}, each
    the times (n,), hang-off tension (n,) [N] and curvature peak (n,) [1/m] every ``SAMPLE`` s, the
    static ones, and wall times [s]."""
    mesh = segments(factor)
    with tempfile.TemporaryDirectory(prefix="waves-lazy-") as folder:
        (Path(folder) / "wave_frequencies.txt").write_text(FREQUENCIES)
        scene = cable.cablefem_scene(mesh, folder, options=WAVES, moving=False)
        ours = cablefem_side.run(scene, duration, SAMPLE, DT, INTEGRATOR)
        start = static_start(mesh, folder)
        md = moordyn_side.run(mesh, DTM, start, duration, SAMPLE, lambda t: np.array(cable.HANG_OFF),
                              keep=Path(folder) / "moordyn", options=WAVES,
                              files={"wave_frequencies.txt": FREQUENCIES})
    return {"moordyn": _series(md), "cablefem": _series(ours), "segments": int(sum(mesh))}


def _series(out):
    return {"t": out["times"], "tension": np.linalg.norm(out["run_force"], axis=1), "peak": out["run_peak"],
            "static_tension": float(np.linalg.norm(out["force"])), "static_peak": float(out["curvature_peak"][0]),
            "static_wall_time_s": out["static_wall_time_s"], "run_wall_time_s": out["run_wall_time_s"]}


def run(meshes=MESHES, duration=DURATION, window=WINDOW):
    """The study's numbers (dict): per mesh and quantity (hang-off tension, curvature peak) the
    comparison of ``runners.compare`` over t >= ``window`` [s], the static difference and wall times."""
    started, clock = provenance(), time.perf_counter()
    rows, series = [], {}
    for factor in meshes:
        both = run_both(factor, duration)
        md, ours = both["moordyn"], both["cablefem"]
        for quantity, key in (("hang-off tension", "tension"), ("curvature peak", "peak")):
            pick = lambda run_: {"t": run_["t"], "tension": run_[key]}  # noqa: E731  (compare's keys)
            rows.append({"quantity": quantity, "mesh": factor, "segments": both["segments"],
                         **compare(pick(md), pick(ours), window),
                         "static_difference": ours[f"static_{key}"] / md[f"static_{key}"] - 1.0,
                         "moordyn_static_s": md["static_wall_time_s"], "moordyn_run_s": md["run_wall_time_s"],
                         "cablefem_static_s": ours["static_wall_time_s"], "cablefem_run_s": ours["run_wall_time_s"]})
        series[factor] = (md, ours)
    return {"duration_s": duration, "window_from_s": window, "rows": rows, "series": series,
            "moordyn_version": package_version("moordyn"), "wall_time_s": time.perf_counter() - clock,
            "provenance": stamp(started)}


def report(results):
    """The table, printed (the compare's "mean" and "std" columns in kN for the tension, 1/km for kappa)."""
    print(f"the lazy-wave cable over t >= {results['window_from_s']:g} s (MoorDyn-C {results['moordyn_version']})")
    print(f"{'quantity':17s} {'mesh':>4s} {'static':>8s} {'mean':>9s} {'std':>8s} {'RMS/std':>8s} {'RMS/mean':>9s} "
          f"{'peak':>7s} {'trough':>7s} {'MoorDyn [s]':>12s} {'cablefem [s]':>12s}")
    for r in results["rows"]:
        unit = 1e3 if r["quantity"] == "curvature peak" else 1e-3
        print(f"{r['quantity']:17s} {r['segments']:4d} {100 * r['static_difference']:+7.2f}% {r['mean_N'] * unit:9.3f} "
              f"{r['std_N'] * unit:8.4f} {100 * r['rms_of_std']:7.1f}% {100 * r['rms_of_mean']:8.3f}% "
              f"{100 * r['peak_difference']:+6.2f}% {100 * r['trough_difference']:+6.2f}% "
              f"{r['moordyn_static_s']:5.1f}+{r['moordyn_run_s']:5.1f} {r['cablefem_static_s']:5.1f}+{r['cablefem_run_s']:5.1f}")


def figure(results, folder):
    """lazy_wave.png: both codes' hang-off tension and curvature peak over the window, on each mesh."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    for factor, (md, ours) in results["series"].items():
        for label, run_ in (("MoorDyn-C", md), ("cablefem", ours)):
            window = run_["t"] >= results["window_from_s"]
            mesh = f"{sum(segments(factor))} {'segments' if label == 'MoorDyn-C' else 'Hermite'}"
            axes[0].plot(run_["t"][window], run_["tension"][window] / 1e3, label=f"{label}, {mesh}")
            axes[1].plot(run_["t"][window], run_["peak"][window] * 1e3, label=f"{label}, {mesh}")
    axes[0].set_ylabel("hang-off tension [kN]")
    axes[1].set_ylabel("curvature peak [1/km]")
    axes[1].set_xlabel("time [s]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(Path(folder) / "lazy_wave.png", dpi=110)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=HERE, help="folder for lazy_wave.json and lazy_wave.png")
    args = parser.parse_args(argv)
    results = run()
    report(results)
    figure(results, args.out)
    write_json(args.out / "lazy_wave.json", {key: value for key, value in results.items() if key != "series"})


if __name__ == "__main__":
    main()
