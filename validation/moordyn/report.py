"""The tables of validation/moordyn's results, as text."""

from validation.moordyn.inputs import MN


def _pct(x):
    return f"{100 * x:+7.2f}%"


def report(results):
    """The tables as text: case differences and wall times, convergence, switches, statics."""
    out = ["Fairlead tension, cablefem - MoorDyn over the last periods, relative to MoorDyn's mean there",
           f"{'case':<19} {'line':<8} {'MoorDyn mean':>12} {'mean':>8} {'peak':>8} {'trough':>8} {'RMS':>8} "
           f"{'max':>8} {'RMS*':>8} {'MoorDyn [s]':>11} {'cablefem [s]':>12}"]
    for case, e in results["cases"].items():
        for k, (d, p) in enumerate(zip(e["differences"], e["differences_point_force"])):
            times = (f"{e['moordyn_wall_time_s']:11.1f} {e['cablefem_wall_time_s']:12.1f}" if k == 0 else "")
            out.append(f"{case if k == 0 else '':<19} {e['lines'][k]:<8} {d['reference_mean_N'] / MN:9.4f} MN "
                       f"{_pct(d['mean'])} {_pct(d['peak'])} {_pct(d['trough'])} {_pct(d['rms'])} {_pct(d['max'])} "
                       f"{_pct(p['rms'])} {times}")
    out.append("RMS*: against MoorDyn's force minus its end-node inertia (the force on the point, as cablefem's)")
    if any("periodicity" in e for e in results["cases"].values()):
        out.append("")
        out.append("Periodicity: change from the second-to-last period to the last (mean, max, min; % of MoorDyn mean)")
    for case, e in results["cases"].items():
        if "periodicity" not in e:
            continue
        for k, line in enumerate(e["lines"]):
            cells = [" ".join(_pct(e["periodicity"][code][k][key]) for key in ("mean", "max", "min"))
                     for code in ("moordyn", "cablefem")]
            out.append(f"{case if k == 0 else '':<19} {line:<8} MoorDyn {cells[0]} | cablefem {cells[1]}")
    if any("convergence" in e for e in results["cases"].values()):
        out.append("")
        out.append("Convergence: change of each code's statistics from the reference to the check resolution "
                   "(coarse: 1/2 segments, 2 dt), and the two codes compared there")
    for case, e in results["cases"].items():
        c = e.get("convergence")
        if not c:
            continue
        if "error" in c:
            out.append(f"{case:<19} convergence check failed: {c['error']}")
            continue
        for k, line in enumerate(e["lines"]):
            cells = []
            for part in (c["moordyn"]["change"][k], c["cablefem"]["change"][k], c["differences"][k]):
                cells.append(f"{_pct(part['mean'])} {_pct(part['peak'])} {_pct(part['rms'])}")
            out.append(f"{case if k == 0 else '':<19} {c['check'] if k == 0 else '':<6} {line:<8} "
                       f"MoorDyn {cells[0]} | cablefem {cells[1]} | cablefem - MoorDyn {cells[2]}")
        out.append(f"{'':<19} (mean peak RMS each; wall time MoorDyn {c['moordyn']['wall_time_s']:.1f} s, "
                   f"cablefem {c['cablefem']['wall_time_s']:.1f} s)")
    out.append("")
    out.append("Physics switches: cablefem - MoorDyn, as in the file -> with the switch")
    for case, e in results["cases"].items():
        for name, sw in e["switches"].items():
            if "error" in sw:
                out.append(f"{case:<19} {name:<36} failed: {sw['error']}")
                continue
            for k, d in enumerate(sw["differences"]):
                ref = e["differences"][k]
                out.append(f"{case:<19} {name:<36} {e['lines'][k]:<8} mean {_pct(ref['mean'])} -> {_pct(d['mean'])}, "
                           f"peak {_pct(ref['peak'])} -> {_pct(d['peak'])}, RMS {_pct(ref['rms'])} -> {_pct(d['rms'])}")
    failures = [(case, name, run["cablefem_failures"]) for case, e in results["cases"].items()
                for name, run in [("reference", e)] + list(e["switches"].items()) if run.get("cablefem_failures")]
    for case, name, messages in failures:
        out.append(f"cablefem reran {case} {name} with a smaller dt: {'; '.join(messages)}")
    for case, e in results["cases"].items():
        for name, run in [("reference", e)] + list(e["switches"].items()):
            if run.get("cablefem_start", "catenary guess") != "catenary guess":
                out.append(f"cablefem statics of {case} {name}: {run['cablefem_start']}")
    s = results["statics"]
    out.append("")
    out.append(f"Static pretension, flat flume line: MoorDyn ({s['moordyn_segments']} segments) {s['moordyn_N']:.1f} N "
               f"(held 5 s: {s['moordyn_hold_5s_change']:.1e}), MoorPy catenary {s['moorpy_N']:.1f} N "
               f"({_pct(s['moordyn_vs_moorpy'])}), cablefem ({s['cablefem_elements']} elements) {s['cablefem_N']:.1f} N "
               f"(MoorDyn/cablefem {_pct(s['moordyn_vs_cablefem'])})")
    if "fairlead_1m_below" in s:
        b = s["fairlead_1m_below"]
        out.append(f"  seabed elasticity (cablefem 640 el, kBot 3e5 vs 3e9): {_pct(s['seabed_elasticity'])}; "
                   f"MoorPy vs cablefem stiff seabed {_pct(s['moorpy_vs_cablefem_stiff_seabed'])}; "
                   f"fairlead 1 m below the surface: MoorDyn/cablefem {_pct(b['moordyn_vs_cablefem'])}")
    if "wall_time_s" in results:
        out.append(f"study wall time {results['wall_time_s']:.0f} s")
    return "\n".join(out)
