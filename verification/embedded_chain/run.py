"""An embedded anchor chain pulled through clay, fully mobilised: cablefem's soil (rui2025 Eqs. 1-3)
against the equilibrium equations of the embedded chain (Neubecker & Randolph 1995).

A chain runs from a padeye z_a below the mudline up through clay whose strength grows with depth
(su = su_gradient z), to the mudline. Where the soil is fully mobilised, an element of unstretched
length ds carries the bearing resistance Q (normal to the chain, against its cutting) and the
friction F (along it, against its sliding), both per unit length:

    Q(z) = E_n d_b N_c s_u(z),   F(z) = E_t d_b s_u(z)                       (rui2025 Eq. 3 / (dL/2))

and with its submerged weight w, tension T, angle theta above the horizontal, the equilibrium of
the element d(T t)/ds + Q n - F t - w e_z = 0 (t = (cos theta, sin theta), n = (-sin theta, cos theta))
gives the equations of Neubecker & Randolph (1995), with the stretch of the chain kept:

    dT/ds = F + w sin(theta),   T dtheta/ds = -Q + w cos(theta),
    dx/ds = (1 + T/EA) cos(theta),   dz/ds = (1 + T/EA) sin(theta).

Dropping w, taking T ~ T_a and sin(theta) ~ theta, they integrate from the padeye (T_a, theta_a) to
the mudline (T_0, theta_0) in closed form: (T_a / 2)(theta_a^2 - theta_0^2) = z_a Q_bar (Q_bar the
mean of Q over the depth), and T_0 / T_a = exp(mu (theta_a - theta_0)), mu = F / Q = E_t / (E_n N_c).

The reference: the equations integrated with scipy (``solve_ivp``, rtol 1e-10) from a padeye force
(T_a, theta_a) up to the mudline, which gives the line's length L and where it reaches the mudline.
cablefem gets that chain (padeye, mudline point, L) and is driven to full mobilisation: the chain
starts 2 m behind on the reference's shape with the soil unloaded, and both ends are dragged
horizontally onto their places (``cablefem.statics.pretension.LoadPath``): every point of an inverse
catenary then slides along the chain (e_x . t = cos theta > 0) and cuts towards the chord
(e_x . n = -sin theta < 0) by far more than the springs' elastic offsets 1/k, so every point ends at
yield in the directions the equations assume (checked: ``mobilised``). The study reports cablefem's
padeye tension and angle against the reference's T_a and theta_a over element count and order.

Run ``python -m verification.embedded_chain.run [--fast] [--out DIR]``; ``run(fast=True)`` returns
what the tests assert on.
"""

import argparse
import time
from pathlib import Path

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq, fsolve

from cablefem.geometry import Horizontal
from cablefem.model.line import Line, LineType, Segment
from cablefem.loads.soil import Soil
from cablefem.statics.pretension import LoadPath
from cablefem.runs.results import end_forces
from cablefem.study import write_json
from cablefem.model.scene import Contact, Environment
from cablefem.fem.system import LineSystem

HERE = Path(__file__).resolve().parent

D_B = 0.185  # chain bar diameter [m] (rui2025 Table 2)
CHAIN = LineType("chain", diameter=1.8 * D_B, mass=685.0, EA=3.27e9, nominal_diameter=D_B)
ENVIRONMENT = Environment(water_density=1025.0, gravity=9.81)
SOIL = {"su_mudline": 0.0, "su_gradient": 1500.0, "bearing_factor": 7.6, "width_normal": 2.5,
        "width_tangential": 8.0}
MUDLINE = -200.0  # [m]: the chain stays in deep water (fully buoyed)
PADEYE_DEPTH = 10.0  # z_a [m]
PADEYE_TENSION, PADEYE_ANGLE = 1.0e6, np.radians(45.0)  # the reference's T_a [N], theta_a [rad]
DRAG, DRAG_STEPS = 2.0, 40  # [m]: both ends dragged horizontally onto their places, in steps
ORDERS = {1: (8, 16, 32, 64, 128), 2: (4, 8, 16, 32, 64), 3: (4, 8, 16, 32)}
FAST_ORDERS = {1: ORDERS[1], 2: ORDERS[2]}  # all of it takes ~3 s: the fast variant leaves out P3
RTOL = 1e-13  # solve_ivp: the reference to ~1e-12 (the issue asks 1e-8 at least)
#: relative errors below this are round-off (the padeye force from a residual of forces ~EA 1e-16 / h)
FLOOR = 1e-9
TOLERANCE = 1e-8  # relative to the weight; the padeye force is ~10x the chain's weight, and round-off of EA / h = 2e10 N/m sits at ~1e-8


