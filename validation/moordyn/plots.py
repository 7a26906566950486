"""The figures of validation/moordyn: per case, both codes' tensions overlaid with their differences,
and a summary of the switches."""

import textwrap
from pathlib import Path

import numpy as np

from validation.moordyn.comparison import on_grid
from validation.moordyn.inputs import MN

#: how the figures draw each series: (label, colour, line style, width)
STYLES = {"moordyn": ("MoorDyn", "tab:blue", "-", 1.6), "cablefem": ("cablefem", "tab:red", "--", 1.2),
          "vertical": ("cablefem, MoorDyn's vertical contact", "black", ":", 1.4),
          "moordyn_relaxed": ("MoorDyn from its relaxation under friction", "tab:cyan", "-.", 1.2),
          "lumped": ("cablefem, lumped mass", "tab:green", "-.", 1.1)}
SWITCH_LABELS = {
    "vertical_contact": "contact vertical, friction horizontal, as MoorDyn-C",
    "friction": "friction mu = 0.5 on, both codes",
    "friction_vertical_contact": "friction mu = 0.5 on + contact vertical",
    "friction_vertical_contact_moordyn_relaxed": "as above, MoorDyn from its relaxation under friction",
    "no_seabed_damping": "seabed damping cBot = 0, both codes",
    "no_friction": "friction off, both codes",
    "hydrodynamics_per_unstretched_length": "drag, added mass per unstretched length, as MoorDyn",
    "cdax_not_converted": "CdAx read without the pi (cablefem; shows the conversion)",
    "lumped_mass": "lumped structural mass in cablefem, as MoorDyn's nodes",
    "kbot_default": "kBot = 3e6 N/m^3 (MoorDyn's default), both codes",
    "cablefem_kbot_3e5_moordyn_default": "kBot 3e5 in cablefem, 3e6 in MoorDyn",
}


def _difference_series(md, cf, k, line, scale):
    """Times and cablefem - MoorDyn tension of point k / cablefem line ``line`` on the coarser grid, over scale."""
    grid = cf["t"] if len(cf["t"]) <= len(md["t"]) else md["t"]
    return grid, (on_grid(cf["t"], cf["tensions"][:, line], grid) - on_grid(md["t"], md["tensions"][:, k], grid)) / scale


