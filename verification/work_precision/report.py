"""The tables of verification/work_precision's results, as text."""

from verification.work_precision.runners import MoordynSettings
from verification.work_precision.runs import CablefemSettings


def report(results):
    """The tables as text: references, ratio table per motion, Pareto fronts, time order."""
    out = []
    for motion, e in results["motions"].items():
        out.append(f"{motion}: {e['duration_s']:g} s, error window {e['window_s'][0]:g}-{e['window_s'][1]:g} s")
        if "references" in e:
            out.extend(_sweep_report(e))
        t = e["time_order"]
        out.append(f"  time error alone ({t['mesh']}, BDF2, against dt {t['reference_dt']:g}): "
                   + ", ".join(f"dt {dt:g}: {err:.2e}" for dt, err in zip(t["dt"], t["errors"]))
                   + f"; order {t['order']:.2f}")
        out.append("")
    if "profile" in results:
        p = results["profile"]
        out.append(f"profile: {p['run']}, {p['motion']}, {p['duration_s']:g} s: {p['profiled_s']:.2f} s, "
                   f"{p['steps']} steps, {p['newton_iterations']} Newton iterations, {p['nfev']} evaluations, "
                   f"{p['nlu']} LU")
        for row in p["top"]:
            out.append(f"  {row['own_fraction']:6.1%} {row['own_s']:7.3f} s {row['calls']:7d} calls  {row['function']}")
    return "\n".join(out)


def _sweep_report(e):
    """Lines of the references and the ratio table of one motion."""
    out = []
    ref = e["references"]
    out.append(f"  cablefem reference {CablefemSettings(**ref['cablefem']['settings']).label()} "
               f"({ref['cablefem']['wall_time_s']:.1f} s); "
               + "; ".join(f"{c['label']}: {c['change']:.2e}" for c in ref["checks"]))
    out.append(f"  MoorDyn reference {MoordynSettings(**ref['moordyn']['settings']).label()} "
               f"({ref['moordyn']['wall_time_s']:.1f} s); model floor (finest MoorDyn vs finest cablefem) "
               f"{ref['moordyn_vs_cablefem']:.2e}; {ref['moordyn_next']['label']}: {ref['moordyn_next']['change']:.2e}"
               + (f"; IC solve skipped vs done: {ref['moordyn_ic_check']['change']:.1e}" if "moordyn_ic_check" in ref else ""))
    out.append(f"  {'MoorDyn error':>13} {'MoorDyn':<28} {'[s]':>7} {'cablefem':<46} {'error':>8} {'[s]':>7} {'ratio':>6}")
    for row in e["ratios"]:
        cf = (f"{row['cablefem']:<46} {row['cablefem_error']:8.2e} {row['cablefem_s']:7.2f} {row['ratio']:6.2f}"
              if row["cablefem"] else f"{'(none as accurate)':<46}")
        out.append(f"  {row['error']:13.2e} {row['moordyn']:<28} {row['moordyn_s']:7.2f} {cf}")
    return out