def soil_profile():
    """The soil of the study as a ``Soil`` on one element: Q(depth) and F(depth) [N/m] from it."""
    keys = SOIL
    return Soil(Horizontal(-MUDLINE), keys["width_tangential"] * D_B,
                keys["width_normal"] * keys["bearing_factor"] * D_B, np.array([1.0 / D_B]), np.array([2.0 / D_B]),
                keys["su_mudline"], keys["su_gradient"], np.array([D_B]))


def resistances(depth):
    """Bearing Q and friction F [N/m] at full mobilisation at ``depth`` [m] below the mudline."""
    soil = soil_profile()
    s = soil.strength(np.atleast_1d(np.asarray(depth, dtype=float))[None, :])[0][0]
    return soil.a_n[0, 0] * s, soil.a_t[0, 0] * s


def weight():
    """Submerged weight per unit length [N/m]."""
    return CHAIN.submerged_weight(ENVIRONMENT.water_density, ENVIRONMENT.gravity)


def equations(s, y, w, EA):
    """Neubecker & Randolph's equations (module docstring) in y = (x, z, T, theta), z from the mudline."""
    x, z, T, theta = y
    Q, F = (float(v[0]) for v in resistances(-z))
    stretch = 1.0 + T / EA
    return [stretch * np.cos(theta), stretch * np.sin(theta), F + w * np.sin(theta),
            (-Q + w * np.cos(theta)) / T]


def reference(tension=PADEYE_TENSION, angle=PADEYE_ANGLE, depth=PADEYE_DEPTH, w=None, EA=CHAIN.EA):
    """The equations integrated from the padeye force (T_a [N], theta_a [rad]) at ``depth`` to the
    mudline: dict of L [m], the mudline point's x [m], T_0 [N], theta_0 [rad] and the profile."""
    w = weight() if w is None else w

    def mudline(s, y, *args):
        return y[1]

    mudline.terminal, mudline.direction = True, 1.0
    solution = solve_ivp(equations, (0.0, 50.0 * depth), [0.0, -depth, tension, angle], args=(w, EA),
                         events=mudline, rtol=RTOL, atol=RTOL * 1e-2, dense_output=True, method="DOP853")
    length = float(solution.t_events[0][0])
    x, z, T, theta = solution.y_events[0][0]
    engaged = brentq(lambda s: solution.sol(s)[1] + D_B, 0.0, length, xtol=1e-14)  # depth d_b
    return {"length": length, "x": float(x), "T0": float(T), "theta0": float(theta), "engaged": float(engaged),
            "solution": solution}


def closed_form(T0, theta0, depth=PADEYE_DEPTH):
    """Padeye (T_a [N], theta_a [rad]) of the approximate closed form from the mudline's (T_0, theta_0)."""
    mean_q = quad(lambda d: float(resistances(d)[0][0]), 0.0, depth, points=[D_B], epsabs=1e-6)[0] / depth
    Q, F = (float(v[0]) for v in resistances(depth))
    mu = F / Q

    def residual(unknown):
        Ta, theta_a = unknown
        return [0.5 * Ta * (theta_a**2 - theta0**2) - depth * mean_q, T0 / Ta - np.exp(mu * (theta_a - theta0))]

    Ta, theta_a = fsolve(residual, [T0, theta0 + 0.3], xtol=1e-13)
    return float(Ta), float(theta_a), mean_q, mu


