"""Axial laws of a line type other than T = EA (e + beta de/dt): a strain-tension table, MoorDyn-C's
viscoelastic rope (static and dynamic stiffness, the dynamic one constant or rising with the mean
load) and its SYROPE working curves (``cablefem.loads.rope`` evaluates them; docs/scene.md names
their keys).

- **table** (``EA = { strain = [...], tension = [...] }``, MoorDyn's EA curve file): T(e) piecewise
  linear through the rows; below the first row straight from (0, 0), beyond the last with the last
  row's slope. MoorDyn-C (``Line::getNonlinearEA``, ``Util/Interp.hpp``) holds the end values
  instead: the first tension for any strain below the first row, the last beyond the last.
- **internal damping** BA [N s] (T_d = BA de/dt), or a table of T_d against de/dt (MoorDyn's BA curve,
  ``Line::getNonlinearBA``: a table of positive rates acts mirrored on negative ones).
- **viscoelastic** (``EA_s|EA_d``, ``EA_s|EA_Dc|EA_D_Lm``; ``Line.cpp``, ELASTIC_VISCO_CTE/MEAN):
  a spring EA_1 with the damper BA (the slow part, stretch e_1) in series with the spring EA_2 and
  the damper BA_D (the fast part); EA_1 = EA_2 EA_s / (EA_2 - EA_s) so that the series is EA_s,
  EA_2 = EA_Dc + EA_D_Lm T_mean with T_mean = EA_1 e_1 (EA_D_Lm = 0: constant), and
  (BA + BA_D) de_1/dt = EA_2 e - (EA_1 + EA_2) e_1 + BA_D de/dt, T = EA_1 e_1 + BA de_1/dt.
- **syrope** (``SYROPE:file|EA_Dc|EA_D_Lm`` with the SYROPE IC section; ``Line::setWorkingCurve``):
  the original working curve (OWC, a table) and the working curve below the highest mean tension
  T_max seen so far, x = eps_min + (eps_max - eps_min) xi, y = T_max f(xi) (linear, quadratic or
  exponential f), each with its slow strain z = x - ln(1 + beta y / alpha) / beta;
  T_mean = y(z = e_1) and (BA + BA_D) de_1/dt = (e - x(T_mean)) (alpha + beta T_mean) + BA_D de/dt.

Tables hold at most ``MAX_ROWS`` rows (MoorDyn-C: 30, ``nCoef``).
"""

import math
from dataclasses import dataclass

import numpy as np

from cablefem.errors import InputError

#: rows of a table the compiled parameters hold (MoorDyn-C holds 30)
MAX_ROWS = 32
#: rows of a SYROPE working curve, as MoorDyn-C tabulates it (``Line.hpp``, nEApointsWC)
WORKING_ROWS = 30
WORKING_CURVES = ("linear", "quadratic", "exp")
KINDS = ("table", "viscoelastic", "syrope")


def _numbers(values, key, what):
    """A finite float array from a list of numbers; InputError naming ``key`` otherwise."""
    if not isinstance(values, (list, tuple, np.ndarray)) or isinstance(values, str):
        raise InputError(f"expected an array of {what}", key=key)
    out = []
    for i, value in enumerate(values):
        if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
            raise InputError(f"expected a number, got {value!r}", key=f"{key}[{i}]")
        if not math.isfinite(float(value)):
            raise InputError(f"must be finite, got {value}", key=f"{key}[{i}]")
        out.append(float(value))
    return np.array(out)


