"""validation/cables' tables, printed from its results (``run.run``)."""


def print_tables(results):
    """The lazy wave's meshes in both codes against MoorDyn-C's finest, and the beam."""
    lazy = results["lazy_wave"]
    ref = lazy["moordyn"][-1]
    print(f"lazy wave: MoorDyn-C's finest run ({ref['segments']} segments) is the reference: static hang-off "
          f"tension {ref['static_tension']:.1f} N, curvature peak {ref['static_peak']:.5f} 1/m at s = "
          f"{ref['static_peak_s']:.1f} m; over the run, tension up to {ref['run_tension']:.1f} N, peak up to "
          f"{ref['run_peak']:.5f} 1/m")
    print("  differences from the reference (relative); wall times [s]")
    print("  code      mesh        static T    static peak  run max T    run max peak  statics  run    note")
    for code, unit in (("moordyn", "segments"), ("cablefem", "elements")):
        for e in lazy[code]:
            d = e["differences"]
            note = f"dtM {e['dtM']:g}" if code == "moordyn" else f"least strain {e['least_strain']:.1e}"
            print(f"  {code:9s} {e[unit]:4d} {unit[:4]}   {d['static_tension']:+.2e}   {d['static_peak']:+.2e}    "
                  f"{d['run_tension']:+.2e}    {d['run_peak']:+.2e}     {e['static_wall_time_s']:6.1f}  "
                  f"{e['run_wall_time_s']:6.1f}  {note}")
    print("  cheapest mesh within 1 % (and every finer one):")
    for code, found in lazy["within_tolerance"].items():
        for quantity, entry in found.items():
            if entry is None:
                print(f"    {code:9s} {quantity:15s} none")
                continue
            mesh = entry.get("segments", entry.get("elements"))
            print(f"    {code:9s} {quantity:15s} {mesh:4d} ({entry['length']:g} m): statics {entry['static_wall_time_s']:.1f} s, "
                  f"run {entry['run_wall_time_s']:.1f} s")

    b = results["beam"]
    print(f"\nMoorDyn's BeamSimplySupported.txt: Euler-Bernoulli midspan 5wL^4/384EI = {b['euler_bernoulli_midspan']:.6g} m; "
          f"stretched by its sag (N = {b['stretched_axial_force']:.1f} N) {b['stretched_midspan']:.6g} m")
    for name in ("cablefem", "cablefem_fine", "moordyn"):
        r = b[name]
        mesh = r.get("elements", r.get("segments"))
        print(f"  {name:14s} {mesh:4d}: largest deflection {r['largest']:.6g} m = {r['ratio_to_euler_bernoulli']:.4f} x "
              f"Euler-Bernoulli; from the stretched beam {r['error_to_stretched']:.2e} of its midspan, "
              f"{r['wall_time_s']:.2f} s")
    c = results["cantilever"]
    print(f"\nMoorDyn's BeamCantilevered.txt: tip w L^4 / (8 EI) = {c['euler_bernoulli_tip']:.6g} m, clamp moment "
          f"w L^2 / 2 = {c['clamp_moment_exact']:.6g} N m")
    for name in ("cablefem", "moordyn"):
        r = c[name]
        mesh = r.get("elements", r.get("segments"))
        extra = f", clamp moment {r['clamp_moment_error']:+.2e}" if "clamp_moment_error" in r else ""
        print(f"  {name:14s} {mesh:4d}: tip drop {r['tip_drop']:.6g} m ({r['tip_error']:+.2e}){extra}, {r['wall_time_s']:.2f} s")
