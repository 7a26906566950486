"""Cyclic fairlead motion after the pretension of rui2025's Case 1 (``validation.rui2025.run``): the
padeye tension relaxes as the embedded chain cuts its trench (rui2025 Sec. 1, after Shen et al. 2019
and Xiong et al. 2017's inverse catenary shakedown).

The line of Case 1 (850 m, padeye 10 m below the mudline, [soil] as in Sec. 4) is pretensioned by its
path (``cablefem.statics.pretension``), then ``cablefem run`` moves its fairlead harmonically along the line's
vertical plane (surge ``AMPLITUDE`` [m] at ``PERIOD`` [s], ramped in over the first period). Each
cycle pulls the embedded chain up through the clay, which yields and keeps the trench: the next pull
finds the chain higher and straighter, the soil above it weaker, and the padeye gets less of the
fairlead's load. The table gives, per cycle, the peak fairlead and padeye tensions and the soil's
plastic work, whose growth stops as the trench settles (shakedown).

    python -m validation.rui2025.cyclic [--fast] [--out DIR]
"""

import argparse
import csv
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from cablefem.runs.run import run_scene
from cablefem.model.scene import Motion, Output
from cablefem.study import write_json

from . import run as study

HERE = Path(__file__).resolve().parent
#: surge amplitude [m] (towards the platform centre and away from the anchor) and period [s]
AMPLITUDE, PERIOD = 6.0, 30.0
DT = 0.1  # [s]


def cyclic_scene(cycles):
    """Case 1 with the fairlead moving ``cycles`` periods (the first a ramp) and frames once a period."""
    base = study.scene("case1", study.SOIL)
    motion = Motion(kind="harmonic", amplitude=(-AMPLITUDE, 0.0, 0.0), period=PERIOD, ramp=PERIOD)
    solver = replace(base.solver, dt=DT, duration=cycles * PERIOD)
    return replace(base, name="rui2025-case1-cyclic", motion=motion, solver=solver,
                   output=Output(dir=base.output.dir, every=PERIOD))


def read_rows(path):
    """tensions.csv as a dict of columns (arrays)."""
    with open(path) as handle:
        rows = list(csv.DictReader(handle))
    return {key: np.array([float(row[key]) for row in rows]) for key in rows[0]}


def run(cycles=10, out=None):
    """The run and its per-cycle peaks: a dict (``table``)."""
    with tempfile.TemporaryDirectory(prefix="cablefem-rui2025-cyclic-") as tmp:
        folder = Path(out or tmp)
        start = time.perf_counter()
        summary = run_scene(cyclic_scene(cycles), folder, progress=False)
        wall = time.perf_counter() - start
        rows = read_rows(folder / "tensions.csv")
    cycle = np.floor(rows["t"] / PERIOD - 1e-9).astype(int)
    peaks = [{"cycle": int(k) + 1,
              "fairlead_max": float(rows["fairlead_tension"][cycle == k].max()),
              "padeye_max": float(rows["anchor_tension"][cycle == k].max()),
              "padeye_min": float(rows["anchor_tension"][cycle == k].min())}
             for k in range(cycles)]
    settled = peaks[1:]  # the first cycle is the ramp
    return {"amplitude_m": AMPLITUDE, "period_s": PERIOD, "dt_s": DT, "cycles": cycles, "peaks": peaks,
            "padeye_relaxation": settled[-1]["padeye_max"] / settled[0]["padeye_max"] - 1.0,
            "fairlead_change": settled[-1]["fairlead_max"] / settled[0]["fairlead_max"] - 1.0,
            "steps": summary["steps"], "newton_iterations": summary["newton_iterations"],
            "status": summary["status"], "wall_time_s": wall,
            "series": {"t": rows["t"][::10], "fairlead_tension": rows["fairlead_tension"][::10],
                       "anchor_tension": rows["anchor_tension"][::10]}}


def table(results):
    """The per-cycle peaks as text."""
    lines = [f"Case 1, surge {results['amplitude_m']:g} m every {results['period_s']:g} s (dt {results['dt_s']:g} s): "
             "peak tensions per cycle [kN]",
             f"{'cycle':>5}{'fairlead max':>14}{'padeye max':>12}{'padeye min':>12}"]
    for row in results["peaks"]:
        lines.append(f"{row['cycle']:5d}{row['fairlead_max'] / 1e3:14.1f}{row['padeye_max'] / 1e3:12.1f}"
                     f"{row['padeye_min'] / 1e3:12.1f}")
    lines.append(f"padeye peak from cycle 2 to {results['cycles']}: {100 * results['padeye_relaxation']:+.1f} %, "
                 f"fairlead peak {100 * results['fairlead_change']:+.1f} %; {results['steps']} steps, "
                 f"{results['newton_iterations']} Newton iterations, {results['wall_time_s']:.1f} s ({results['status']})")
    return "\n".join(lines)


def figure(results, path):
    """The fairlead and padeye tension against time."""
    import matplotlib.pyplot as plt

    series = results["series"]
    fig, ax = plt.subplots(figsize=(8, 4.2))
    ax.plot(series["t"], np.asarray(series["fairlead_tension"]) / 1e3, lw=1.0, label="fairlead")
    ax.plot(series["t"], np.asarray(series["anchor_tension"]) / 1e3, lw=1.0, label="padeye (10 m deep)")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("tension [kN]")
    ax.set_title(f"Case 1 after pretension, surge {results['amplitude_m']:g} m / {results['period_s']:g} s")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="4 cycles instead of 10")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for cyclic.json and cyclic.png")
    args = parser.parse_args(argv)
    results = run(cycles=4 if args.fast else 10)
    print(table(results))
    write_json(args.out / "cyclic.json", results)
    figure(results, args.out / "cyclic.png")
    print(f"wrote {args.out / 'cyclic.json'}, {args.out / 'cyclic.png'}")


if __name__ == "__main__":
    main()
