"""The bending study's tables, printed from its results (``run.run``)."""

import math


def _orders(orders, key):
    found = orders.get(key, {}).get("fitted")
    return "-" if found is None else f"{found:.2f}"


def print_tables(results):
    """Print every case's table."""
    c = results["cantilever"]
    print(f"cantilever under its own weight (tip w L^4 / 8 EI = {c['tip_deflection']:.6g} m): relative errors")
    print("  elements  tip          vertices     Newton")
    for r in c["rows"]:
        print(f"  {r['elements']:8d}  {r['tip_error']:+.3e}  {r['node_error']:.3e}    {r['iterations']}")

    print("\nelastica under a dead tip load (Bisshopp & Drucker 1945), from straight at the full load:")
    print("  tip error |r - r_exact| / L, clamp curvature from r'' and from the clamp's reaction (relative)")
    for case in results["elastica"]:
        x, drop = case["tip"]
        print(f"  alpha = PL^2/EI = {case['alpha']:g}: tip x/L = {x:.10f}, drop/L = {drop:.10f}, "
              f"angle {case['tip_angle_deg']:.4f} deg")
        print("    elements  tip          kappa(0) r''   M(0) reaction  Newton")
        for r in case["rows"]:
            print(f"    {r['elements']:8d}  {r['tip_error']:.3e}    {r['curvature_error']:+.3e}     "
                  f"{r['moment_error']:+.3e}     {r['iterations']}")
        o = case["orders"]
        print(f"    observed order: tip {_orders(o, 'tip_error')}, kappa(0) {_orders(o, 'curvature_error')}, "
              f"M(0) {_orders(o, 'moment_error')}")

    print("\npure end moment (the free end's tangent clamped at theta): against the arc, stretched as the model stretches it")
    for case in results["end_moment"]:
        print(f"  theta = {case['theta_deg']:g} deg ({case['stages']} stages from straight)")
        print("    elements  tip / L      max |kappa / kappa_arc - 1| (vertices)  Newton")
        for r in case["rows"]:
            flag = "" if r["converged"] else "  (not converged)"
            print(f"    {r['elements']:8d}  {r['tip_error']:.3e}    {r['curvature_error']:.3e}"
                  f"                          {r['iterations']}{flag}")
        o = case["orders"]
        print(f"    observed order: tip {_orders(o, 'tip_error')}, curvature {_orders(o, 'curvature_error')}")

    for name, title in (("pinned", "pinned beam"), ("taut", "taut pinned beam (T = 1e4 N)")):
        f = results["frequencies"][name]
        print(f"\n{title}: natural frequencies, relative errors (two planes each, the larger)")
        print("  reference [rad/s]: " + ", ".join(f"{w:.8g}" for w in f["reference"]))
        print("  elements  " + "  ".join(f"mode {k + 1:<7d}" for k in range(len(f["reference"]))))
        for r in f["rows"]:
            print(f"  {r['elements']:8d}  " + "  ".join(f"{e:.3e}   " for e in r["errors"]))
        print("  observed order: " + ", ".join(f"mode {k[5:]} {v['fitted']:.2f}" for k, v in f["orders"].items()
                                               if v["fitted"] is not None))

    v = results["vibration"]
    print(f"\ncantilever's free vibration ({v['elements']} elements, {v['steps_per_period']} steps a period, compiled):")
    print(f"  omega_1 (eigenproblem) {v['omega']:.8g} rad/s, closed form {v['reference']:.8g}: "
          f"{v['omega_error']:+.2e}")
    for name, run in v["runs"].items():
        print(f"  {name:18s} period error {run['period_error']:+.3e} (against the FE omega {run['period_error_fem']:+.3e}), "
              f"amplitude after the run / before {run['amplitude_ratio']:.5f}, {run['seconds']:.2f} s")
    h = 2.0 * math.pi / v["steps_per_period"]
    print(f"  (the trapezoidal rule, generalised-alpha at rho_inf = 1, lengthens the period by (omega dt)^2 / 12 = "
          f"{h * h / 12:.3e})")

    cl = results["catenary_limit"]
    print(f"\ncatenary limit: the hanging cable (fairlead tension {cl['fairlead_tension']:.6g} N) as EI -> 0")
    print("  EI [N m^2]   sqrt(EI/T) [m]  max |r - r_cat| [m]  at vertices [m]  T_F error   Newton")
    for r in cl["rows"]:
        print(f"  {r['EI']:10.3g}   {r['boundary_layer']:.3e}       {r['curve_error']:.3e}            "
              f"{r['node_error']:.3e}        {r['fairlead_tension_error']:+.2e}  {r['iterations']}")
