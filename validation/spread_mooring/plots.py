"""The figures of validation/spread_mooring: single_lines.png, spread_offset.png, spread_polar.png."""

import numpy as np

from cablefem.statics.catenary import elastic_catenary

from validation.spread_mooring.lines import EA, HEIGHT, LENGTH, barreiro_line
from validation.spread_mooring.spread import ANCHOR_AZIMUTHS, DIRECTIONS, _unit, spread_forces, spread_layout


def figures(results, out):
    """PNG figures: single_lines.png, spread_offset.png and spread_polar.png in directory out."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    single_lines_figure(plt, results["single_lines"], out)
    spread_offset_figure(plt, results["spread"], out)
    spread_polar_figure(plt, results["spread"], out)
    plt.close("all")


def single_lines_figure(plt, single, out):
    """single_lines.png: per line, the tensions of (a), (b), (c) against the span, and their differences."""
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    for column, (name, data) in enumerate(single["lines"].items()):
        rows = data["rows"]
        spans = np.array([r["span_m"] for r in rows])
        dense = np.linspace(80.05, min(single["taut_span_m"] - 0.05, spans.max() + 0.1), 400)
        formula = [barreiro_line(x, data["weight_N_per_m"]) for x in dense]
        inside = np.array([f is not None for f in formula])
        rigid = [elastic_catenary(x, HEIGHT, LENGTH, np.inf, data["weight_N_per_m"]) for x in dense]
        ax = axes[0, column]
        ax.semilogy(dense[inside], [f["tension"] / 1e3 for f in formula if f is not None], "-", lw=3.5,
                    color="0.75", label="(a) barreiro2015 formula, T = T_H + w h")
        ax.semilogy(dense, [c.fairlead_tension / 1e3 for c in rigid], "-", color="C0",
                    label="(b) elastic_catenary, EA = inf")
        ax.semilogy(spans, [r["fem_tension_N"] / 1e3 for r in rows], "o", ms=4, color="C3",
                    label=f"(c) FEM statics, EA = {EA:.0e} N")
        ax.semilogy(dense[inside], [f["horizontal"] / 1e3 for f in formula if f is not None], "-", lw=3.5,
                    color="0.85")
        ax.semilogy(dense, [c.fairlead_horizontal / 1e3 for c in rigid], "--", color="C0",
                    label="horizontal tension T_H: (a), (b) dashed, (c) squares")
        ax.semilogy(spans, [r["fem_horizontal_N"] / 1e3 for r in rows], "s", ms=3.5, mfc="none", color="C3")
        ax.axvline(single["barreiro_limit_span_m"], color="0.5", ls=":", lw=1)
        ax.text(single["barreiro_limit_span_m"] - 0.15, 2.0, "touchdown\nat anchor", ha="right", fontsize=8,
                color="0.4")
        ax.set(ylabel="fairlead tension [kN]", ylim=(1.0, None),
               title=f"{name}: w = {data['weight_N_per_m']:g} N/m, h = {HEIGHT:g} m, l = {LENGTH:g} m")
        ax.legend(fontsize=7.5, loc="upper left")
        ax.grid(True, which="both", alpha=0.3)
        ax = axes[1, column]
        for key, label, style in (("fem_vs_barreiro_tension", "T: |(c)/(a) - 1|", "o-"),
                                  ("fem_vs_catenary_tension", "T: |(c)/(b) - 1|", "^--"),
                                  ("fem_vs_barreiro_horizontal", "T_H: |(c)/(a) - 1|", "s:"),
                                  ("fem_vs_elastic_tension", f"T: |(c)/(b at EA = {EA:.0e}) - 1|", "d-."),
                                  ("fitted_vs_elastic_tension", "T: |(c*)/(b at EA) - 1|, fitted mesh", "v"),
                                  ("elastic_vs_rigid_tension", f"T: EA = {EA:.0e} vs inf (closed forms)", "x-")):
            xs = [r["span_m"] for r in rows if key in r]
            ax.semilogy(xs, [max(r[key], 1e-12) for r in rows if key in r], style, ms=3.5, lw=1, label=label)
        ax.axhline(1e-4, color="k", lw=0.8)
        ax.set(xlabel="horizontal span anchor-fairlead X [m]", ylabel="relative difference", ylim=(1e-11, 1e-2))
        ax.legend(fontsize=7, ncol=2, loc="lower left")
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "single_lines.png", dpi=120)


def spread_offset_figure(plt, spread, out):
    """spread_offset.png: the restoring force against the offset, and the FEM against the closed form."""
    rows = spread["rows"]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    ax = axes[0]
    for i, direction in enumerate(DIRECTIONS):
        chosen = sorted((r for r in rows if r["direction_deg"] == direction or r["offset_m"] == 0.0),
                        key=lambda r: r["offset_m"])
        offsets = [r["offset_m"] for r in chosen]
        dense = np.linspace(0.0, max(spread["offsets_m"]), 60)
        closed = [np.hypot(*spread_forces(d * _unit(direction), fem=False)["closed_form"][:2]) / 1e3 for d in dense]
        ax.plot(dense, closed, "-", color=f"C{i}", lw=1, label=f"{direction:g} deg: closed form")
        ax.plot(offsets, [r["fem_restoring_N"] / 1e3 for r in chosen], "o", color=f"C{i}", ms=4,
                label=f"{direction:g} deg: FEM")
    ax.set(xlabel="floater offset [m]", ylabel="horizontal restoring force |F_h| [kN]",
           title="spread mooring: restoring force against offset")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(True, alpha=0.3)
    ax = axes[1]
    moving = [r for r in rows if r["offset_m"]]
    ax.semilogy([r["offset_m"] + 0.04 * (r["direction_deg"] % 120 / 30 - 1.5) for r in moving],
                [max(r["fem_vs_closed_form"], 1e-12) for r in moving], "o", ms=4,
                label="|F_FEM - F_closed form| / |F_closed form| (horizontal)")
    ax.semilogy([r["offset_m"] for r in rows], [max(r["fem_vs_closed_form_vertical"], 1e-12) for r in rows],
                "^", ms=4, label="vertical force, relative")
    checks = spread["checks"]
    for group, marker, label in (("rotation", "x", "120 deg rotation symmetry"), ("mirror", "+", "mirror symmetry")):
        ax.semilogy([c["offset_m"] for c in checks[group]], [max(c["relative"], 1e-12) for c in checks[group]],
                    marker, ms=6, label=label)
    ax.axhline(1e-4, color="k", lw=0.8)
    ax.axhline(1e-6, color="k", lw=0.8, ls=":")
    ax.set(xlabel="floater offset [m]", ylabel="relative difference", ylim=(1e-12, 1e-2),
           title="FEM against closed form; FEM symmetries")
    ax.legend(fontsize=7, loc="upper right")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "spread_offset.png", dpi=120)


def spread_polar_figure(plt, spread, out):
    """spread_polar.png: the plan view of the restoring forces, and |F_h| against the offset direction."""
    rows = spread["rows"]
    fig = plt.figure(figsize=(11, 6))
    ax = fig.add_subplot(1, 2, 1)
    anchors, fairleads = spread_layout()
    for anchor, fairlead in zip(anchors, fairleads):
        ax.plot([fairlead[0], anchor[0]], [fairlead[1], anchor[1]], "-", color="0.6", lw=1)
    ax.plot(anchors[:, 0], anchors[:, 1], "kv", ms=7, label="anchors")
    ax.plot(fairleads[:, 0], fairleads[:, 1], "ko", ms=3, label="fairleads at rest")
    largest = max(spread["offsets_m"])
    outer = [r for r in rows if r["offset_m"] == largest]
    ring, arrow = 55.0, 30.0  # [m] on the drawing: where each case is drawn, length of the largest arrow
    kilonewtons = max(r["fem_restoring_N"] for r in outer) / 1e3
    for r in outer:
        start = ring * _unit(r["direction_deg"])[:2]
        force = np.array(r["fem_force_N"][:2]) / 1e3 * arrow / kilonewtons
        ax.annotate("", xy=start + force, xytext=start, arrowprops={"arrowstyle": "->", "color": "C3", "lw": 1.4})
        ax.annotate("", xy=start + 6.0 * _unit(r["direction_deg"])[:2], xytext=start,
                    arrowprops={"arrowstyle": "->", "color": "C0", "lw": 1.0})
        ax.text(*(1.28 * start), f"{r['direction_deg']:g}\N{DEGREE SIGN}", fontsize=7, ha="center", va="center")
    ax.plot([], [], "-", color="C0", label=f"offset direction ({largest:g} m, not to scale)")
    ax.plot([], [], "-", color="C3", label=f"FEM restoring force (arrow {arrow:g} m = {kilonewtons:.1f} kN)")
    ax.set(aspect="equal", xlabel="x [m]", ylabel="y [m]", xlim=(-110, 110), ylim=(-110, 110),
           title=f"plan view: restoring force for a {largest:g} m offset\nin each direction (drawn on a ring)")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2)
    ax.grid(True, alpha=0.3)
    ax = fig.add_subplot(1, 2, 2, projection="polar")
    for j, offset in enumerate(spread["offsets_m"]):
        theta = np.radians(np.linspace(0.0, 360.0, 145))
        closed = [np.hypot(*spread_forces(offset * _unit(np.degrees(t)), fem=False)["closed_form"][:2]) / 1e3
                  for t in theta]
        ax.plot(theta, closed, "-", lw=1, color=f"C{j}", label=f"{offset:g} m: closed form")
        chosen = [r for r in rows if r["offset_m"] == offset]
        ax.plot(np.radians([r["direction_deg"] for r in chosen]), [r["fem_restoring_N"] / 1e3 for r in chosen],
                "o", ms=4, color=f"C{j}", label=f"{offset:g} m: FEM")
    ax.plot(np.radians(ANCHOR_AZIMUTHS), [0.0] * 3, "kv", ms=6)
    ax.set_title("|F_h| [kN] against the offset direction [deg]\n(anchors at 0, 120, 240 deg)", fontsize=10)
    ax.legend(fontsize=6.5, loc="upper left", bbox_to_anchor=(1.05, 1.0))
    fig.tight_layout()
    fig.savefig(out / "spread_polar.png", dpi=120)
