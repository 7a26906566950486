"""The driver of verification/stability's cases: a line marched step by step with its energy
ledger (W_fairlead = dKE + dPE + D_internal + D_seabed + D_drag + W_added_mass + E_numerical), and
the helpers the cases share (a tabled motion, samples, summaries, series, a flume-like scene)."""

import math
import time

import numpy as np

from cablefem.errors import ConvergenceError
from cablefem.geometry import Horizontal
from cablefem.model.line import Line, Segment
from cablefem.loads import State
from cablefem.loads.added_mass import AddedMass
from cablefem.loads.drag import Drag
from cablefem.model.scene import Contact, Environment, Friction, Motion, Output, Scene, Solver
from cablefem.model.builtin import FLUME_DEPTH, table5_chain
from cablefem.study import start_line

LENGTH = 635.0  # m, the desire2023 line (Tables 2 and 5)

#: dissipative loads whose power the ledger integrates
DISSIPATIONS = ("internal", "seabed", "drag")


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
        if system.has("friction"):  # on the normal force the contact just handed it
            contact = contact + system.load("friction").evaluate(state, False).force
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
