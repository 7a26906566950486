"""Figures of the rui2025 study: the configurations (rui2025 Fig. 4) and the tension along the line
(Fig. 5), from ``run.run``'s results."""

from pathlib import Path

import numpy as np

STYLES = {"conventional": ("conventional (no soil)", "0.5", "--"), "case1": ("Case 1: 850 m, padeye 10 m deep", "C0", "-"),
          "case2": ("Case 2: 840 m, padeye on the mudline", "C1", "-"),
          "case3": ("Case 3: 850 m, padeye on the mudline", "C2", "-"),
          "case3_catenary": ("Case 3, catenary start", "C2", ":")}


def _runs(results):
    runs = {"conventional": results["conventional"], **results["cases"]}
    runs["case3_catenary"] = results["case3_catenary"]
    return runs


def _radius(nodes):
    return np.hypot(nodes[:, 0], nodes[:, 1])


def configurations(results, path):
    """rui2025 Fig. 4: the lines in their vertical plane, whole and near the padeye."""
    import matplotlib.pyplot as plt

    fig, (whole, near) = plt.subplots(1, 2, figsize=(12, 4.6))
    for name, row in _runs(results).items():
        label, colour, style = STYLES[name]
        nodes = np.asarray(row["profile"]["nodes"])
        for ax in (whole, near):
            ax.plot(_radius(nodes), nodes[:, 2], style, color=colour, label=label, lw=1.4)
    for ax in (whole, near):
        ax.axhline(-200.0, color="saddlebrown", lw=0.8)
        ax.set_xlabel("distance from the platform centre [m]")
        ax.set_ylabel("z [m]")
        ax.grid(alpha=0.3)
    whole.invert_xaxis()
    near.set_xlim(845.0, 230.0)
    near.set_ylim(-211.0, -190.0)
    near.set_title("near the padeye (the mudline at z = -200 m)")
    whole.set_title("rui2025 Fig. 4: configurations after pretension")
    whole.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def tensions(results, path):
    """rui2025 Fig. 5: tension along the line against the distance from the platform centre."""
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 4.6))
    for name, row in _runs(results).items():
        label, colour, style = STYLES[name]
        nodes = np.asarray(row["profile"]["nodes"])
        ax.plot(_radius(nodes), np.asarray(row["profile"]["tension"]) / 1e3, style, color=colour, label=label, lw=1.4)
    paper = results["comparison"]
    for case, marker in (("case1", "o"), ("case2", "s"), ("case3", "^")):
        entry = paper[case]["fairlead_tension"]
        ax.plot(58.0, entry["paper"] / 1e3, marker, color=STYLES[case][1], mfc="none", ms=8)
    ax.plot(837.6, paper["case3"]["padeye_tension"]["paper"] / 1e3, "^", color=STYLES["case3"][1], mfc="none", ms=8,
            label="rui2025 (open markers)")
    ax.invert_xaxis()
    ax.set_xlabel("distance from the platform centre [m]")
    ax.set_ylabel("tension [kN]")
    ax.set_title("rui2025 Fig. 5: tension along the line after pretension")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def figures(results, out):
    """Write configurations.png and tensions.png to ``out``; their names."""
    out = Path(out)
    configurations(results, out / "configurations.png")
    tensions(results, out / "tensions.png")
    return ["configurations.png", "tensions.png"]
