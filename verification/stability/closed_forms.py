"""The cases of verification/stability held against closed forms: 1. the stiff Batista-Perkovic line
swept along its fairlead; 4. a line lying on the seabed and a line pulled nearly taut."""

import math

import numpy as np

from cablefem.statics.catenary import elastic_catenary, inclined_catenary
from cablefem.model.line import Line, LineType, Segment
from cablefem.model.motion import fairlead_motion
from cablefem.fem.system import build_system
from cablefem.model.scene import Contact, Friction, Motion, Scene, Solver
from cablefem.model.builtin import FLUME_DEPTH, table5_chain
from cablefem.statics.solve import solve_static

from verification.stability.driver import (LENGTH, flume_like, raised_cosine, sample, series, simulate, summary,
                                           table_motion)

# -- 1. Batista-Perkovic stiffness

#: s, one sweep 3.5 -> 4.5 -> 3.5 MN: slow enough that drag and inertia move the tension by ~1e-3
#: (5e-3 at 120 s, 1.5e-3 at 240 s, 7e-4 at 480 s against P1 x 31's static error of 5e-4)
STIFF_PERIOD = 240.0


def stiff_case(dt, integrator="bdf2", stiffness=3e14, period=STIFF_PERIOD):
    """The Batista-Perkovic line (EA 5.055e11 N, G_K [N/m^3], P1 x 31, 15 deg seabed) with its
    fairlead swept from the H = 3.5 MN span to the H = 4.5 MN span and back over ``period`` [s]
    (a raised cosine: at rest at both ends). Returns (scene, span(t) [m])."""
    from verification.batista_perkovic import case as bp

    near, far = bp.Case(3.5e6), bp.Case(4.5e6)
    stroke = far.span - near.span
    chain = table5_chain()
    stiff = LineType("bp-chain", diameter=bp.DIAMETER, mass=bp.MASS, EA=bp.EA, damping=chain.damping,
                     Cd_normal=chain.Cd_normal, Cd_tangential=chain.Cd_tangential,
                     Ca_normal=chain.Ca_normal, Ca_tangential=chain.Ca_tangential)
    anchor = near.line(1, 31, stiffness=stiffness).anchor
    line = Line("stiff", anchor, near.fairlead, (Segment(stiff, bp.LENGTH, 31),), 1)
    motion = table_motion(lambda t: np.array([stroke * raised_cosine(t, period), 0.0, 0.0]), period)
    scene = Scene(name="stiff", lines=[line], seabed=near.seabed, contact=Contact(stiffness=stiffness),
                  environment=bp.environment(), friction=Friction(model="none"), motion=motion,
                  solver=Solver(integrator=integrator, dt=dt, duration=period))
    return scene, (lambda t: near.span + stroke * raised_cosine(t, period))


def explicit_limits(stiffness=3e14, elements=31):
    """The step limits an explicit code would face on the stiff case [s]: the axial wave
    h / sqrt(EA/m) and the seabed spring 2 / sqrt(G_K d / m)."""
    from verification.batista_perkovic import case as bp

    h = bp.LENGTH / elements
    return {"axial_cfl_s": h / math.sqrt(bp.EA / bp.MASS),
            "seabed_spring_s": 2.0 / math.sqrt(stiffness * bp.DIAMETER / bp.MASS),
            "element_m": h}


def run_stiff(fast):
    """Case 1: the stiff line at dt 0.01-0.1 s against the closed form along the motion."""
    from verification.batista_perkovic import case as bp

    period = STIFF_PERIOD
    settings = [(0.1, "bdf2"), (0.05, "bdf2")] if fast else \
        [(0.1, "bdf2"), (0.05, "bdf2"), (0.02, "bdf2"), (0.01, "bdf2"), (0.1, "generalized-alpha"),
         (0.05, "generalized-alpha")]
    duration = period / 2 if fast else period  # fast: the loading half only
    checks = np.arange(0.0, duration + 1e-9, 2.0)
    _, span = stiff_case(0.1, period=period)
    closed = np.array([inclined_catenary(span(t), bp.HEIGHT, bp.LENGTH, bp.weight(), bp.SLOPE, bp.EA).fairlead_tension
                       for t in checks])
    # the static FEM at five fairlead positions: the discretisation floor of P1 x 31
    statics = []
    scene, _ = stiff_case(0.1, period=period)
    line = scene.lines[0]
    for fraction in (0.0, 0.25, 0.5, 0.75, 1.0):
        t = period / 2 * math.acos(1.0 - 2.0 * fraction) / math.pi
        moved = Line(line.name, line.anchor, line.fairlead + [span(t) - span(0.0), 0.0, 0.0], line.segments, 1)
        system = build_system(scene, moved, dynamic=False)
        X = solve_static(system, tolerance=scene.solver.tolerance).X
        tension = float(np.linalg.norm(system.residual(X)[system.fem.fairlead_dof]))
        reference = inclined_catenary(span(t), bp.HEIGHT, bp.LENGTH, bp.weight(), bp.SLOPE, bp.EA).fairlead_tension
        statics.append({"span_m": span(t), "fem": tension, "closed_form": reference, "error": tension / reference - 1})
    rows, runs = [], {}
    for dt, integrator in settings:
        scene, _ = stiff_case(dt, integrator, period=period)
        run = simulate(scene, dt, duration, integrator)
        fem = sample(run, checks)
        error = fem / closed - 1.0
        loading = checks <= period / 2
        row = summary(run)
        row.update({"max_error_loading": float(np.nanmax(np.abs(error[loading]))),
                    "max_error_unloading": float(np.nanmax(np.abs(error[~loading]))) if np.any(
                        ~loading & np.isfinite(error)) else None,
                    "max_error_last_10s_before_stop": float(np.nanmax(np.abs(error[(checks > run["t"][-1] - 10) & (
                        checks <= run["t"][-1])]))) if not run["completed"] else None})
        rows.append(row)
        runs[(dt, integrator)] = run
    finest = min((r for r in runs.values() if r["integrator"] == "bdf2"), key=lambda r: r["dt"])
    reference = sample(finest, checks)
    for row, run in zip(rows, runs.values()):
        difference = sample(run, checks) / reference - 1.0
        keep = checks <= period / 2
        row["max_difference_to_finest_loading"] = float(np.nanmax(np.abs(difference[keep])))
    return {"period_s": period, "duration_s": duration, "explicit_limits": explicit_limits(),
            "statics": statics, "rows": rows,
            "series": {f"{integ} dt={dt:g}": series(run) for (dt, integ), run in runs.items()},
            "closed_form": {"t": checks.tolist(), "fairlead_tension": closed.tolist()}}


# -- 4. lying and taut lines

LYING_PRETENSION = 1.0e5  # N: the lying line starts straight, just taut
LYING_STROKE = 0.05  # m: out along the line (tension x 3.5) and in (0.03 m of slack on the floor)
LYING_PERIOD = 60.0  # s


def lying_scene(dt, friction, period=LYING_PERIOD):
    """The whole line on the flat floor, fairlead on it too, both at the resting penetration,
    pulled straight to a pretension of 100 kN; the fairlead slides 0.05 m out along the line
    and 0.05 m in (harmonic, ramped in over a quarter period), so the lying line is stretched
    to 3.5 times its pretension and then lies 0.03 m slack. Returns (scene, span(t) [m])."""
    chain = table5_chain()
    weight = chain.submerged_weight(1025.0, 9.81)
    sink = weight / (3.0e5 * chain.diameter)  # resting penetration [m]
    span = LENGTH * (1.0 + LYING_PRETENSION / chain.EA)
    z = -FLUME_DEPTH - sink
    motion = Motion(kind="harmonic", amplitude=(LYING_STROKE, 0.0, 0.0), period=period, ramp=period / 4)
    scene = flume_like("lying", (-span, 0.0, z), (0.0, 0.0, z), motion, friction=friction, dt=dt, duration=period)
    return scene, (lambda t: span + fairlead_motion(motion, t)[0][0])