@dataclass(frozen=True)
class Curve:
    """A piecewise-linear table y(x), rows (x, y) with x strictly increasing and y not decreasing,
    anchored at the origin: a first row at x > 0 gets (0, 0) before it (``x_name``/``y_name`` name
    the keys in errors). ``signed``: x may be negative (a damping table over negative rates)."""

    x: tuple
    y: tuple

    @classmethod
    def from_rows(cls, x, y, key, x_name="strain", y_name="tension", signed=False):
        """The checked curve of two arrays (errors name ``key``.x_name / y_name); a table that would
        make the law unstable or ambiguous is refused: fewer than 2 rows, more than MAX_ROWS, rows
        not strictly increasing in x, y not strictly increasing (a flat or falling piece is a zero or
        negative stiffness: no unique strain for a tension), a negative strain, a force at zero
        strain. ``signed`` (a damping table): x may be negative, y may stay level (a saturating
        damper), and the force at zero rate must be 0."""
        xs, ys = _numbers(x, f"{key}.{x_name}", x_name), _numbers(y, f"{key}.{y_name}", y_name)
        if len(xs) != len(ys):
            raise InputError(f"{len(xs)} {x_name} values but {len(ys)} {y_name} values: give one {y_name} "
                             f"per {x_name}", key=key)
        if len(xs) < 2:
            raise InputError(f"a table needs at least 2 rows, got {len(xs)}", key=key)
        for i in range(1, len(xs)):
            if xs[i] <= xs[i - 1]:
                raise InputError(f"not monotonic: {x_name} must strictly increase, but row {i} has "
                                 f"{xs[i]:g} after {xs[i - 1]:g}", key=f"{key}.{x_name}")
            if ys[i] < ys[i - 1] or (ys[i] == ys[i - 1] and not signed):
                raise InputError(f"not monotonic: {y_name} must strictly increase, but row {i} has {ys[i]:g} "
                                 f"after {ys[i - 1]:g} (a flat or falling piece is a zero or negative stiffness)",
                                 key=f"{key}.{y_name}")
        if ys[-1] <= ys[0]:
            raise InputError(f"the {y_name} never rises: a flat table carries no load", key=f"{key}.{y_name}")
        if not signed and xs[0] < 0.0:
            raise InputError(f"{x_name} must be >= 0 (a line carries no compression), got {xs[0]:g}",
                             key=f"{key}.{x_name}")
        if xs[-1] <= 0.0:
            raise InputError(f"{x_name} must reach above 0, got at most {xs[-1]:g}", key=f"{key}.{x_name}")
        if xs[0] == 0.0 and ys[0] != 0.0:
            raise InputError(f"the {y_name} at zero {x_name} must be 0, got {ys[0]:g}", key=f"{key}.{y_name}")
        if signed and xs[0] < 0.0 < xs[-1]:
            at_zero = float(np.interp(0.0, xs, ys))
            if abs(at_zero) > 1e-9 * float(np.max(np.abs(ys))):
                raise InputError(f"the {y_name} at zero {x_name} must be 0, the table gives {at_zero:g}",
                                 key=f"{key}.{y_name}")
        if xs[0] > 0.0:
            if ys[0] < 0.0:
                raise InputError(f"{y_name} must be >= 0 where {x_name} > 0, got {ys[0]:g}", key=f"{key}.{y_name}")
            xs, ys = np.append(0.0, xs), np.append(0.0, ys)
        if len(xs) > MAX_ROWS:
            raise InputError(f"at most {MAX_ROWS} rows (MoorDyn-C takes 30), got {len(xs)}: resample the curve",
                             key=key)
        return cls(tuple(xs.tolist()), tuple(ys.tolist()))

    @property
    def secant(self):
        """y / x at the last row: MoorDyn-C's stiffness of a line with an EA curve, for everything
        that needs one number (the start shape, step estimates, scales)."""
        return self.y[-1] / self.x[-1]

    def at(self, x):
        """y at x (array), straight from (0, 0) below the first row and with the last slope beyond."""
        xs, ys = np.asarray(self.x), np.asarray(self.y)
        x = np.asarray(x, dtype=float)
        k = np.clip(np.searchsorted(xs, x, side="right") - 1, 0, len(xs) - 2)
        slope = (ys[k + 1] - ys[k]) / (xs[k + 1] - xs[k])
        return ys[k] + slope * (x - xs[k])

    def inverse(self, y):
        """x at y (array) on the same law (y strictly increasing where it is inverted)."""
        xs, ys = np.asarray(self.x), np.asarray(self.y)
        y = np.asarray(y, dtype=float)
        k = np.clip(np.searchsorted(ys, y, side="right") - 1, 0, len(ys) - 2)
        slope = (xs[k + 1] - xs[k]) / (ys[k + 1] - ys[k])
        return xs[k] + slope * (y - ys[k])


@dataclass(frozen=True)
class Syrope:
    """The working-curve family of a SYROPE rope: ``form`` (linear, quadratic, exp) and MoorDyn-C's
    k1, k2 (ranges as MoorDyn-C checks them, ``read_syrope_working_curves``)."""

    form: str
    k1: float
    k2: float

    def __post_init__(self):
        if self.form not in WORKING_CURVES:
            raise InputError(f"expected one of {', '.join(WORKING_CURVES)}, got {self.form!r}", key="working_curve")
        k1, k2 = self.k1, self.k2
        if self.form == "linear" and k1 < 0.0:
            raise InputError(f"a linear working curve needs k1 >= 0, got {k1:g}", key="k1")
        if self.form == "quadratic" and not (0.0 <= k1 < 1.0 and 0.0 < k2 <= 1.0):
            raise InputError(f"a quadratic working curve needs 0 <= k1 < 1 and 0 < k2 <= 1, got k1 = {k1:g}, "
                             f"k2 = {k2:g}", key="k1")
        if self.form == "exp" and not (0.0 <= k1 < 1.0 and k2 > 0.0):
            raise InputError(f"an exponential working curve needs 0 <= k1 < 1 and k2 > 0, got k1 = {k1:g}, "
                             f"k2 = {k2:g}", key="k1")

    @property
    def code(self):
        """The compiled face's number of the form (1, 2, 3)."""
        return WORKING_CURVES.index(self.form) + 1


