"""Numerical stability on hard cases: stiff lines, snap loads, a convex seabed edge, lying and
taut lines, a sudden stop and time steps from 1e-4 to 0.1 s (issue 6 item 3).

Each case drives cablefem's own time-domain path (``cablefem.run``: ``start_states``,
``build_system``, ``boundary_path`` and the integrators of ``cablefem.dynamics``; the
time-step sweep goes through ``run_scene`` and reads back the files it writes) and
reports an error against a closed form or a converged run, or an energy balance:

    W_fairlead = dKE + dPE + D_internal + D_seabed + D_drag + W_added_mass + E_numerical,

with W_fairlead the work of the support force on the line (the fairlead's residual row
times its velocity, integrated by the trapezoidal rule over the steps), KE = V.M V / 2,
PE = ``LineSystem.energy`` (strain, weight and seabed spring), each D the integral of a
dissipative load's power (internal damping: the damped minus the elastic flux times
dv/ds; seabed: contact damping and friction, the contact force minus its spring part,
times v; drag without current), W_added_mass the work of the added-mass force, and
E_numerical what is left: the integrator's own dissipation (> 0) or energy creation
(< 0), plus the quadrature error of the trapezoidal rule. Each dissipative power must be
>= 0 at every step and E_numerical must be small against the energy passed through the
fairlead and shrink with dt: checks that fail when a load or an integrator creates energy.

Run ``python -m verification.stability.run [--fast] [--out DIR] [--case NAME ...]``;
``run(fast=True)`` returns what tests/test_stability.py asserts. Every run stops with a
status: "completed", "stopped: <the ConvergenceError's message>" or "non-finite state"
(a NaN cablefem let through, which never happened in the runs recorded in README.md).
"""

import argparse
import csv
import json
import math
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from cablefem.catenary import elastic_catenary, inclined_catenary
from cablefem.errors import ConvergenceError
from cablefem.geometry import Horizontal
from cablefem.line import Line, LineType, Segment
from cablefem.loads import State
from cablefem.loads.added_mass import AddedMass
from cablefem.loads.drag import Drag
from cablefem.motion import fairlead_motion
from cablefem.run import build_system, run_scene
from cablefem.scene import Contact, Environment, Friction, Motion, Output, Scene, Solver
from cablefem.scenes import FLUME_ANCHOR, FLUME_DEPTH, flume_scene, table5_chain
from cablefem.statics import solve_static
from cablefem.study import jsonable, start_line, write_json

HERE = Path(__file__).resolve().parent
LENGTH = 635.0  # m, the desire2023 line (Tables 2 and 5)
CASES = ("stiff", "snap", "edge", "lying", "taut", "stop", "steps", "repro")
#: dissipative loads whose power the ledger integrates
DISSIPATIONS = ("internal", "seabed", "drag")


# ------------------------------------------------------------------ the driver

