"""The bending study's figure: errors against the element count (matplotlib imported here only)."""


def convergence(results, path):
    """Tip position errors of the elastica and the arc, the clamp moment's, and the first frequencies'
    against the element count, on log axes, with h^4 for reference; saved to ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2))
    for case in results["elastica"]:
        n = [r["elements"] for r in case["rows"]]
        axes[0].loglog(n, [r["tip_error"] for r in case["rows"]], "o-", label=f"tip, alpha {case['alpha']:g}")
        axes[0].loglog(n, [abs(r["moment_error"]) for r in case["rows"]], "s--", ms=3,
                       label=f"clamp moment, alpha {case['alpha']:g}")
    for case in results["end_moment"]:
        rows = [r for r in case["rows"] if r["tip_error"] > 1e-10]
        axes[1].loglog([r["elements"] for r in rows], [r["tip_error"] for r in rows], "o-",
                       label=f"arc tip, {case['theta_deg']:g} deg")
        axes[1].loglog([r["elements"] for r in case["rows"]], [r["curvature_error"] for r in case["rows"]], "s--",
                       ms=3, label=f"arc curvature, {case['theta_deg']:g} deg")
    for name, f in results["frequencies"].items():
        n = [r["elements"] for r in f["rows"]]
        for k in range(len(f["reference"])):
            axes[2].loglog(n, [r["errors"][k] for r in f["rows"]], "o-", ms=3, label=f"{name}, mode {k + 1}")
    for ax, title in zip(axes, ("elastica (tip load)", "pure end moment", "natural frequencies")):
        n = np.array([2.0, 32.0])
        ax.loglog(n, 1e-2 * (n / 2) ** -4.0, "k:", label="h^4")
        ax.set_xticks([2, 4, 8, 16, 32], minor=False)
        ax.set_xticks([], minor=True)
        ax.set_xticklabels(["2", "4", "8", "16", "32"])
        ax.set_xlabel("Hermite elements")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
    axes[0].set_ylabel("relative error")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
