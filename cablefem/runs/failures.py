"""Line failures during a run: when a held line end lets go, and what the line is after it.

A scene's ``failures`` (``cablefem.model.failure``) are watched at the end of each accepted step of the
run (each row of tensions.csv): a time threshold is a time the steps land on (``next_time``, as the
output times are), a tension threshold is compared with the tension at that end after each step
(``cablefem.runs.run``: the steps stop after the first one over it). At
the first row where a failure's condition holds the end lets go (``release``): the line is built again
with that end free (an unknown like any free end: ``Line.prescribed``), its integrator made again from
the same positions, velocities, scheme memory, clock and counters, with the acceleration its new free
end gives (``Integrator.initial_acceleration``), and the groups that step the lines are made again
(a new factorisation and a new compiled problem: one event per failure). In a network the end leaves
its point or body: the line's end names no point any more. The solvers do not know that a line
failed; the released end reports no force from then on (its tension 0 in tensions.csv).
"""

from dataclasses import replace

import numpy as np

from cablefem.dynamics.registry import integrator_options
from cablefem.fem.system import build_system


class Failures:
    """The failures of ``scene`` still to happen and those that did, for the run's loop and summary.json."""

    def __init__(self, scene, dt):
        self.pending = list(scene.failures)
        self.released = []  # (string, end) of the ends that let go
        self.record = []  # summary.json's entries, in the order the ends let go
        self.near = 1e-6 * dt  # times closer than this are the same time

    @property
    def watching_tension(self):
        """Whether a pending failure has a tension threshold (the run then checks after every step)."""
        return any(f.tension is not None for f in self.pending)

    def next_time(self, t):
        """The earliest time threshold of a pending failure after t [s], inf if none."""
        return min((f.time for f in self.pending if f.time is not None and f.time > t + self.near), default=np.inf)

    def summary(self):
        """summary.json's ``failures``: per failure its line, end, condition (time, tension), and for an
        end that let go ``released_at`` [s], ``tension_at_release`` [N] and which condition held."""
        return self.record + [{**f.describe(), "released_at": None, "tension_at_release": None, "condition": None}
                              for f in self.pending]

    def due(self, row):
        """The pending failures whose condition holds at ``row`` (t, [(fairlead, anchor) force per line])."""
        t, forces = row
        return [f for f in self.pending
                if (f.time is not None and f.time <= t + self.near)
                or (f.tension is not None and _tension(forces, f) > f.tension)]

    def first_due(self, rows):
        """The index of the first of ``rows`` at which a pending failure's condition holds, or None."""
        return next((k for k, row in enumerate(rows) if self.due(row)), None)

    def zero(self, rows):
        """``rows`` with the forces of the released ends set to zero (a free end carries no force)."""
        if not self.released:
            return rows
        out = []
        for t, forces in rows:
            forces = [np.array(f, dtype=float) for f in forces]
            for k, end in self.released:
                forces[k][1 - end] = 0.0  # a row's forces are (fairlead, anchor)
            out.append((t, forces))
        return out

    def release_due(self, row, scene, integrators):
        """Let go of every end whose failure is due at ``row``, each line's integrator replaced in
        ``integrators`` (``release``); the indices of the lines replaced (empty if nothing was due)."""
        t, forces = row
        replaced = []
        for failure in self.due(row):
            k, end = failure.string, failure.string_end
            self.record.append({**failure.describe(), "released_at": float(t),
                                "tension_at_release": _tension(forces, failure),
                                "condition": "time" if failure.time is not None and failure.time <= t + self.near
                                else "tension"})
            integrators[k] = release(scene, integrators[k], end)
            self.pending.remove(failure)
            self.released.append((k, end))
            replaced.append(k)
        return replaced

def _tension(forces, failure):
    """The tension [N] at the failure's end in a row's forces ((fairlead, anchor) per line)."""
    return float(np.linalg.norm(forces[failure.string][1 - failure.string_end]))


def release(scene, integ, end):
    """A new integrator of ``integ``'s line with its end ``end`` (0 anchor, 1 fairlead) free, from the
    same state: positions, velocities, the scheme's memory and clock, the history of the points and
    the counters; its acceleration the one its loads give with that end free."""
    old = integ.system
    prescribed, ends, tangents = list(old.line.prescribed), list(old.line.ends), list(old.line.tangents)
    prescribed[end], ends[end], tangents[end] = False, None, None  # a clamped tangent lets go with its end
    line = replace(old.line, prescribed=tuple(prescribed), ends=tuple(ends), tangents=tuple(tangents))
    system = build_system(scene, line)
    for rule, (committed, _) in old.history.items():
        system.history[rule][0][...] = committed
        system.history[rule][1][...] = committed
    new = type(integ)(system, integ.X, integ.boundary, V0=integ.V, t0=integ.t, dt=integ.dt, anchor=integ.anchor_path,
                      **integrator_options(scene.solver, type(integ)))
    new.memory[...] = integ.memory
    new.clock[...] = integ.clock
    new.counters[...] = integ.counters
    new.last_h = integ.last_h
    return new

