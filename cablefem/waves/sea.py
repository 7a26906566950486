"""A linear (Airy) sea: a sum of regular wave components over water of constant depth.

Each component j has an amplitude A_j [m], an angular frequency omega_j [rad/s], a propagation
heading beta_j [rad, from +x towards +y] and a phase phi_j [rad]; its wave number k_j solves the
finite-depth dispersion relation omega^2 = g k tanh(k h) (``cablefem.waves.dispersion``). The free
surface is

    eta(x, y, t) = R(t) sum_j A_j cos(theta_j),   theta_j = k_j (x cos beta_j + y sin beta_j) - omega_j t + phi_j,

R the ramp (the smoothstep 3u^2 - 2u^3 of u = t / ramp, 1 without a ramp), and the water moves as
linear theory has it below the surface (``cablefem.waves.airy``), at a stretched height (Wheeler,
vertical or none). A ``Sea`` is data only: its constructors (``regular``, ``from_components``;
``cablefem.waves.spectra`` for irregular seas, ``cablefem.waves.series`` for an elevation record)
check their input and name the key of a bad value.
"""

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from cablefem.errors import InputError
from cablefem.waves.dispersion import wave_number

#: how the kinematics are evaluated above and below the mean level (``cablefem.waves.airy``)
STRETCHING = ("wheeler", "vertical", "none")


