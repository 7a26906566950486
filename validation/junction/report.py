"""The tables of validation/junction's results, as markdown."""

import numpy as np

from validation.junction.dynamics import QUANTITIES


def _pct(x):
    return "–" if x is None else f"{100 * x:+.2f}"


def report(results):
    """The tables as markdown text."""
    s = results["statics"]
    out = ["## Statics (fairlead at rest): cablefem's network statics against MoorPy's System", "",
           "| tension | MoorPy [N] | cablefem [N] | cablefem − MoorPy [%] |", "|---|---|---|---|"]
    for row in s["rows"]:
        out.append(f"| {row['quantity']} | {row['moorpy_N']:.1f} | {row['cablefem_N']:.1f} | "
                   f"{100 * row['cablefem_rel']:+.6f} |")
    out += ["", f"Junction: MoorPy {np.round(np.asarray(s['junction_moorpy_m']), 4).tolist()} m; cablefem "
            f"{s['junction_cablefem_error_m']:.2e} m from it.", "",
            "MoorDyn's initial condition (each run's first sample) against MoorPy:", "",
            "| run | fairlead [%] | anchor 1 [%] | anchor 2 [%] | junction [m] |", "|---|---|---|---|---|"]
    mp = {row["quantity"]: row["moorpy_N"] for row in s["rows"]}
    seen = set()
    for case in results["cases"].values():
        for ic in case["initial_conditions"]:
            label = ic["label"].split(", dtM")[0]
            if label in seen:
                continue
            seen.add(label)
            cells = [_pct((ic[f"{q}_N"] - mp[q]) / mp[q]) for q in QUANTITIES]
            off = np.linalg.norm(np.asarray(ic["junction_m"]) - np.asarray(s["junction_moorpy_m"]))
            out.append(f"| {label} | " + " | ".join(cells) + f" | {off:.2e} |")
    header = ("| run | fairlead RMS / mean / peak [%] | anchor 1 RMS / mean / peak [%] | anchor 2 RMS / mean / peak [%] "
              "| junction RMS [m] (of its excursion [%]) | stepping [s per simulated s] |")
    rule = "|---|---|---|---|---|---|"
    for name, case in results["cases"].items():
        m = case["motion"]
        out += ["", f"## Case {name}: surge {m['amplitude'][0]:g} m, heave {m['amplitude'][2]:g} m, period "
                f"{m['period']:g} s; {case['duration_s']:g} s simulated, statistics from {case['statistics_from_s']:g} s", ""]
        out += ["cablefem − MoorDyn, finest runs (relative to MoorDyn's mean):", "", header, rule]
        out.append(_ladder_row(f"{case['references']['cablefem']} against {case['references']['moordyn']}",
                               case["comparison"], case["ladders"]["cablefem"][-1]["s_per_simulated_s"]))
        for code in ("moordyn", "cablefem"):
            out += ["", f"{code}: each run against its own finest run, and against the other code's finest run "
                    "(second row):", "", header, rule]
            for entry in case["ladders"][code]:
                out.append(_ladder_row(entry["label"], entry["against_own_reference"], entry["s_per_simulated_s"]))
                out.append(_ladder_row("  against the other", entry["against_other_reference"],
                                       entry["s_per_simulated_s"]))
        out += ["", "Cost at comparable accuracy: each code's cheapest run whose every tension is within the "
                "threshold (RMS of the mean) of ONE common reference, cablefem's finest run (the codes' finest "
                "runs agree to the first table's row):", "",
                "| threshold | MoorDyn run | its largest RMS [%] | s per simulated s | cablefem run | "
                "its largest RMS [%] | s per simulated s |", "|---|---|---|---|---|---|---|"]
        for threshold, picks in comparable_costs(case).items():
            cells = []
            for code in ("moordyn", "cablefem"):
                entry, error = picks[code]
                cells += (["none", "–", "–"] if entry is None else
                          [entry["label"], f"{100 * error:.2f}", f"{entry['s_per_simulated_s']:.3f}"])
            out.append(f"| {100 * threshold:g} % | " + " | ".join(cells) + " |")
        if "switches" in case:
            out += ["", f"Switches ({case['switches']['base']['label']}):", "", header.replace(
                " | stepping [s per simulated s] |", " |"), rule[:-4]]
            for switch, entry in case["switches"].items():
                out.append(_ladder_row(switch, entry["comparison"], None))
    return "\n".join(out)


def comparable_costs(case, thresholds=(0.02, 0.01, 0.005)):
    """{threshold: {code: (ladder entry, its largest tension RMS)}}: each code's cheapest run (by
    stepping time) within ``threshold`` of cablefem's finest run in every tension (None if none)."""
    def error(code, entry):
        c = entry["against_other_reference" if code == "moordyn" else "against_own_reference"]
        return max(c[q]["rms"] for q in QUANTITIES)

    out = {}
    for threshold in thresholds:
        out[threshold] = {}
        for code in ("moordyn", "cablefem"):
            fits = [(entry["s_per_simulated_s"], i) for i, entry in enumerate(case["ladders"][code])
                    if error(code, entry) <= threshold]
            entry = case["ladders"][code][min(fits)[1]] if fits else None
            out[threshold][code] = (entry, None if entry is None else error(code, entry))
    return out


def _ladder_row(label, c, seconds):
    cells = [f"{100 * c[q]['rms']:.2f} / {_pct(c[q]['mean'])} / {_pct(c[q]['peak'])}" for q in QUANTITIES]
    j = c["junction"]
    tail = "" if seconds is None else f" {seconds:.3f} |"
    return f"| {label} | " + " | ".join(cells) + f" | {j['rms_m']:.4f} ({100 * j['rms']:.2f}) |" + tail