def _overlay(plt, entry, order, runs, title, path):
    """Rows per line: tensions of ``runs`` (list of (style key, MoorDyn-or-cablefem run, is_moordyn)) over
    the run, and each cablefem run minus the first MoorDyn run in % of MoorDyn's window mean; a case
    with one line gets a second row, the last period enlarged."""
    rows = [(k, line, False) for k, line in enumerate(order)]
    if len(order) == 1:
        rows.append((0, order[0], True))
    fig, axes = plt.subplots(len(rows), 2, figsize=(12, 2.7 * len(rows) + 0.9), squeeze=False,
                             gridspec_kw={"width_ratios": [1.35, 1]})
    t0, t1 = entry["window_s"]
    reference = next(run for _, run, is_md in runs if is_md)
    for (k, line, zoom), (left, right) in zip(rows, axes):
        mean = float(on_grid(reference["t"], reference["tensions"][:, k],
                             reference["t"][reference["t"] >= t0 - 1e-9]).mean())
        for key, run, is_md in runs:
            label, colour, style, width = STYLES[key]
            column = k if is_md else line
            left.plot(run["t"], run["tensions"][:, column] / MN, color=colour, ls=style, lw=width, label=label)
            if not is_md:
                grid, diff = _difference_series(reference, run, k, line, mean)
                right.plot(grid, 100 * diff, color=colour, ls=style, lw=width, label=f"{label} - MoorDyn")
        for ax in (left, right):
            ax.axvspan(t0, t1, color="0.92", zorder=0)
            ax.grid(alpha=0.3)
            ax.set_xlim((t1 - entry["period_s"], t1) if zoom else (0.0, t1))
        right.axhline(0.0, color="0.5", lw=0.6)
        left.set_ylabel(f"{entry['lines'][k]}\nfairlead tension [MN]")
        right.set_ylabel("difference [% of MoorDyn mean]")
        right.set_title(f"{entry['lines'][k]}: MoorDyn mean {mean / MN:.3f} MN over the shaded window"
                        + (", last period" if zoom else ""), fontsize=9)
    axes[0, 0].legend(loc="best", fontsize=8)
    axes[0, 1].legend(loc="best", fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("t [s]")
    fig.suptitle("\n".join(textwrap.wrap(title, 140, break_long_words=False)) if "\n" not in title else title,
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return Path(path).name


def _switch_summary(plt, results, path):
    """Bars: the largest |mean| and RMS difference over a case's lines, as run and with each switch."""
    rows = []
    for case, entry in results["cases"].items():
        for name, switch in entry["switches"].items():
            if "error" in switch:
                continue
            before, after = entry["differences"], switch["differences"]
            rows.append((f"{case}:\n{SWITCH_LABELS.get(name, name)}",
                         [max(abs(r[key]) for r in before) for key in ("mean", "rms")],
                         [max(abs(r[key]) for r in after) for key in ("mean", "rms")]))
    if not rows:
        return None
    height = 0.5 * len(rows) + 1.4
    fig, axes = plt.subplots(1, 2, figsize=(14, height), sharey=True)
    y = np.arange(len(rows))[::-1]
    for j, (ax, what) in enumerate(zip(axes, ("|mean|", "RMS"))):
        ax.barh(y + 0.2, [100 * max(r[1][j], 1e-5) for r in rows], height=0.38, color="0.65",
                label="as in the MoorDyn file")
        ax.barh(y - 0.2, [100 * max(r[2][j], 1e-5) for r in rows], height=0.38, color="tab:green",
                label="with the switch")
        ax.set_xscale("log")
        ax.set_xlim(5e-3, 300)
        ax.set_xlabel(f"{what} of cablefem - MoorDyn [% of MoorDyn mean],\nlargest over the lines")
        ax.axvline(1.0, color="0.3", lw=0.8, ls="--")
        ax.grid(alpha=0.3, axis="x", which="both")
    axes[0].set_yticks(y)
    axes[0].set_yticklabels([r[0] for r in rows], fontsize=8)
    axes[1].legend(loc="lower right", fontsize=8)
    fig.suptitle("Physics switches: fairlead tension difference over the last two periods, "
                 "before and after each switch (dashed: 1 %)", fontsize=10)
    fig.subplots_adjust(left=0.3, right=0.98, wspace=0.06, top=1 - 0.45 / height, bottom=0.85 / height)
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return Path(path).name


def figures(results, series, out_dir):
    """PNGs: per case the fairlead tension of both codes and their difference (slopes add cablefem
    with MoorDyn's vertical contact); the friction switch on the up-slope; the switch summary."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out_dir = Path(out_dir)
    written = []
    for case, entry in results["cases"].items():
        data = series[case]
        runs = [("moordyn", data["moordyn"], True), ("cablefem", data["cablefem"], False)]
        if "vertical_contact" in data:
            runs.append(("vertical", data["vertical_contact"]["cablefem"], False))
        if "lumped_mass" in data:
            runs.append(("lumped", data["lumped_mass"]["cablefem"], False))
        written.append(_overlay(plt, entry, data["order"], runs, entry["title"], out_dir / f"{case}.png"))
        if "friction" in data and "friction_vertical_contact" in data:
            runs = [("moordyn", data["friction"]["moordyn"], True), ("cablefem", data["friction"]["cablefem"], False),
                    ("vertical", data["friction_vertical_contact"]["cablefem"], False)]
            if "friction_vertical_contact_moordyn_relaxed" in data:
                runs.append(("moordyn_relaxed", data["friction_vertical_contact_moordyn_relaxed"]["moordyn"], True))
            written.append(_overlay(plt, entry, data["order"], runs,
                                    f"{case} with seabed friction mu = 0.5 in both codes (MoorDyn-C: isotropic "
                                    "saturated damping on the horizontal velocity), both from the frictionless "
                                    "equilibrium unless said",
                                    out_dir / f"{case}-friction.png"))
    summary = _switch_summary(plt, results, out_dir / "switches.png")
    if summary:
        written.append(summary)
    return written