@dataclass(frozen=True)
class AxialLaw:
    """A line type's axial law (module docstring). ``curve``: the EA table (table) or the original
    working curve (syrope); ``static_EA`` the static stiffness EA_s [N] (viscoelastic);
    ``dynamic_EA`` EA_Dc [N] and ``dynamic_slope`` EA_D_Lm [-] (viscoelastic, syrope); ``damping``
    BA [N s] or ``damping_curve`` (T_d [N] against de/dt [1/s]); ``dynamic_damping`` BA_D [N s];
    ``syrope`` the working-curve family."""

    kind: str
    curve: Curve | None = None
    static_EA: float = 0.0
    dynamic_EA: float = 0.0
    dynamic_slope: float = 0.0
    damping: float = 0.0
    damping_curve: Curve | None = None
    dynamic_damping: float = 0.0
    syrope: Syrope | None = None

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"unknown axial law {self.kind!r}")
        if self.kind in ("table", "syrope") and self.curve is None:
            raise InputError("needs a strain-tension table", key="EA")
        if self.kind == "viscoelastic":
            if not self.dynamic_EA > self.static_EA > 0.0:
                raise InputError(f"the dynamic stiffness must exceed the static EA = {self.static_EA:g} N (the "
                                 f"slow spring EA_d EA / (EA_d - EA) would be infinite or negative), got "
                                 f"{self.dynamic_EA:g} N", key="EA_dynamic")
        if self.kind == "syrope":
            if self.syrope is None:
                raise InputError("a SYROPE line type needs its working curves", key="syrope")
            if not self.dynamic_EA > 0.0:
                raise InputError(f"SYROPE needs EA_dynamic > 0 (MoorDyn's EA_Dc), got {self.dynamic_EA:g}",
                                 key="EA_dynamic")
            slow = self.slow_strain(np.asarray(self.curve.x), np.asarray(self.curve.y))
            if np.any(np.diff(slow) <= 0.0):
                raise InputError("the slow strains of the original working curve (strain - ln(1 + EA_dynamic_slope "
                                 "T / EA_dynamic) / EA_dynamic_slope) do not strictly increase: the curve is "
                                 "stiffer than the dynamic stiffness somewhere (MoorDyn-C refuses it too)", key="EA")
        if self.dynamic_slope < 0.0:
            raise InputError(f"must be >= 0, got {self.dynamic_slope:g}", key="EA_dynamic_slope")
        for name in ("damping", "dynamic_damping"):
            if getattr(self, name) < 0.0:
                raise InputError(f"must be >= 0, got {getattr(self, name):g}", key=name)
        if self.kind != "table" and self.damping + self.dynamic_damping <= 0.0:
            raise InputError("a viscoelastic rope needs BA > 0 or BA_dynamic > 0: its slow strain relaxes "
                             "through them", key="BA")

    @property
    def reference_EA(self):
        """One stiffness [N] for what needs a number: the static EA, or a table's last secant (as
        MoorDyn-C initialises a line with an EA curve)."""
        return self.static_EA if self.kind == "viscoelastic" else self.curve.secant

    def slow_strain(self, x, y):
        """SYROPE's slow strain z = x - ln(1 + beta y / alpha) / beta of rows (x, y) (beta -> 0: x - y / alpha)."""
        alpha, beta = self.dynamic_EA, self.dynamic_slope
        if beta == 0.0:
            return x - y / alpha
        return x - np.log1p(beta * y / alpha) / beta

    def working_curve(self, peak):
        """SYROPE's working curve below the highest mean tension ``peak`` [N]: rows (x, y, z), each
        (WORKING_ROWS,), tabulated at even xi as MoorDyn-C does (``Line::setWorkingCurve``)."""
        curve, form, k1, k2 = self.curve, self.syrope.form, self.syrope.k1, self.syrope.k2
        eps_max = float(curve.inverse(peak))
        eps_0 = curve.x[0]
        eps_min = eps_max - peak / k1 if form == "linear" and k1 >= 1.0 else eps_0 + k1 * (eps_max - eps_0)
        xi = np.linspace(0.0, 1.0, WORKING_ROWS)
        x = eps_min + (eps_max - eps_min) * xi
        if form == "linear":
            y = peak * xi
        elif form == "quadratic":
            y = peak * xi * (k2 * xi + (1.0 - k2))
        else:
            y = peak * (1.0 - np.exp(k2 * xi)) / (1.0 - np.exp(k2))
        return x, y, self.slow_strain(x, y)

    def check_peak(self, peak, key):
        """Refuse a highest mean tension T_max outside the original working curve (MoorDyn-C does)."""
        if not 0.0 < peak <= self.curve.y[-1]:
            raise InputError(f"Tmax = {peak:g} N is outside the original working curve (0, {self.curve.y[-1]:g}] N",
                             key=key)
        x, y, z = self.working_curve(peak)
        if np.any(np.diff(z) <= 0.0):
            raise InputError(f"the working curve below Tmax = {peak:g} N is stiffer than the dynamic stiffness "
                             "somewhere: its slow strains do not increase", key=key)
