"""The step control of a run's lines taken together: fixed steps landing on the output times, or
adaptive steps from the local error estimate."""

import numpy as np

from cablefem.dynamics.integrator import Integrator


class StepControl:
    """Fixed steps of dt (``times``), or (``solver.adaptive``, BDF2; ``advance``) steps chosen
    from the local error estimate so that the tension error per step stays near
    ``solver.error_tolerance`` (a fraction of the largest tension), never above dt; all lines
    step together. Either lands on the stops it is given without leaving a sliver before them."""

    def __init__(self, solver, dt):
        self.adaptive = solver.adaptive
        self.tolerance = solver.error_tolerance
        self.max_dt = dt
        self.h = dt / 8 if self.adaptive else dt
        self.accepted = self.rejected = 0

    @staticmethod
    def landing(h, to_stop):
        """The step to take instead of h with ``to_stop`` [s] left: all of it when h would leave
        no more than ``Integrator.STRETCH`` h (never a sliver before a stop), half of it when
        it is under 2 h, else h."""
        if to_stop <= h * (1 + Integrator.STRETCH):
            return to_stop
        return to_stop / 2 if to_stop < 2 * h else h

    def times(self, t, stop):
        """The times (m,) of fixed steps of dt from t to ``stop``, landing on it (``landing``)."""
        times = []
        while stop - t > 1e-9 * self.max_dt:
            h = self.landing(self.max_dt, stop - t)
            t = stop if h == stop - t else t + h
            times.append(t)
        return np.array(times)

    def advance(self, integrators, to_stop):
        """Take one step (retrying smaller ones when adaptive) of at most ``to_stop`` [s]."""
        while True:
            h = self.landing(self.h if self.adaptive else self.max_dt, to_stop)
            snapshots = [integ.snapshot() for integ in integrators]
            first = any(getattr(integ, "previous", True) is None for integ in integrators)
            for integ in integrators:
                integ.step(h)
            if not self.adaptive or first:
                return h
            error = max(integ.error_estimate() for integ in integrators)
            factor = 0.9 * (self.tolerance / error) ** (1 / 3) if error > 0 else 2.0
            if error <= self.tolerance or h <= integrators[0].min_dt:
                self.accepted += 1
                if h >= self.h * (1 - 1e-12):  # not shortened to land on an output time
                    self.h = min(self.max_dt, h * min(2.0, max(0.5, factor)))
                return h
            self.rejected += 1
            for integ, snap in zip(integrators, snapshots):
                integ.restore(snap)
            self.h = h * max(0.2, factor)
