"""The figures of verification/batista_perkovic: Fig. 8 and the convergence plot."""

import math

import numpy as np

from verification.batista_perkovic.case import LENGTH, MESHES, ORDERS, SLOPE, TARGETS, Case


def figures(results, out):
    """fig8.png (FEM nodes over the closed forms, with a magnification) and convergence.png."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(2, 1, figsize=(9, 8))
    s = np.linspace(0.0, LENGTH, 1000)
    paper_rows = results["setups"][0]["rows"]
    touchdowns = []
    for k, row in enumerate(paper_rows):  # in the anchor's frame, where the five seabeds coincide
        case = Case(row["force"])
        curve = case.reference_points(case.inextensible, s) - case.anchor
        nodes = np.array(row["positions_32_nodes"]) - case.anchor
        touchdowns.append(case.reference_points(case.inextensible, [case.inextensible.touchdown_s])[0] - case.anchor)
        for a in ax:
            a.plot(curve[:, 0], curve[:, 2], "-", color=f"C{k}", lw=1, label=f"closed form, H = {row['force'] / 1e6:g} MN")
            a.plot(nodes[:, 0], nodes[:, 2], "o", color=f"C{k}", ms=3)
    seabed_x = np.array([-20.0, 640.0])
    for a in ax:
        a.plot(seabed_x, seabed_x * math.tan(SLOPE), "k-", lw=0.8, label="seabed (-15 deg)")
    touchdowns = np.array(touchdowns)
    ax[1].set(xlim=(touchdowns[:, 0].min() - 25.0, touchdowns[:, 0].max() + 25.0),
              ylim=(touchdowns[:, 2].min() - 12.0, touchdowns[:, 2].max() + 8.0))
    ax[0].set(xlabel="x from the anchor [m]", ylabel="z from the anchor [m]",
              title="desire2023 Fig. 8: FEM nodes (P1 x 31, dots) over the inextensible closed form (lines)")
    ax[1].set(xlabel="x from the anchor [m]", ylabel="z from the anchor [m]", title="magnified at the touchdowns")
    ax[0].legend(fontsize=7)
    for a in ax:
        a.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "fig8.png", dpi=120)
    study = results["convergence"]
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.5))
    styles = {"uniform": "o-", "fitted": "s--", "exact-vertex": "^:"}
    for mesh in MESHES:
        for order in ORDERS:
            runs = [r for r in study["runs"] if r["mesh"] == mesh and r["order"] == order]
            n = [r["elements"] for r in runs]
            kw = dict(color=f"C{order - 1}", label=f"P{order} {mesh}")
            ax[0].loglog(n, [max(abs(r["elastic"]["fairlead_tension_error"]), 1e-13) for r in runs], styles[mesh], **kw)
            ax[1].loglog(n, [r["elastic"]["node_position_error_m"] for r in runs], styles[mesh], **kw)
            for r in runs:
                if not r["converged"]:  # Newton's step-size exit: marked, not trusted
                    ax[0].loglog(r["elements"], max(abs(r["elastic"]["fairlead_tension_error"]), 1e-13), "kx", ms=9)
                    ax[1].loglog(r["elements"], r["elastic"]["node_position_error_m"], "kx", ms=9)
    ax[0].axhline(TARGETS["p1_32_nodes_tension"], color="k", lw=0.6)
    ax[0].axhline(TARGETS["p2_p3_tension"], color="k", lw=0.6, ls="--")
    ax[1].axhline(TARGETS["p1_32_nodes_position_m"], color="k", lw=0.6)
    ax[0].set(xlabel="elements", ylabel="|fairlead tension error| (relative)", title=f"H = {study['force'] / 1e6:g} MN")
    ax[1].set(xlabel="elements", ylabel="max node position error [m]", title="against the elastic closed form")
    ax[0].legend(fontsize=6, ncol=3, title="x: stopped above residual 1e-3", title_fontsize=6)
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "convergence.png", dpi=120)
    plt.close("all")