class EnergyLedger:
    """Work of the fairlead against the change of mechanical energy, the dissipation of each
    dissipative load and the work of added mass, integrated over the steps of ``integ``
    (the module docstring has the balance)."""

    def __init__(self, integ):
        self.integ = integ
        self.system = integ.system
        self.drag = [load for load in self.system.loads if isinstance(load, Drag)]
        self.added = [load for load in self.system.loads if isinstance(load, AddedMass)]
        self.t = integ.t
        self.start = self.mechanical()
        self.power = self.powers()
        self.work = self.throughput = self.added_work = 0.0
        self.dissipated = dict.fromkeys(DISSIPATIONS, 0.0)
        self.least_dissipation_power = 0.0  # W, the most negative of any dissipative power seen
        self.largest_power = 0.0  # W, the largest |fairlead power| seen
        self.peak_kinetic = self.start[0]

    def kinetic(self):
        """Kinetic energy V.M V / 2 [J] of the current state (structural mass)."""
        V = self.integ.V.ravel()
        return 0.5 * float(V @ (self.integ.M @ V))

    def mechanical(self):
        """(kinetic, potential) energy [J] of the current state."""
        return self.kinetic(), self.system.energy(self.integ.X)

    def powers(self):
        """Power [W] of the fairlead on the line, of each dissipative load (>= 0 when it
        dissipates) and of the added mass force, at the current state."""
        integ, system = self.integ, self.system
        fem = system.fem
        X, V, A, t = integ.X, integ.V, integ.A, integ.t
        rows = integ.residual_rows
        if rows is None:  # generalised-alpha balances at t_{n+1-alpha_f}; evaluate at t_{n+1}
            rows = integ.evaluate(X, V, A, t, 0.0, 0.0, jacobian=False)[0] + integ.inertia(A)
        supplied = sum(float(V[d] @ rows[d]) for d in (fem.fairlead_dof, fem.anchor_dof))
        state = system.state(X, V, A, t)
        reduced = state.reduced
        power = dict.fromkeys(DISSIPATIONS, 0.0)
        if system.tension.beta is not None:
            damped = system.tension.evaluate(reduced, False).flux
            elastic = system.tension.evaluate(State(reduced.r, reduced.dr), False).flux
            power["internal"] = float(np.einsum("ceq,ceq,eq->", damped - elastic, reduced.dv, fem.reduced.dx))
        contact = system.contact.evaluate(state, False).force
        spring = system.contact.evaluate(State(state.r, state.dr), False).force
        power["seabed"] = -float(np.einsum("ceq,ceq,eq->", contact - spring, state.v, fem.full.dx))
        for load in self.drag:
            power["drag"] -= float(np.einsum("ceq,ceq,eq->", load.evaluate(state, False).force, state.v, fem.full.dx))
        added = 0.0
        for load in self.added:
            added -= float(np.einsum("ceq,ceq,eq->", load.evaluate(state, False).force, state.v, fem.full.dx))
        return supplied, power, added

    def update(self):
        """Integrate the powers over the step just taken (trapezoidal rule)."""
        supplied, power, added = self.powers()
        h = self.integ.t - self.t
        old_supplied, old_power, old_added = self.power
        self.work += 0.5 * h * (old_supplied + supplied)
        self.throughput += 0.5 * h * (abs(old_supplied) + abs(supplied))
        self.added_work += 0.5 * h * (old_added + added)
        for key in DISSIPATIONS:
            self.dissipated[key] += 0.5 * h * (old_power[key] + power[key])
        self.least_dissipation_power = min(self.least_dissipation_power, *power.values())
        self.largest_power = max(self.largest_power, abs(supplied))
        self.t, self.power = self.integ.t, (supplied, power, added)
        self.peak_kinetic = max(self.peak_kinetic, self.kinetic())

    def balance(self):
        """The terms of the balance so far [J] and its relative residual (JSON-ready)."""
        kinetic, potential = self.mechanical()
        change = kinetic + potential - sum(self.start)
        dissipated = sum(self.dissipated.values())
        numerical = self.work - change - dissipated - self.added_work
        return {"fairlead_work_J": self.work, "throughput_J": self.throughput,
                "mechanical_change_J": change, "kinetic_J": kinetic, "peak_kinetic_J": self.peak_kinetic,
                "dissipated_J": dict(self.dissipated), "added_mass_work_J": self.added_work,
                "numerical_J": numerical,
                "numerical_relative": numerical / self.throughput if self.throughput > 0 else 0.0,
                "least_dissipation_power_W": self.least_dissipation_power,
                "least_dissipation_relative": self.least_dissipation_power / self.largest_power
                if self.largest_power > 0 else 0.0}


def simulate(scene, dt, duration, integrator="bdf2", energy=True, monitor=None, integrator_class=None):
    """Run one line of ``scene`` for ``duration`` [s] in fixed steps of ``dt`` [s] (failed steps
    are halved by the integrator); returns a dict with the status, time series (arrays),
    counters, wall time and, with ``energy``, the energy balance. ``monitor(integ)`` is
    called after every step; ``integrator_class`` replaces cablefem's class for ``integrator``
    (the diagnosis of case 7). A ConvergenceError becomes the status "stopped: <message>"."""
    out = {"dt": dt, "integrator": integrator, "duration": duration}
    start = time.perf_counter()
    try:
        integ = start_line(scene, dt=dt, integrator=integrator_class or integrator)
    except ConvergenceError as error:
        out.update(status=f"static start failed: {error}", completed=False, wall_time_s=0.0,
                   t=np.zeros(0), fairlead_tension=np.zeros(0), anchor_tension=np.zeros(0))
        return out
    ledger = EnergyLedger(integ) if energy else None
    fairlead, anchor = integ.reactions()
    times, tensions, anchors = [integ.t], [np.linalg.norm(fairlead)], [np.linalg.norm(anchor)]
    worst_cascade = most_iterations = 0
    peak_kinetic = 0.0
    status = "completed"
    try:
        for _ in range(int(round(duration / dt))):
            rejected, iterations = integ.rejected, integ.newton_iterations
            integ.step(dt)
            worst_cascade = max(worst_cascade, integ.rejected - rejected)
            most_iterations = max(most_iterations, integ.newton_iterations - iterations)
            fairlead, anchor = integ.reactions()
            if not all(np.all(np.isfinite(a)) for a in (integ.X, integ.V, integ.A, fairlead, anchor)):
                status = f"non-finite state at t = {integ.t:.6g} s"
                break
            V = integ.V.ravel()
            peak_kinetic = max(peak_kinetic, 0.5 * float(V @ (integ.M @ V)))
            times.append(integ.t)
            tensions.append(float(np.linalg.norm(fairlead)))
            anchors.append(float(np.linalg.norm(anchor)))
            if ledger is not None:
                ledger.update()
            if monitor is not None:
                monitor(integ)
    except ConvergenceError as error:
        status = f"stopped: {error}"
    stats = integ.statistics()
    out.update(status=status, completed=status == "completed", wall_time_s=time.perf_counter() - start,
               simulated_s=integ.t, steps=stats["steps"], rejected=stats["rejected"],
               newton_iterations=stats["newton_iterations"], worst_rejections_in_one_step=worst_cascade,
               most_newton_iterations_in_one_step=most_iterations,
               t=np.array(times), fairlead_tension=np.array(tensions), anchor_tension=np.array(anchors),
               peak_tension=float(np.max(tensions)), least_tension=float(np.min(tensions)),
               peak_kinetic_J=peak_kinetic)
    if ledger is not None:
        out["energy"] = ledger.balance()
    out["integ"] = integ
    return out