def taut_span(ratio, height=FLUME_DEPTH):
    """Horizontal span [m] at which the chord of the Table 5 line 100 m high is ``ratio`` times
    its stretched length (elastic catenary, frictionless)."""
    from scipy.optimize import brentq

    chain = table5_chain()
    weight = chain.submerged_weight(1025.0, 9.81)
    s = np.linspace(0.0, LENGTH, 4001)

    def excess(span):
        solution = elastic_catenary(span, height, LENGTH, chain.EA, weight)
        stretched = LENGTH + float(np.trapezoid(solution.tension(s) / chain.EA, s))
        return math.hypot(span, height) / stretched - ratio

    return brentq(excess, 560.0, 640.0, xtol=1e-9)


TAUT_RATIOS = (0.99, 0.996)  # chord / stretched length at the start and at the peak of the pull

TAUT_PERIOD = 240.0  # s: drag moves the tension by 2e-3 at this speed (2e-2 at 60 s)


def taut_scene(dt, period=TAUT_PERIOD):
    """The Table 5 line pulled from a chord 1 % short of its stretched length to 0.4 % short
    (raised cosine over ``period`` [s]). Returns (scene, span(t))."""
    start, peak = (taut_span(r) for r in TAUT_RATIOS)
    motion = table_motion(lambda t: np.array([(peak - start) * raised_cosine(t, period), 0.0, 0.0]), period)
    scene = flume_like("taut", (-start, 0.0, -FLUME_DEPTH), (0.0, 0.0, 0.0), motion, dt=dt, duration=period)
    return scene, (lambda t: start + (peak - start) * raised_cosine(t, period))


def closed_form_error(run, times, reference, scale):
    """Max |T - T_closed| / scale over ``times`` (NaN-free part) and the errors T / T_closed - 1."""
    fem = sample(run, times)
    with np.errstate(divide="ignore", invalid="ignore"):
        relative = fem / reference - 1.0
    return float(np.nanmax(np.abs(fem - reference)) / scale), relative


def run_lying_taut(fast):
    """Case 4: a line lying fully on the seabed stretched and let slack; a line pulled nearly taut.
    Errors are against the frictionless elastic catenary (lying regime: T = EA (X / L - 1) while
    X > L, else 0; taut: suspended or touching at the anchor), relative to its peak."""
    chain = table5_chain()
    weight = chain.submerged_weight(1025.0, 9.81)
    steps = (0.1,) if fast else (0.1, 0.05, 0.02)
    rows = []
    checks = np.arange(0.0, LYING_PERIOD + 1e-9, 0.25)
    for friction in (False, True):
        for dt in steps:
            scene, span = lying_scene(dt, friction)
            run = simulate(scene, dt, LYING_PERIOD)
            closed = np.array([elastic_catenary(span(t), 0.0, LENGTH, chain.EA, weight).fairlead_tension
                               for t in checks])
            worst, error = closed_form_error(run, checks, closed, closed.max())
            row = summary(run)
            row.update(case="lying", friction=friction, max_error_vs_frictionless_closed_form=worst,
                       error_at_start=float(error[0]), error_at_end=float(error[-1]),
                       closed_form_start=float(closed[0]), closed_form_peak=float(closed.max()),
                       slack_time_s=float(np.sum(closed == 0.0) * (checks[1] - checks[0])))
            rows.append(row)
    duration = TAUT_PERIOD / 2 if fast else TAUT_PERIOD  # fast: up to the peak of the pull
    checks = np.arange(0.0, duration + 1e-9, 1.0)
    for dt in steps:
        scene, span = taut_scene(dt)
        run = simulate(scene, dt, duration)
        closed = np.array([elastic_catenary(span(t), FLUME_DEPTH, LENGTH, chain.EA, weight).fairlead_tension
                           for t in checks])
        worst, error = closed_form_error(run, checks, closed, closed.max())
        row = summary(run)
        row.update(case="taut", friction=True, max_error_vs_frictionless_closed_form=worst,
                   error_at_start=float(error[0]), error_at_peak=float(error[np.argmax(closed)]),
                   closed_form_start=float(closed[0]), closed_form_peak=float(closed.max()))
        rows.append(row)
    return {"lying": {"pretension_N": LYING_PRETENSION, "stroke_m": LYING_STROKE, "period_s": LYING_PERIOD},
            "taut": {"chord_ratios": TAUT_RATIOS, "spans_m": [taut_span(r) for r in TAUT_RATIOS],
                     "period_s": TAUT_PERIOD},
            "rows": rows}
