"""The figure of verification/stability: tensions.png."""

import numpy as np


def figures(results, out):
    """tensions.png: the fairlead tension of the stiff, snap, stop and edge cases."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels = [(k, t) for k, t in (("stiff", "1. stiff line vs closed form"), ("snap", "2. snap loads"),
                                   ("edge", "3. steep step"), ("stop", "5. sudden stop")) if k in results]
    if not panels:
        return
    fig, axes = plt.subplots(len(panels), 1, figsize=(10, 3.2 * len(panels)), squeeze=False)
    for ax, (key, title) in zip(axes[:, 0], panels):
        for label, curve in results[key]["series"].items():
            ax.plot(curve["t"], np.array(curve["fairlead_tension"]) / 1e6, lw=0.8, label=label)
        if key == "stiff":
            closed = results[key]["closed_form"]
            ax.plot(closed["t"], np.array(closed["fairlead_tension"]) / 1e6, "k--", lw=1, label="closed form")
            ax.set_ylim(4.0, 6.0)
        ax.set(title=title, xlabel="t [s]", ylabel="fairlead tension [MN]")
        ax.legend(fontsize=6, ncol=3)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "tensions.png", dpi=110)
    plt.close("all")