@dataclass(frozen=True)
class Sea:
    """Components (tuples, so that a scene stays hashable): amplitude [m], omega [rad/s],
    direction [rad], phase [rad]; water ``depth`` [m] and ``gravity`` [m/s^2] of the dispersion;
    ``stretching`` (``STRETCHING``); ``ramp`` [s]; ``kind`` (what it was made from: "regular",
    "irregular", "components", "elevation", a MoorDyn WaveKin); ``state``: (name, value) pairs that
    describe the sea state (summary.json); ``source``: where it was read; ``current``: a current that
    varies in time and space (``cablefem.waves.grid.CurrentGrid``, MoorDyn-C's Currents 2 and 5), which
    adds to the waves' velocity, or None. A sea of no components (``current_only``) is such a current
    in still water."""

    amplitude: tuple
    omega: tuple
    direction: tuple
    phase: tuple
    depth: float
    gravity: float = 9.81
    stretching: str = "wheeler"
    ramp: float = 0.0
    kind: str = "components"
    state: tuple = field(default=())
    source: str = ""
    current: object = None

    @classmethod
    def from_components(cls, amplitude, omega, direction, phase, depth, gravity=9.81, stretching="wheeler",
                        ramp=0.0, kind="components", state=(), source="", key="waves"):
        """A checked Sea from component arrays (m,) each [m, rad/s, rad, rad]; InputError at ``key``."""
        arrays = [np.atleast_1d(np.asarray(a, dtype=float)) for a in (amplitude, omega, direction, phase)]
        m = len(arrays[0])
        for name, array in zip(("amplitude", "omega", "direction", "phase"), arrays):
            if array.ndim != 1 or len(array) != m:
                raise InputError(f"{name}: expected {m} values, one per component, got shape {array.shape}", key=key)
            if not np.all(np.isfinite(array)):
                raise InputError(f"{name}: values must be finite", key=key)
        if m == 0:
            raise InputError("no wave components", key=key)
        if np.any(arrays[0] < 0.0) or np.any(arrays[1] < 0.0):
            raise InputError("amplitudes and frequencies must be >= 0", key=key)
        if not (np.isfinite(depth) and depth > 0.0):
            raise InputError(f"the water depth must be > 0, got {depth:g} m", key=f"{key}.depth")
        if stretching not in STRETCHING:
            raise InputError(f"unknown stretching '{stretching}'; valid: {' | '.join(STRETCHING)}",
                             key=f"{key}.stretching")
        # the deepest trough: at most the amplitudes' sum, and ~Hm0 in any realistic record of many
        reach = min(float(np.sum(arrays[0])), 2.0 * 4.0 * np.sqrt(0.5 * np.sum(arrays[0] ** 2)))
        if reach >= depth:
            raise InputError(f"troughs of {reach:g} m would reach the seabed {depth:g} m down (linear waves "
                             "need amplitudes well below the depth)", key=key)
        return cls(*(tuple(float(x) for x in a) for a in arrays), float(depth), float(gravity), stretching,
                   float(ramp), kind, tuple(state), source)

    @classmethod
    def current_only(cls, current, depth, gravity=9.81):
        """Still water carrying ``current`` (a ``CurrentGrid``) over water ``depth`` [m] deep."""
        return cls((), (), (), (), float(depth), float(gravity), "none", 0.0, current.kind, (), current.source,
                   current)

    @classmethod
    def regular(cls, amplitude, period, direction=0.0, phase=0.0, depth=100.0, gravity=9.81, **options):
        """One component: amplitude [m], period [s], direction and phase [rad]."""
        return cls.from_components([amplitude], [2.0 * np.pi / period], [direction], [phase], depth, gravity,
                                   kind=options.pop("kind", "regular"), **options)

    # ------------------------------------------------------------------ derived arrays
    @cached_property
    def arrays(self):
        """Per-component arrays (m,): amplitude, omega, k, cos beta, sin beta, phase."""
        amplitude, omega, direction, phase = (np.array(x) for x in (self.amplitude, self.omega, self.direction,
                                                                       self.phase))
        k = wave_number(omega, self.depth, self.gravity)
        return amplitude, omega, k, np.cos(direction), np.sin(direction), phase

    @property
    def count(self):
        """Number of components."""
        return len(self.amplitude)

    def ramp_factor(self, t):
        """R(t) and dR/dt [1/s] (arrays shaped like t): the smoothstep 3u^2 - 2u^3, u = t / ramp."""
        t = np.asarray(t, dtype=float)
        if self.ramp <= 0.0:
            return np.ones_like(t), np.zeros_like(t)
        u = np.clip(t / self.ramp, 0.0, 1.0)
        return u * u * (3.0 - 2.0 * u), np.where((u > 0.0) & (u < 1.0), 6.0 * u * (1.0 - u) / self.ramp, 0.0)

    def elevation(self, x, y, t):
        """Free-surface elevation eta [m] at horizontal positions x, y [m] and times t [s] (broadcast)."""
        amplitude, omega, k, cos_b, sin_b, phase = self.arrays
        x, y, t = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (x, y, t)))
        theta = k * (x[..., None] * cos_b + y[..., None] * sin_b) - omega * t[..., None] + phase
        return self.ramp_factor(t)[0] * np.sum(amplitude * np.cos(theta), axis=-1)

    def kinematics(self, points, t, gradients=False):
        """The water's motion at points (n, 3) [m] and time t [s] (``cablefem.waves.airy.Kinematics``)."""
        from cablefem.waves.airy import kinematics

        result = kinematics(self, points, t, gradients)
        if self.current is not None:
            U, G = self.current.at(points, t, gradients)
            result.velocity = result.velocity + U
            if gradients:
                result.velocity_gradient = result.velocity_gradient + G
        return result

    def spectrum_moments(self):
        """m0 [m^2] of the components (sum A^2 / 2) and the significant height 4 sqrt(m0) [m]."""
        m0 = 0.5 * float(np.sum(np.square(self.amplitude)))
        return m0, float(4.0 * np.sqrt(m0))

    def describe(self):
        """The sea state as a JSON-able dict (summary.json; its waves, not its ``current``)."""
        m0, hs = self.spectrum_moments()
        omega = np.array(self.omega)
        return {"kind": self.kind, **dict(self.state), "components": self.count, "depth": self.depth,
                "stretching": self.stretching, "ramp": self.ramp, "m0": m0, "Hm0": hs,
                "omega_range": [float(omega.min()), float(omega.max())],
                **({"source": self.source} if self.source else {})}