def chain_system(ref, elements, order):
    """The reference's chain (padeye, mudline point, length) as a cablefem line in soil, with a mesh
    vertex where the chain crosses the depth d_b: there the soil's engagement (``Soil``) has its kink,
    which inside an element would hold P2 and P3 at ~1e-6."""
    padeye = np.array([0.0, 0.0, MUDLINE - PADEYE_DEPTH])
    end = np.array([ref["x"], 0.0, MUDLINE])
    line = Line("chain", padeye, end, [Segment(CHAIN, ref["length"], elements)], order)
    return LineSystem(line.split_at(ref["engaged"]), Horizontal(-MUDLINE), Contact(), ENVIRONMENT,
                      sections={"soil": SOIL})


def dragged(ref, elements, order):
    """cablefem's chain dragged to full mobilisation (module docstring): (system, X, path result)."""
    system = chain_system(ref, elements, order)
    solution, shift = ref["solution"], np.array([DRAG, 0.0, 0.0])

    def shape(s):
        x, z = solution.sol(np.minimum(s, ref["length"]))[:2]
        return np.column_stack([x, np.zeros_like(x), z + MUDLINE]) - shift

    X = system.fem.interpolate(shape)
    system.reset_history(X)  # the soil unloaded where the chain starts
    ends = np.array([system.line.anchor, system.line.fairlead])
    path = LoadPath(system, TOLERANCE, 50, "drag")
    system.tension.compression = True
    try:
        path.settle(X, ends - shift, "start")
        path.follow(ends - shift, ends, DRAG_STEPS)
    finally:
        system.tension.compression = False
    path.settle(path.X, ends, "tension-only end")
    return system, path.X, path.result


def mobilised(system, X):
    """Fraction of the soil's points at yield along the chain (reaction against its sliding, -t) and
    across it (reaction along +n, in the chain's vertical plane)."""
    soil = system.load("soil")
    state = system.state(X)
    e_t, e_n, _, _, _, _, size, t, _ = soil.offsets(state)
    along = soil.k_t * e_t >= 1.0 - 1e-9  # offset along +t at its yield: the soil pulls back along -t
    n = np.stack([-t[2], np.zeros_like(t[0]), t[0]])  # +n of a chain in the x-z plane
    across = (soil.k_n * size >= 1.0 - 1e-9) & (np.einsum("ceq,ceq->eq", -e_n, n) > 0.999 * size)
    return float(np.mean(along)), float(np.mean(across))


def padeye(system, X):
    """The force on the padeye: its tension [N] and angle above the horizontal [rad]."""
    anchor = end_forces(system, X)[1]
    return float(np.linalg.norm(anchor)), float(np.arctan2(anchor[2], anchor[0]))


def convergence(ref, orders):
    """Padeye tension and angle errors against the reference, per order and element count."""
    rows = []
    for order, counts in orders.items():
        for n in counts:
            start = time.perf_counter()
            system, X, result = dragged(ref, n, order)
            T, theta = padeye(system, X)
            along, across = mobilised(system, X)
            rows.append({"order": order, "elements": n, "tension": T, "angle": theta,
                         "tension_error": T / PADEYE_TENSION - 1.0, "angle_error": theta / PADEYE_ANGLE - 1.0,
                         "mobilised_along": along, "mobilised_across": across, "steps": result.steps,
                         "halvings": result.halvings, "wall_time_s": time.perf_counter() - start})
    return rows


def observed_orders(rows):
    """Observed order of the padeye tension and angle errors, per element order: between the two finest
    meshes whose errors stay above ``FLOOR``."""
    orders = {}
    for order in sorted({r["order"] for r in rows}):
        orders[order] = {}
        for key in ("tension_error", "angle_error"):
            pair = [r for r in rows if r["order"] == order and abs(r[key]) > FLOOR][-2:]
            ratio = pair[1]["elements"] / pair[0]["elements"]
            orders[order][key] = float(np.log(abs(pair[0][key]) / abs(pair[1][key])) / np.log(ratio))
    return orders


