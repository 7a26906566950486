"""(1) of validation/spread_mooring: single lines, fairlead and horizontal tension against the
span from (a) Barreiro's formula, (b) ``elastic_catenary`` and (c) the FEM."""

import math

import numpy as np

from cablefem.statics.catenary import elastic_catenary

from validation.spread_mooring.lines import (DRAFT, EA, HEIGHT, LENGTH, WEIGHTS, _relative, barreiro_limit,
                                             barreiro_line, fem_line, fitted_line)


def single_line_spans(fast):
    """Spans X [m]: from 78 % of the line on the seabed (84 m) to 99.7 % of the taut span (97.7 m)."""
    if fast:
        return [85.0, 92.0, 97.0, 97.6]
    _, x_max = barreiro_limit()
    spans = list(np.arange(84.0, 97.01, 0.5)) + [97.2, x_max, 97.4, 97.5, 97.6, 97.7]
    return sorted(float(x) for x in spans)


def single_lines(fast):
    """(1): tensions of (a), (b) and (c) against the span for both lines; their differences."""
    _, x_max = barreiro_limit()
    out = {"spans_m": single_line_spans(fast), "barreiro_limit_span_m": x_max,
           "taut_span_m": math.sqrt(LENGTH**2 - HEIGHT**2), "lines": {}}
    for name, weight in WEIGHTS.items():
        rows = []
        for span in out["spans_m"]:
            formula = barreiro_line(span, weight)
            rigid = elastic_catenary(span, HEIGHT, LENGTH, np.inf, weight)
            elastic = elastic_catenary(span, HEIGHT, LENGTH, EA, weight)
            fem = fem_line(np.array([-span, 0.0, -DRAFT - HEIGHT]), np.array([0.0, 0.0, -DRAFT]), weight)
            force = fem["force"]
            fitted = fitted_line(np.array([-span, 0.0, -DRAFT - HEIGHT]), np.array([0.0, 0.0, -DRAFT]), weight)
            row = {
                "span_m": span, "regime": rigid.regime, "lying_length_m": rigid.lying_length,
                "barreiro_tension_N": None if formula is None else formula["tension"],
                "barreiro_horizontal_N": None if formula is None else formula["horizontal"],
                "catenary_tension_N": rigid.fairlead_tension,
                "catenary_horizontal_N": rigid.fairlead_horizontal,
                "elastic_catenary_tension_N": elastic.fairlead_tension,
                "elastic_catenary_horizontal_N": elastic.fairlead_horizontal,
                "fem_tension_N": float(np.linalg.norm(force)),
                "fem_horizontal_N": float(np.hypot(force[0], force[1])),
                "fem_vertical_N": float(-force[2]),
                "fem_iterations": fem["iterations"], "fem_residual": fem["residual"],
                "fem_wall_time_s": fem["wall_time_s"],
            }
            row["fem_vs_catenary_tension"] = _relative(row["fem_tension_N"], row["catenary_tension_N"])
            row["fem_vs_catenary_horizontal"] = _relative(row["fem_horizontal_N"], row["catenary_horizontal_N"])
            row["fem_vs_elastic_tension"] = _relative(row["fem_tension_N"], row["elastic_catenary_tension_N"])
            row["fem_vs_elastic_horizontal"] = _relative(row["fem_horizontal_N"],
                                                         row["elastic_catenary_horizontal_N"])
            row["elastic_vs_rigid_tension"] = _relative(row["elastic_catenary_tension_N"],
                                                        row["catenary_tension_N"])
            if "error" in fitted:
                row["fitted_error"] = fitted["error"]
            else:
                fitted_force = fitted["force"]
                row["fitted_tension_N"] = float(np.linalg.norm(fitted_force))
                row["fitted_horizontal_N"] = float(np.hypot(fitted_force[0], fitted_force[1]))
                row["fitted_iterations"] = fitted["iterations"]
                row["fitted_vs_elastic_tension"] = _relative(row["fitted_tension_N"],
                                                             row["elastic_catenary_tension_N"])
                row["fitted_vs_elastic_horizontal"] = _relative(row["fitted_horizontal_N"],
                                                                row["elastic_catenary_horizontal_N"])
            row["fitted_wall_time_s"] = fitted["wall_time_s"]
            if formula is not None:
                row["fem_vs_barreiro_tension"] = _relative(row["fem_tension_N"], formula["tension"])
                row["fem_vs_barreiro_horizontal"] = _relative(row["fem_horizontal_N"], formula["horizontal"])
                row["barreiro_vs_catenary_tension"] = _relative(formula["tension"], rigid.fairlead_tension)
                row["barreiro_vs_catenary_horizontal"] = _relative(formula["horizontal"],
                                                                   rigid.fairlead_horizontal)
            rows.append(row)
        out["lines"][name] = {"weight_N_per_m": weight, "rows": rows, "max": _maxima(rows),
                              "fitted_failed_spans_m": [r["span_m"] for r in rows if "fitted_error" in r]}
    out["formula_check"] = barreiro_check()
    return out


def _maxima(rows):
    """Largest value of each relative-difference column over the rows that have it."""
    keys = [k for k in rows[0] if "_vs_" in k] + ["fem_vs_barreiro_tension", "fem_vs_barreiro_horizontal",
                                                  "fitted_vs_elastic_tension", "fitted_vs_elastic_horizontal",
                                                  "barreiro_vs_catenary_tension",
                                                  "barreiro_vs_catenary_horizontal"]
    return {k: max((r[k] for r in rows if k in r), default=None) for k in dict.fromkeys(keys)}


def barreiro_check(count=200):
    """Largest relative difference between Barreiro's formula and ``elastic_catenary`` (EA = inf)
    in T_H, V and T, over ``count`` spans across the whole touchdown regime, for both lines."""
    _, x_max = barreiro_limit()
    spans = np.linspace(LENGTH - HEIGHT, x_max, count + 1)[1:]
    worst = {"horizontal": 0.0, "vertical": 0.0, "tension": 0.0}
    for weight in WEIGHTS.values():
        for span in spans:
            formula = barreiro_line(float(span), weight)
            rigid = elastic_catenary(float(span), HEIGHT, LENGTH, np.inf, weight)
            for key, ours in (("horizontal", rigid.fairlead_horizontal), ("vertical", rigid.fairlead_vertical),
                              ("tension", rigid.fairlead_tension)):
                worst[key] = max(worst[key], _relative(formula[key], ours))
    return {"spans": int(count), "span_range_m": [float(spans[0]), float(spans[-1])], "max_relative": worst}
