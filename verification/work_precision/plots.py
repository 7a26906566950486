"""The figures of verification/work_precision: work_precision.png and references.png."""

import numpy as np

from verification.work_precision.errors import pareto
from verification.work_precision.motions import LOOSE_NEWTON


def figures(results, series, out_dir):
    """work_precision.png: error against wall time per motion (log-log, both codes, Pareto fronts);
    references.png: the two finest runs' tensions over the window and their difference."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    motions = [m for m, e in results["motions"].items() if "cablefem" in e]
    written = [out_dir / "work_precision.png", out_dir / "references.png"]
    work_precision_figure(plt, results, motions).savefig(written[0], dpi=90)
    plt.close("all")
    references_figure(plt, results, series, motions).savefig(written[1], dpi=90)
    plt.close("all")
    return [p.name for p in written]


def work_precision_figure(plt, results, motions):
    """Error against wall time per motion (log-log, both codes, Pareto fronts)."""
    fig, axes = plt.subplots(1, len(motions), figsize=(7.2 * len(motions), 5.6), squeeze=False)
    markers = {1: "o", 2: "s", 3: "^"}
    loose = f"BDF2, Newton tol {LOOSE_NEWTON:g}"
    colours = {"BDF2": "tab:red", loose: "tab:green", f"{loose}, modified Newton": "tab:olive",
               "gen-alpha": "tab:orange", "adaptive BDF2": "tab:purple"}
    for ax, motion in zip(axes[0], motions):
        _work_precision_axes(ax, results["motions"][motion], motion, markers, colours, loose)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles[4:], labels[4:], loc="lower center", ncol=5, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    return fig


def _work_precision_axes(ax, e, motion, markers, colours, loose):
    """One motion's runs, Pareto fronts, floors and legend entries on ``ax``."""
    for row in e["cablefem"]:
        s = row["settings"]
        if row["error"] is None:
            continue
        kind = ("adaptive BDF2" if s["adaptive"] else "gen-alpha" if s["integrator"] != "bdf2"
                else "BDF2" if s["tolerance"] == 1e-8
                else f"{loose}, modified Newton" if s.get("newton") == "modified" else loose)
        ax.scatter(row["wall_time_s"], row["error"], marker=markers[s["order"]], s=22,
                   facecolors="none", edgecolors=colours[kind], lw=0.9)
    md = e["moordyn"]
    ax.scatter([r["wall_time_s"] for r in md], [r["error"] for r in md], marker="x", color="tab:blue", s=24)
    for r in md:
        if r["largest_stable_dtM"]:
            ax.annotate(str(r["settings"]["segments"]), (r["wall_time_s"], r["error"]), fontsize=7,
                        color="tab:blue", xytext=(3, 3), textcoords="offset points")
    for rows, colour, name in ((md, "tab:blue", "MoorDyn Pareto front"),
                               (e["cablefem"], "tab:red", "cablefem Pareto front")):
        front = pareto(rows)
        ax.step([r["wall_time_s"] for r in front], [r["error"] for r in front], where="post",
                color=colour, lw=1.2, label=name)
    floor = e["references"]["moordyn_vs_cablefem"]
    ax.axhline(floor, color="0.4", ls=":", lw=1.0, label=f"model floor {floor:.1e} (finest vs finest)")
    check = max(c["change"] for c in e["references"]["checks"])
    ax.axhline(check, color="tab:red", ls="--", lw=0.8,
               label=f"cablefem reference: finest vs next {check:.1e}")
    for order, marker in markers.items():
        ax.scatter([], [], marker=marker, facecolors="none", edgecolors="0.3", label=f"cablefem P{order}")
    for kind, colour in colours.items():
        ax.scatter([], [], marker="o", facecolors="none", edgecolors=colour, label=f"cablefem {kind}")
    ax.scatter([], [], marker="x", color="tab:blue", label="MoorDyn (label: segments)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time [s] (cablefem: whole run; MoorDyn: Init + Step)")
    ax.set_ylabel("RMS fairlead tension error / mean tension")
    ax.set_title(f"{motion}: {e['duration_s']:g} s, error over {e['window_s'][0]:g}-{e['window_s'][1]:g} s "
                 "(each code against its own finest run)", fontsize=9)
    ax.grid(alpha=0.3, which="both")
    ax.legend(handles=ax.get_legend_handles_labels()[0][:4], fontsize=7, loc="upper right")


def references_figure(plt, results, series, motions):
    """The two finest runs' tensions over the window and their difference, per motion."""
    fig, axes = plt.subplots(2, len(motions), figsize=(7.2 * len(motions), 6.0), squeeze=False, sharex="col")
    for k, motion in enumerate(motions):
        e, s = results["motions"][motion], series[motion]
        t0 = e["window_s"][0]
        cf, md = s["cablefem_reference"], s["moordyn_reference"]
        window = md["t"] >= t0 - 1e-9
        axes[0, k].plot(cf["t"], cf["tension"] / 1e6, color="tab:red", lw=0.9, label="cablefem finest")
        axes[0, k].plot(md["t"], md["tension"] / 1e6, color="tab:blue", lw=0.9, ls="--", label="MoorDyn finest")
        axes[0, k].set_xlim(t0, e["window_s"][1])
        axes[0, k].set_ylabel("fairlead tension [MN]")
        axes[0, k].legend(fontsize=8)
        axes[0, k].set_title(motion, fontsize=9)
        difference = md["tension"][window] - np.interp(md["t"][window], cf["t"], cf["tension"])
        axes[1, k].plot(md["t"][window], difference / 1e3, color="0.3", lw=0.8)
        axes[1, k].set_ylabel("MoorDyn - cablefem [kN]")
        axes[1, k].set_xlabel("t [s]")
        for ax in axes[:, k]:
            ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig
