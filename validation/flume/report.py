"""The tables of validation/flume's results (the cases, the convergence and sensitivity studies), as
text."""

from cablefem.model.builtin import FLUME_MOTIONS, FLUME_SEABEDS

from validation.flume.cases import MN, MOTIONS, PAPER_LOWEST_PEAK


def report_sensitivity(rows):
    """The sensitivity table, as text [MN]."""
    lines = ["sensitivity (80 P1 elements): fairlead tension over the last two periods [MN]; "
             "static: equilibrium at the smallest and largest surge",
             f"{'seabed':7s} {'motion':12s} {'variant':22s} {'min':>7s} {'max':>7s} {'mean':>7s} "
             f"{'static@min':>10s} {'static@max':>10s}"]
    for r in rows:
        if not r.get("completed"):
            lines.append(f"{r['seabed']:7s} {r['motion']:12s} {r['variant']:22s} FAILED: {r['error'] or r['status']}")
            continue
        lines.append(f"{r['seabed']:7s} {r['motion']:12s} {r['variant']:22s} {r['min_N'] / MN:7.4f} "
                     f"{r['max_N'] / MN:7.4f} {r['mean_N'] / MN:7.4f} {r['static_at_min_surge_N'] / MN:10.4f} "
                     f"{r['static_at_max_surge_N'] / MN:10.4f}")
    return "\n".join(lines)


def report(results):
    """The table of the six cases and the findings, as text."""
    lines = [f"desire2023 flume cases, {'fast' if results['fast'] else 'full'} settings "
             f"({_settings_words(results['settings'])}); statistics over the last two periods",
             f"{'seabed':7s} {'motion':12s} {'mean':>6s} {'max':>6s} {'min':>6s} {'range':>6s} "
             f"{'paper':>6s} {'touchdown x [m]':>17s} {'anchor max':>10s} {'wall':>6s} {'rej':>4s}",
             f"{'':7s} {'':12s} {'[MN]':>6s} {'[MN]':>6s} {'[MN]':>6s} {'[MN]':>6s} {'[MN]':>6s} "
             f"{'from .. to':>17s} {'[MN]':>10s} {'[s]':>6s} {'':>4s}"]
    for c in results["cases"]:
        if not c.get("completed"):
            lines.append(f"{c['seabed']:7s} {c['motion']:12s} FAILED: {c['error'] or c['status']}")
            continue
        paper = f"{PAPER_LOWEST_PEAK[c['seabed']] / MN:6.2f}" if c["motion"] == "quasi-static" else f"{'-':>6s}"
        td = (f"{c['touchdown_x_min_m']:7.1f} .. {c['touchdown_x_max_m']:6.1f}"
              if "touchdown_x_min_m" in c else f"{'-':>17s}")
        lines.append(f"{c['seabed']:7s} {c['motion']:12s} {c['mean_N'] / MN:6.3f} {c['max_N'] / MN:6.3f} "
                     f"{c['min_N'] / MN:6.3f} {c['range_N'] / MN:6.3f} {paper} {td:>17s} "
                     f"{c['anchor_max_N'] / MN:10.3f} {c['wall_time_s']:6.1f} {c['rejected_steps']:4d}")
    f = results["findings"]
    if "error" in f:
        lines.append(f["error"])
        return "\n".join(lines)
    mn = lambda values: ", ".join(f"{v / MN:.3f}" for v in values)  # noqa: E731
    q, d, s = f["quasi_static_lowest_peak_ordering"], f["dynamic_ordering"], f["dynamic_spread_larger"]
    r = s["relative_spreads"]
    word = lambda ok: "PASS" if ok else "FAIL"  # noqa: E731
    lines += [
        "findings (flat, gentle, steep):",
        f"  1. quasi-static lowest peak flat > gentle > steep: {word(q['passed'])}  "
        f"{mn(q['lowest_peak_N'])} MN (paper {mn(q['paper_N'])}; "
        + ", ".join(f"{100 * x:+.0f} %" for x in q["relative_difference_to_paper"]) + ")",
        f"  2. dynamic peak flat > gentle > steep:             {word(d['passed'])}  {mn(d['max_N'])} MN "
        f"(range {mn(d['range_N'])}: {'ordered' if d['range_ordered'] else 'NOT ordered'}; "
        f"mean {mn(d['mean_N'])}: {'ordered' if d['mean_ordered'] else 'NOT ordered'})",
        f"  3. seabed matters more in the dynamic cases:       {word(s['passed'])}  relative spread "
        f"(max - min)/mean across seabeds: dynamic peak {100 * r['dynamic_max']:.1f} % "
        f"{'>' if s['passed'] else 'not >'} quasi-static peak {100 * r['quasi_static_max']:.1f} % and "
        f"lowest peak {100 * r['quasi_static_lowest_peak']:.1f} % "
        f"(dynamic range {100 * r['dynamic_range']:.1f} %, means: dynamic {100 * r['dynamic_mean']:.1f} %, "
        f"quasi-static {100 * r['quasi_static_mean']:.1f} %; paper's quasi-static lowest peaks "
        f"{100 * q['paper_spread']:.1f} %)",
        f"wall time {results['wall_time_s']:.1f} s; {_provenance_words(results['provenance'])}",
    ]
    return "\n".join(lines)


def report_convergence(rows):
    """The convergence table, as text: per case and setting, max/min/mean [MN] and the change
    relative to the finest setting."""
    last = rows[-1]
    lines = ["convergence: fairlead tension over the last two of ramp + "
             f"{last['periods']} periods; change relative to {last['elements']} el, dt {last['dt']:g} s",
             f"{'seabed':7s} {'motion':12s} {'el':>4s} {'dt':>6s} {'max':>7s} {'dmax':>7s} {'min':>7s} "
             f"{'dmin':>7s} {'mean':>7s} {'dmean':>7s} {'wall':>6s} {'rej':>4s}"]
    for seabed in FLUME_SEABEDS:
        for motion in MOTIONS:
            group = [r for r in rows if r["seabed"] == seabed and r["motion"] == motion]
            ref = group[-1]
            for r in group:
                if not r.get("completed") or not ref.get("completed"):
                    lines.append(f"{seabed:7s} {motion:12s} {r['elements']:4d} {r['dt']:6g} "
                                 f"FAILED: {r['error'] or r['status']}")
                    continue
                rel = {k: 100 * (r[k] / ref[k] - 1) for k in ("max_N", "min_N", "mean_N")}
                lines.append(f"{seabed:7s} {motion:12s} {r['elements']:4d} {r['dt']:6g} "
                             f"{r['max_N'] / MN:7.4f} {rel['max_N']:+6.1f}% {r['min_N'] / MN:7.4f} "
                             f"{rel['min_N']:+6.1f}% {r['mean_N'] / MN:7.4f} {rel['mean_N']:+6.1f}% "
                             f"{r['wall_time_s']:6.1f} {r['rejected_steps']:4d}")
    return "\n".join(lines)


def _provenance_words(stamp):
    start = stamp["start"]
    where = start["git_head"] or f"at {start['cablefem_path']}, source digest {start['cablefem_sha256']}"
    words = f"cablefem {where}{' + uncommitted changes' if start['cablefem_dirty'] else ''}"
    return words + (" (CHANGED during the run)" if stamp["cablefem_changed_during_run"] else "")


def _settings_words(settings):
    return "; ".join(f"{motion} {v['elements']} P1 elements, dt {v['dt']:g} s, ramp + {v['periods']} periods"
                     for motion, v in settings.items())


def _motion_words(motion):
    m = FLUME_MOTIONS[motion]
    return f"T = {m.period:g} s, {m.amplitude[0]:g} m amplitude, {m.offset[0]:g} m drift"
