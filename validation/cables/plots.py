"""validation/cables' figures (matplotlib imported here only)."""


def figures(results, folder):
    """lazy_wave.png: the hang-off tension and the curvature peak over the run, MoorDyn-C's finest and
    coarsest against cablefem's finest and coarsest; convergence.png: the four compared numbers'
    differences from the reference against the wall time of each run."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    lazy = results["lazy_wave"]
    fig, axes = plt.subplots(2, 1, figsize=(10, 7), sharex=True)
    for code, style in (("moordyn", "-"), ("cablefem", "--")):
        for entry in (lazy[code][0], lazy[code][-1]):
            mesh = entry.get("segments", entry.get("elements"))
            label = f"{code} {mesh}"
            series = entry["series"]
            axes[0].plot(series["t"], np.asarray(series["tension"]) / 1e3, style, lw=1, label=label)
            axes[1].plot(series["t"], series["peak"], style, lw=1, label=label)
    axes[0].set_ylabel("hang-off tension [kN]")
    axes[1].set_ylabel("curvature peak [1/m]")
    axes[1].set_xlabel("t [s]")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{folder}/lazy_wave.png", dpi=110)
    plt.close(fig)

    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for quantity, ax in zip(("run_peak", "run_tension"), axes):
        for code, marker in (("moordyn", "o-"), ("cablefem", "s-")):
            entries = lazy[code][:-1] if code == "moordyn" else lazy[code]
            ax.loglog([e["run_wall_time_s"] for e in entries],
                      [max(abs(e["differences"][quantity]), 1e-6) for e in entries], marker, label=code)
        ax.axhline(0.01, color="k", lw=0.8, ls=":")
        ax.set_xlabel("run wall time [s]")
        ax.set_ylabel(f"|{quantity}| difference from MoorDyn's finest")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(f"{folder}/convergence.png", dpi=110)
    plt.close(fig)