def run(fast=False):
    """The reference, the closed form and cablefem's convergence (``FAST_ORDERS`` when ``fast``)."""
    start = time.perf_counter()
    ref = reference()
    Ta, theta_a, mean_q, mu = closed_form(ref["T0"], ref["theta0"])
    weightless = reference(w=0.0)
    rows = convergence(ref, FAST_ORDERS if fast else ORDERS)
    return {"reference": {k: v for k, v in ref.items() if k != "solution"},
            "padeye": {"tension": PADEYE_TENSION, "angle_deg": float(np.degrees(PADEYE_ANGLE)), "depth": PADEYE_DEPTH},
            "closed_form": {"tension": Ta, "angle_deg": float(np.degrees(theta_a)), "mean_bearing": mean_q, "mu": mu,
                            "tension_error": Ta / PADEYE_TENSION - 1.0, "angle_error": theta_a / PADEYE_ANGLE - 1.0},
            "weightless": {"T0": weightless["T0"], "theta0_deg": float(np.degrees(weightless["theta0"])),
                           "length": weightless["length"]},
            "rows": rows, "observed_orders": observed_orders(rows), "wall_time_s": time.perf_counter() - start}


def table(results):
    """The study's tables as text."""
    ref, cf = results["reference"], results["closed_form"]
    lines = [f"reference (solve_ivp, rtol 1e-10): padeye {PADEYE_TENSION / 1e3:.0f} kN at {np.degrees(PADEYE_ANGLE):.1f} deg, "
             f"{PADEYE_DEPTH:g} m deep -> mudline {ref['T0'] / 1e3:.2f} kN at {np.degrees(ref['theta0']):.3f} deg, "
             f"L = {ref['length']:.4f} m, x = {ref['x']:.4f} m",
             f"closed form from the mudline values: padeye {cf['tension'] / 1e3:.2f} kN ({100 * cf['tension_error']:+.2f} %) at "
             f"{cf['angle_deg']:.3f} deg ({100 * cf['angle_error']:+.2f} %); Q_bar {cf['mean_bearing'] / 1e3:.3f} kN/m, "
             f"mu {cf['mu']:.4f}",
             f"without the chain's weight the same padeye force reaches the mudline at {results['weightless']['T0'] / 1e3:.2f} kN, "
             f"{results['weightless']['theta0_deg']:.3f} deg",
             "", f"{'order':>5}{'elements':>9}{'T_a error':>12}{'theta_a error':>15}{'at yield along/across':>24}"
             f"{'steps':>7}{'time [s]':>9}"]
    for r in results["rows"]:
        lines.append(f"{r['order']:>5}{r['elements']:>9}{r['tension_error']:12.2e}{r['angle_error']:15.2e}"
                     f"{r['mobilised_along']:>12.3f} /{r['mobilised_across']:6.3f}{r['steps']:7d}{r['wall_time_s']:9.2f}")
    for order, o in results["observed_orders"].items():
        lines.append(f"P{order}: observed order {o['tension_error']:.2f} (tension), {o['angle_error']:.2f} (angle)")
    lines.append(f"wall time {results['wall_time_s']:.1f} s")
    return "\n".join(lines)


def figures(results, out):
    """convergence.png: padeye errors against element count per order; names of the files."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, key, label in ((axes[0], "tension_error", "padeye tension"), (axes[1], "angle_error", "padeye angle")):
        for order in sorted({r["order"] for r in results["rows"]}):
            rows = [r for r in results["rows"] if r["order"] == order]
            n = np.array([r["elements"] for r in rows])
            err = np.array([abs(r[key]) for r in rows])
            ax.loglog(n, err, "o-", label=f"P{order} (order {results['observed_orders'][order][key]:.2f})")
        ax.axhline(abs(results["closed_form"][key]), color="0.5", ls="--", label="approximate closed form")
        ax.axhline(1e-2, color="C3", ls=":", lw=0.8, label="target 1 %")
        ax.set_xlabel("elements")
        ax.set_ylabel(f"relative error of the {label}")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.suptitle("embedded chain, fully mobilised: cablefem against Neubecker & Randolph's equations")
    fig.tight_layout()
    fig.savefig(Path(out) / "convergence.png", dpi=130)
    plt.close(fig)
    return ["convergence.png"]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="two meshes of P1 and P2 only")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for results.json and PNGs")
    args = parser.parse_args(argv)
    results = run(fast=args.fast)
    print(table(results))
    path = write_json(args.out / "results.json", results)
    print(f"wrote {path}, {', '.join(figures(results, args.out))}")


if __name__ == "__main__":
    main()