def table_motion(displacement, duration, samples=2401):
    """A "table" Motion sampling displacement(t) -> (3,) [m] at ``samples`` times over [0, duration]."""
    times = np.linspace(0.0, duration, samples)
    return Motion(kind="table", times=times, positions=np.array([displacement(t) for t in times]))


def raised_cosine(t, period):
    """(1 - cos(2 pi t / period)) / 2: 0 -> 1 -> 0 over one period, at rest at both ends."""
    return 0.5 * (1.0 - math.cos(2.0 * math.pi * t / period))


def sample(run, times):
    """The run's fairlead tension [N] interpolated at ``times`` (NaN past where it stopped)."""
    values = np.interp(times, run["t"], run["fairlead_tension"])
    return np.where(times <= run["t"][-1] + 1e-9, values, np.nan)


def summary(run, keep=("dt", "integrator", "status", "completed", "wall_time_s", "simulated_s", "steps",
                       "rejected", "newton_iterations", "worst_rejections_in_one_step",
                       "most_newton_iterations_in_one_step", "peak_tension", "least_tension", "peak_kinetic_J",
                       "energy")):
    """The JSON-ready part of a run."""
    return {key: run[key] for key in keep if key in run}


def series(run, points=400):
    """A run's time series thinned to about ``points`` points, for results.json and figures."""
    stride = max(1, len(run["t"]) // points)
    return {"t": run["t"][::stride].tolist(), "fairlead_tension": run["fairlead_tension"][::stride].tolist()}


def flume_like(name, anchor, fairlead, motion, friction=True, elements=40, dt=0.01, duration=60.0):
    """A scene with the desire2023 Table 5 chain over the flume's flat 100 m floor."""
    line = Line(name, anchor, fairlead, (Segment(table5_chain(), LENGTH, elements),), 1)
    return Scene(name=name, lines=[line], seabed=Horizontal(FLUME_DEPTH),
                 contact=Contact(stiffness=3.0e5, damping_ratio=1.0),
                 environment=Environment(water_density=1025.0, gravity=9.81),
                 friction=Friction(model="isotropic", mu=0.3, v_threshold=0.01) if friction else Friction(),
                 motion=motion, solver=Solver(dt=dt, duration=duration), output=Output(every=1.0))


# --------------------------------------------------- 1. Batista-Perkovic stiffness

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


# ----------------------------------------------------------------- 2. snap loads

SNAP_AMPLITUDE = 7.5  # m: 1.5 x the paper's dynamic motion; the upper line goes slack each period


def snap_scene(dt, duration, friction=True):
    """The flume's flat floor driven at 7.5 m / 6 s (ramped over the first period)."""
    scene = flume_scene("flat", "dynamic", duration=duration, dt=dt)
    scene.motion = Motion(kind="harmonic", amplitude=(SNAP_AMPLITUDE, 0.0, 0.0), period=6.0, ramp=6.0)
    if not friction:
        scene.friction = Friction()
    return scene


class SlackMonitor:
    """Largest fraction of the suspended elements that are slack (strain <= 0) at any step."""

    def __init__(self, depth=FLUME_DEPTH, clearance=1.0):
        self.depth, self.clearance = depth, clearance
        self.fraction = 0.0

    def __call__(self, integ):
        system = integ.system
        strain = system.tension_strain(integ.X)
        r, _ = system.fem.at_quadrature(integ.X, system.fem.reduced)
        suspended = r[2] > -self.depth + self.clearance
        if np.any(suspended):
            self.fraction = max(self.fraction, float(np.mean(strain[suspended] <= 0.0)))


def run_snap(fast):
    """Case 2: snap loads; peak tension against dt and the energy balance."""
    duration = 12.0 if fast else 24.0
    steps = (0.02, 0.01, 0.005) if fast else (0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125)
    rows, runs = [], []
    for dt in steps:
        monitor = SlackMonitor()
        run = simulate(snap_scene(dt, duration), dt, duration, monitor=monitor)
        row = summary(run)
        row["slack_fraction"] = monitor.fraction
        row["peak_per_period"] = [float(run["fairlead_tension"][(run["t"] > 6.0 * k) & (run["t"] <= 6.0 * (k + 1))].max())
                                  for k in range(int(round(duration / 6.0)))]
        rows.append(row)
        runs.append(run)
    finest = rows[-1]["peak_tension"]
    errors = [r["peak_tension"] / finest - 1.0 for r in rows[:-1]]
    for row, error in zip(rows, errors + [0.0]):
        row["peak_error_vs_finest"] = error
    return {"duration_s": duration, "amplitude_m": SNAP_AMPLITUDE, "rows": rows,
            "series": {f"dt={r['dt']:g}": series(r) for r in runs}}


# ------------------------------------------------------------ 3. the steep step's edge

EDGE_X = -200.0  # m, the steep step's convex top (cablefem.geometry.generators.flume_step)


class EdgeMonitor:
    """Changes of contact state per step at the quadrature points within ``reach`` [m] of the
    convex edge: chatter shows as points flipping in and out of contact every step."""

    def __init__(self, reach=25.0):
        self.reach = reach
        self.previous = None
        self.changes = 0
        self.steps = 0

    def __call__(self, integ):
        system = integ.system
        r, _ = system.fem.at_quadrature(integ.X)
        points = r.reshape(3, -1).T
        near = np.abs(points[:, 0] - EDGE_X) <= self.reach
        touching = system.seabed.gap_only(points) < 0.0
        if self.previous is not None:
            self.changes += int(np.sum((touching != self.previous) & near))
            self.steps += 1
        self.previous = touching


def run_edge(fast):
    """Case 3: the steep step's convex edge under both flume motions, three dt."""
    motions = {"quasi-static": 17.0 if fast else 34.0, "dynamic": 12.0 if fast else 18.0}
    steps = (0.02,) if fast else (0.05, 0.02, 0.01)
    rows = []
    series_out = {}
    for motion, duration in motions.items():
        for dt in steps:
            monitor = EdgeMonitor()
            run = simulate(flume_scene("steep", motion, duration=duration, dt=dt), dt, duration, monitor=monitor)
            row = summary(run)
            row.update(motion=motion, edge_contact_changes=monitor.changes,
                       edge_changes_per_step=monitor.changes / max(monitor.steps, 1))
            rows.append(row)
            series_out[f"{motion} dt={dt:g}"] = series(run)
    for motion in motions:
        mine = [r for r in rows if r["motion"] == motion]
        finest = mine[-1]["peak_tension"]
        for row in mine:
            row["peak_difference_vs_finest"] = row["peak_tension"] / finest - 1.0
    return {"durations_s": motions, "rows": rows, "series": series_out}


# ------------------------------------------------------------ 4. lying and taut lines

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


# ----------------------------------------------------------------- 5. sudden stop

STOP_SPEED, STOP_DISTANCE, STOP_START = 1.0, 10.0, 2.0  # m/s, m, s


def stop_scene(dt, duration):
    """The flume line on its flat floor, frictionless (so that the static end state is unique):
    at rest for 2 s, then the fairlead moves away from the anchor at 1 m/s for 10 m and stops
    dead (a velocity jump at both ends of the stroke)."""
    end = STOP_START + STOP_DISTANCE / STOP_SPEED
    motion = Motion(kind="table", times=np.array([0.0, STOP_START, end, end + 1e3]),
                    positions=np.array([[0, 0, 0], [0, 0, 0], [STOP_DISTANCE, 0, 0], [STOP_DISTANCE, 0, 0]], float))
    return flume_like("stop", FLUME_ANCHOR, (0.0, 0.0, 0.0), motion, friction=False, dt=dt, duration=duration), end


def run_stop(fast):
    """Case 5: ring-down after a dead stop; decay of the tension's deviation from the static value."""
    duration = 32.0 if fast else 62.0
    steps = (0.02,) if fast else (0.05, 0.01)
    rows, runs = [], []
    for dt in steps:
        scene, stop = stop_scene(dt, duration)
        run = simulate(scene, dt, duration)
        line = scene.lines[0]
        final = fairlead_motion(scene.motion, duration)[0]
        moved = Line(line.name, line.anchor, line.fairlead + final, line.segments, line.order)
        system = build_system(scene, moved, dynamic=False)
        X = solve_static(system, tolerance=scene.solver.tolerance).X
        static = float(np.linalg.norm(system.residual(X)[system.fem.fairlead_dof]))
        t, T = run["t"], run["fairlead_tension"]
        windows = []
        for k in range(int((duration - stop) // 5)):
            inside = (t > stop + 5 * k) & (t <= stop + 5 * (k + 1))
            if np.any(inside):
                windows.append({"from_s": 5.0 * k, "to_s": 5.0 * (k + 1),
                                "max_deviation_N": float(np.max(np.abs(T[inside] - static)))})
        deviations = np.array([w["max_deviation_N"] for w in windows])
        # e-folding time of the envelope: a line fitted to log(deviation) over the windows
        usable = deviations > 1e-6 * static
        rate = -np.polyfit([5.0 * k + 2.5 for k in range(len(windows))], np.log(deviations), 1)[0] \
            if usable.sum() >= 2 else None
        row = summary(run)
        row.update(static_tension=static, overshoot=float(np.max(T[t > stop]) / static - 1.0),
                   final_error=float(T[-1] / static - 1.0), windows=windows,
                   envelope_decay_time_s=(1.0 / rate) if rate and rate > 0 else None)
        rows.append(row)
        runs.append(run)
    return {"duration_s": duration, "speed_m_s": STOP_SPEED, "stroke_m": STOP_DISTANCE,
            "stop_s": STOP_START + STOP_DISTANCE / STOP_SPEED, "rows": rows,
            "series": {f"dt={r['dt']:g}": series(r) for r in runs}}


# ------------------------------------------------------------ 6. 1e-4 s to 0.1 s

def run_steps(fast):
    """Case 6: the snap scene from dt = 1e-4 to 0.1 s through ``run_scene`` (the user's path,
    with its output frames): every run completes or stops with a message; the files it wrote
    are read back and checked for NaN and for tensions no line can carry; error against a run
    in plain fixed steps of the finest dt (``simulate``, no output frames), and cost per dt."""
    duration = 8.0 if fast else 12.0
    steps = (0.005, 0.01, 0.05, 0.1) if fast else (1e-4, 3e-4, 1e-3, 3e-3, 0.01, 0.03, 0.1)
    finest = 0.002 if fast else 1e-4
    grid = np.arange(0.0, duration + 1e-9, 0.1)
    reference = simulate(snap_scene(finest, duration), finest, duration, energy=False)
    ref = sample(reference, grid)
    scale = float(np.mean(ref))
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for dt in steps:
            out = os.path.join(scratch, f"dt{dt:g}")
            scene = snap_scene(dt, duration)
            scene.output = Output(dir=out, every=0.5)
            row = {"dt": dt}
            try:
                run_scene(scene, out_dir=out, progress=False)
                row["status"] = "completed"
            except ConvergenceError as error:
                row["status"] = f"stopped: {error}"
            with open(os.path.join(out, "summary.json")) as handle:
                written = json.load(handle)
            with open(os.path.join(out, "tensions.csv")) as handle:
                table = np.array([[float(x) for x in r] for r in list(csv.reader(handle))[1:]])
            t, T = table[:, 0], table[:, 1]
            ok = grid <= t[-1] + 1e-9
            difference = np.interp(grid[ok], t, T) - ref[ok]
            row.update(wall_time_s=written["wall_time_s"], steps=written["steps"],
                       newton_iterations=written["newton_iterations"],
                       rejected=sum(s["rejected"] for s in written["integrator"]),
                       simulated_s=written["simulated_time_s"], summary_status=written["status"],
                       rows_written=len(table), nan_in_outputs=bool(not np.all(np.isfinite(table)))
                       or "nan" in json.dumps(written).lower(),
                       largest_tension_written=float(np.max(T)), shortest_step_written=float(np.min(np.diff(t))),
                       rms_error_vs_finest=float(np.sqrt(np.mean(difference**2)) / scale),
                       peak_error_vs_finest=float(np.max(T) / reference["peak_tension"] - 1.0))
            rows.append(row)
    return {"duration_s": duration, "reference_dt": finest, "reference_status": reference["status"],
            "reference_peak_tension": reference["peak_tension"], "rows": rows}


# ----------------------------------------------- 7. minimal reproductions of what failed

def toy_scene(stiffness, dt, integrator="bdf2", rho_inf=0.5, depth=10.0, motion=None, EA=5.055e11):
    """A 22 m chain (Table 2 mass and diameter, EA [N], no drag, added mass or damping) of
    4 P1 elements between (0, 0, -5) and (21, 0, -5) over a flat seabed ``depth`` [m] deep
    (G_K ``stiffness`` [N/m^3]). By default the fairlead moves 4 m towards the anchor at
    0.1 m/s, which lays the middle of the chain onto a seabed 10 m deep at ~0.06 m/s."""
    chain = LineType("toy-chain", diameter=0.3539, mass=835.4, EA=EA, damping=0.0, Cd_normal=0.0,
                     Cd_tangential=0.0, Ca_normal=0.0, Ca_tangential=0.0)
    line = Line("toy", (0.0, 0.0, -5.0), (21.0, 0.0, -5.0), (Segment(chain, 22.0, 4),), 1)
    if motion is None:
        motion = Motion(kind="table", times=np.array([0.0, 40.0, 1e3]),
                        positions=np.array([[0, 0, 0], [-4.0, 0, 0], [-4.0, 0, 0]]))
    return Scene(name="toy", lines=[line], seabed=Horizontal(depth), contact=Contact(stiffness=stiffness),
                 environment=Environment(), friction=Friction(), motion=motion,
                 solver=Solver(integrator=integrator, dt=dt, rho_inf=rho_inf, duration=60.0))


def run_reproductions(fast):
    """Case 7, the problems this suite found, kept as regressions: (a) a chain laid onto a stiff
    seabed gained energy when halved BDF2 steps jumped back to dt (fixed: steps grow by at most
    2x); (b) generalised-alpha with rho_inf >= 0.6 pumps energy into a stiff chain pulled taut
    (a property of the scheme on nonlinear problems: default rho_inf is now 0.5 and
    ``run.setting_warnings`` says so before a run); (c) output frames no longer leave slivers.
    Peak kinetic energy against what the motion gives it (~1e2 J for (a), ~5e3 J for (b))."""
    landing = []
    settings = [(3e14, 0.01)] if fast else \
        [(3e5, 0.01), (3e8, 0.01), (3e11, 0.01), (3e11, 0.001), (3e14, 0.01), (3e14, 0.001)]
    for stiffness, dt in settings:
        row = summary(simulate(toy_scene(stiffness, dt), dt, 30.0, energy=False))
        row.update(stiffness=stiffness)
        landing.append(row)
    alpha = []
    smooth = Motion(kind="harmonic", amplitude=(-1.0, 0.0, 0.0), period=20.0, ramp=10.0)
    variants = (("bdf2", None), ("generalized-alpha", 0.5)) if fast else (
        ("bdf2", None), ("generalized-alpha", 0.0), ("generalized-alpha", 0.5), ("generalized-alpha", 0.6),
        ("generalized-alpha", 0.8), ("generalized-alpha", 1.0))
    for integrator, rho in variants:
        for EA in ((5.055e11,) if fast else (3.15e9, 5.055e11)):
            scene = toy_scene(3e5, 0.01, integrator, 0.5 if rho is None else rho, depth=1000.0, motion=smooth, EA=EA)
            run = simulate(scene, 0.01, 20.0, integrator, energy=False)
            row = summary(run)
            row.update(rho_inf=rho, EA=EA)
            alpha.append(row)
    return {"landing": landing, "alpha": alpha, "frames": frame_landing()}


def frame_landing(dt=1e-4, duration=1.15, every=0.1):
    """(c) ``run_scene`` lands on its output frames by shortening the step to the frame time;
    t accumulates round-off, and when it sits more than 1e-9 dt short of a frame the step
    taken is that sliver (1.5e-13 s at t = 1.5 s here), after which BDF2's next step has a
    step ratio of ~1e9. The toy chain (EA 3.15e9 N, hanging freely, 1 m surge) at dt = 1e-4 s,
    frames every 0.1 s: the largest tension and the shortest step in tensions.csv."""
    motion = Motion(kind="harmonic", amplitude=(-1.0, 0.0, 0.0), period=4.0, ramp=2.0)
    scene = toy_scene(3e5, dt, depth=1000.0, motion=motion, EA=3.15e9)
    with tempfile.TemporaryDirectory() as out:
        scene.output = Output(dir=out, every=every)
        written = run_scene(scene, out_dir=out, duration=duration, dt=dt, progress=False)
        table = np.loadtxt(os.path.join(out, "tensions.csv"), delimiter=",", skiprows=1)
    t, T = table[:, 0], table[:, 1]
    return {"dt": dt, "every": every, "status": written["status"], "first_tension": float(T[0]),
            "largest_tension": float(T.max()), "time_of_largest": float(t[np.argmax(T)]),
            "shortest_step_written": float(np.min(np.diff(t)))}


# ------------------------------------------------------------------------ all of it

RUNNERS = {"stiff": run_stiff, "snap": run_snap, "edge": run_edge, "lying": run_lying_taut,
           "taut": None, "stop": run_stop, "steps": run_steps, "repro": run_reproductions}  # "taut" runs with "lying"


def run(fast=False, cases=CASES):
    """The cases named in ``cases`` (all by default); a dict of plain numbers (JSON-ready)."""
    start = time.perf_counter()
    results = {"fast": fast}
    for name in cases:
        runner = RUNNERS[name] if name != "taut" else (None if "lying" in cases else run_lying_taut)
        if runner is None:
            continue
        key = "lying_taut" if runner is run_lying_taut else name
        case_start = time.perf_counter()
        results[key] = runner(fast)
        results[key]["wall_time_s"] = time.perf_counter() - case_start
    results["wall_time_s"] = time.perf_counter() - start
    return results


def _f(value, spec):
    return "-" if value is None else format(value, spec)


def _status(row):
    return "ok" if row["status"] == "completed" else row["status"]


def _energy(row):
    e = row.get("energy")
    if not e:
        return "-"
    return (f"W {e['fairlead_work_J'] / 1e6:8.3f} MJ  dE {e['mechanical_change_J'] / 1e6:8.3f}  "
            f"D {sum(e['dissipated_J'].values()) / 1e6:7.3f}  W_am {e['added_mass_work_J'] / 1e6:7.3f}  "
            f"E_num {e['numerical_relative']:+.1e} of {e['throughput_J'] / 1e6:.3g} MJ  "
            f"min P_diss {e['least_dissipation_relative']:+.0e}")


def report_text(results):
    """The tables, as text."""
    out = []
    if "stiff" in results:
        r = results["stiff"]
        lim = r["explicit_limits"]
        out += [f"1. Batista-Perkovic stiffness: EA 5.055e11 N, G_K 3e14 N/m^3, P1 x 31 ({lim['element_m']:.1f} m), "
                f"fairlead swept H 3.5 -> 4.5 -> 3.5 MN over {r['period_s']:g} s (ran {r['duration_s']:g} s)",
                f"   an explicit code needs dt < h/sqrt(EA/m) = {lim['axial_cfl_s']:.2e} s (axial wave) and "
                f"< 2/sqrt(G_K d/m) = {lim['seabed_spring_s']:.2e} s (seabed spring)",
                "   static FEM vs closed form along the motion: "
                + ", ".join(f"{s['error']:+.1e}" for s in r["statics"]),
                "   integrator   dt [s]  max|dT| loading  unloading  vs finest  T range [MN]  peak KE [J]  rejected  "
                "wall [s]  status"]
        for row in r["rows"]:
            out.append(f"   {row['integrator']:17s} {row['dt']:5.3f}  {row['max_error_loading']:9.1e}  "
                       f"{_f(row['max_error_unloading'], '9.1e')}  {row['max_difference_to_finest_loading']:9.1e}  "
                       f"{row['least_tension'] / 1e6:5.2f}-{row['peak_tension'] / 1e6:<6.2f}  "
                       f"{row['peak_kinetic_J']:10.3g}  {row['rejected']:6d}  {row['wall_time_s']:7.1f}  {_status(row)}")
        out.append("")
    if "snap" in results:
        r = results["snap"]
        out += [f"2. Snap loads: flume flat floor, {r['amplitude_m']:g} m / 6 s surge, {r['duration_s']:g} s",
                "   dt [s]   peak T [MN]  vs finest  min T [MN]  slack  rejected  wall [s]  energy balance"]
        for row in r["rows"]:
            out.append(f"   {row['dt']:6.4f}  {row['peak_tension'] / 1e6:9.4f}  {row['peak_error_vs_finest']:+9.2e}  "
                       f"{row['least_tension'] / 1e6:8.4f}  {row['slack_fraction']:5.2f}  {row['rejected']:5d}  "
                       f"{row['wall_time_s']:7.1f}  {_energy(row)}  {'' if row['completed'] else _status(row)}")
        out.append("   peak per 6 s period [MN]: " + "; ".join(
            f"dt {row['dt']:g}: " + " ".join(f"{p / 1e6:.3f}" for p in row["peak_per_period"]) for row in r["rows"]))
        out.append("")
    if "edge" in results:
        r = results["edge"]
        out += ["3. Steep 19 deg step, convex edge at x = -200 m",
                "   motion        dt [s]  peak T [MN]  vs finest  min T [MN]  rejected  worst in one step  "
                "max Newton/step  edge flips/step  energy balance"]
        for row in r["rows"]:
            out.append(f"   {row['motion']:12s}  {row['dt']:5.3f}  {row['peak_tension'] / 1e6:9.4f}  "
                       f"{row['peak_difference_vs_finest']:+9.2e}  {row['least_tension'] / 1e6:8.4f}  {row['rejected']:5d}  "
                       f"{row['worst_rejections_in_one_step']:5d}  {row['most_newton_iterations_in_one_step']:5d}  "
                       f"{row['edge_changes_per_step']:8.3f}  {_energy(row)}  {'' if row['completed'] else _status(row)}")
        out.append("")
    if "lying_taut" in results:
        r = results["lying_taut"]
        out += [f"4. Lying line (fairlead on the floor, {r['lying']['pretension_N'] / 1e3:g} kN, slid "
                f"+-{r['lying']['stroke_m']:g} m along itself over {r['lying']['period_s']:g} s) and taut line "
                f"(chord/stretched {r['taut']['chord_ratios'][0]} -> {r['taut']['chord_ratios'][1]} over "
                f"{r['taut']['period_s']:g} s)",
                "   case   friction  dt [s]  max|T-T_cf|/peak  at start  T_cf peak [MN]  rejected (worst step)  wall [s]  "
                "energy balance"]
        for row in r["rows"]:
            out.append(f"   {row['case']:6s} {str(row['friction']):8s} {row['dt']:5.3f}  "
                       f"{row['max_error_vs_frictionless_closed_form']:9.2e}  {row['error_at_start']:+9.1e}  "
                       f"{row['closed_form_peak'] / 1e6:9.3f}  {row['rejected']:5d} ({row['worst_rejections_in_one_step']:2d})"
                       f"  {row['wall_time_s']:7.1f}  "
                       f"{_energy(row)}  {'' if row['completed'] else _status(row)}")
        out.append("")
    if "stop" in results:
        r = results["stop"]
        out += [f"5. Sudden stop: {r['speed_m_s']:g} m/s for {r['stroke_m']:g} m, dead stop at t = {r['stop_s']:g} s, "
                f"frictionless, {r['duration_s']:g} s",
                "   dt [s]  static T [MN]  overshoot  max|T - T_static| per 5 s after the stop [kN]"
                "                 e-fold [s]  final error  energy balance"]
        for row in r["rows"]:
            env = " ".join(f"{w['max_deviation_N'] / 1e3:7.1f}" for w in row["windows"][:10])
            out.append(f"   {row['dt']:5.3f}  {row['static_tension'] / 1e6:9.4f}  {row['overshoot']:+8.2%}  {env}  "
                       f"{_f(row['envelope_decay_time_s'], '6.2f')}  {row['final_error']:+9.1e}  {_energy(row)}  "
                       f"{'' if row['completed'] else _status(row)}")
        out.append("")
    if "steps" in results:
        r = results["steps"]
        out += [f"6. Time steps on the snap scene ({r['duration_s']:g} s through run_scene), against fixed steps of "
                f"{r['reference_dt']:g} s (peak {r['reference_peak_tension'] / 1e6:.4f} MN)",
                "   dt [s]   RMS error  peak error  largest T written [MN]  shortest step [s]  steps    Newton  "
                "rejected  wall [s]  NaN  status"]
        for row in r["rows"]:
            out.append(f"   {row['dt']:7.4f}  {row['rms_error_vs_finest']:9.2e}  {row['peak_error_vs_finest']:+9.2e}  "
                       f"{row['largest_tension_written'] / 1e6:12.4g}  {row['shortest_step_written']:14.2e}  "
                       f"{row['steps']:6d}  {row['newton_iterations']:7d}  {row['rejected']:6d}  {row['wall_time_s']:7.1f}  "
                       f"{str(row['nan_in_outputs']):5s}  {_status(row)}")
        out.append("")
    if "repro" in results:
        r = results["repro"]
        out += ["7a. A 4-element chain (EA 5.055e11 N) laid onto a flat seabed at 0.06 m/s, 30 s: peak kinetic energy",
                "   G_K [N/m^3]  dt [s]   peak KE [J]  rejected  status"]
        for row in r["landing"]:
            out.append(f"   {row['stiffness']:9.0e}  {row['dt']:6.3f}  {row['peak_kinetic_J']:10.3e}  "
                       f"{row['rejected']:5d}  {_status(row)}")
        out += ["7b. The same chain hanging freely, fairlead moved 1 m (smooth, 20 s), dt = 0.01 s: peak kinetic energy",
                "   integrator          rho_inf  EA [N]     peak KE [J]  rejected  status"]
        for row in r["alpha"]:
            out.append(f"   {row['integrator']:18s}  {_f(row['rho_inf'], '5.1f'):5s}  {row['EA']:9.3g}  "
                       f"{row['peak_kinetic_J']:10.3e}  {row['rejected']:5d}  {_status(row)}")
        f = r["frames"]
        out += [f"7c. run_scene at dt = {f['dt']:g} s with frames every {f['every']:g} s (toy chain, EA 3.15e9 N): "
                f"tension {f['first_tension'] / 1e3:.1f} kN at t = 0, largest written {f['largest_tension'] / 1e3:.4g} kN "
                f"at t = {f['time_of_largest']:.4f} s; shortest step written {f['shortest_step_written']:.2e} s; "
                f"status {f['status']}", ""]
    out.append(f"wall time {results['wall_time_s']:.1f} s")
    return "\n".join(out)


def figures(results, out):
    """tensions.png: the fairlead tension of the stiff, snap, stop and edge cases."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels = [(k, t) for k, t in (("stiff", "1. stiff line vs closed form"), ("snap", "2. snap loads"),
                                   ("edge", "3. steep step"), ("stop", "5. sudden stop")) if k in results]
    if not panels:
        return
    fig, axes = plt.subplots(len(panels), 1, figsize=(10, 3.2 * len(panels)), squeeze=False)
    for ax, (key, title) in zip(axes[:, 0], panels):
        for label, curve in results[key]["series"].items():
            ax.plot(curve["t"], np.array(curve["fairlead_tension"]) / 1e6, lw=0.8, label=label)
        if key == "stiff":
            closed = results[key]["closed_form"]
            ax.plot(closed["t"], np.array(closed["fairlead_tension"]) / 1e6, "k--", lw=1, label="closed form")
            ax.set_ylim(4.0, 6.0)
        ax.set(title=title, xlabel="t [s]", ylabel="fairlead tension [MN]")
        ax.legend(fontsize=6, ncol=3)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "tensions.png", dpi=110)
    plt.close("all")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="short runs and fewer dt: what the tests assert")
    parser.add_argument("--out", type=Path, default=HERE, help="directory for results.json and tensions.png")
    parser.add_argument("--case", nargs="+", choices=CASES, default=list(CASES), help="cases to run")
    args = parser.parse_args(argv)
    results = jsonable(run(fast=args.fast, cases=tuple(args.case)), private=True, drop=("integ",))
    write_json(args.out / "results.json", results)
    print(report_text(results))
    figures(results, args.out)
    print(f"wrote {args.out / 'results.json'} and tensions.png")


if __name__ == "__main__":
    main()
