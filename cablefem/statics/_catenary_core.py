"""Shape functions and solvers behind ``cablefem.statics.catenary`` (private).

A static line with its anchor at the origin lies straight along a seabed
plane of inclination alpha from the anchor to the touchdown point and hangs
from there to the fairlead as an elastic catenary (Jonkman 2007, Eq. 2-1 to
2-38; the MoorPy and MAP++ docs state the same equations). Along the lying
part the tension falls towards the anchor by g = w (sin alpha + mu cos alpha)
per unit unstretched length; where it would turn negative the line is slack
and either stays where it lies (friction holds it: mu > 0 and mu >= tan
alpha) or slides down into a pile at the anchor (a frictionless upslope).

The unknowns are the fairlead force components (H, V). Every formula is
written so that no difference of nearly equal numbers is formed: asinh and
sqrt differences are rewritten with the identities in ``hanging_offset``.
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from cablefem.errors import ConvergenceError


@dataclass(frozen=True)
class Setting:
    """What the solvers need: weight w [N/m], length L [m], EA [N] (inf allowed), seabed plane and friction."""

    weight: float
    length: float
    EA: float
    slope: float  # alpha [rad]; meaningless without a seabed
    friction: float
    seabed: bool

    @property
    def compliance(self):
        """1/EA [1/N], 0 for an inextensible line."""
        return 1.0 / self.EA

    @property
    def gradient(self):
        """Fall of the lying tension per unit unstretched length towards the anchor [N/m]."""
        return self.weight * (math.sin(self.slope) + self.friction * math.cos(self.slope))

    @property
    def slack_held(self):
        """True when a slack lying stretch stays straight (friction holds it) rather than piling at the anchor."""
        return self.friction > 0.0 and self.gradient >= 0.0 and self.friction >= math.tan(self.slope)


def asinh_difference(H, V0, V1):
    """asinh(V1/H) - asinh(V0/H) without cancellation, H > 0; arrays broadcast."""
    T0, T1 = np.hypot(H, V0), np.hypot(H, V1)
    same = V0 * V1 >= 0.0
    den = V1 * T0 + V0 * T1
    # sinh(A - B) = sinh A cosh B - cosh A sinh B; for same signs rationalised.
    with np.errstate(divide="ignore", invalid="ignore"):
        arg_same = np.where(den != 0.0, (V1 - V0) * (V1 + V0) / np.where(den != 0.0, den, 1.0),
                            (V1 - V0) / H)
        arg_opposite = (V1 / H) * (T0 / H) - (V0 / H) * (T1 / H)
    return np.arcsinh(np.where(same, arg_same, arg_opposite))


def hanging_offset(H, V0, length, weight, compliance):
    """(dx, dz) [m] across a hanging stretch of unstretched length(s) [m] that starts with forces (H, V0) [N]."""
    length = np.asarray(length, dtype=float)
    V1 = V0 + weight * length
    T0, T1 = np.hypot(H, V0), np.hypot(H, V1)
    with np.errstate(divide="ignore", invalid="ignore"):
        # (T1 - T0)/w = L (V0 + V1)/(T0 + T1), since T1^2 - T0^2 = w L (V0 + V1)
        dz = np.where(T0 + T1 > 0.0, length * (V0 + V1) / np.where(T0 + T1 > 0.0, T0 + T1, 1.0), 0.0)
    dx = H / weight * asinh_difference(H, V0, V1) if H > 0.0 else np.zeros_like(length)
    dx = dx + H * length * compliance
    dz = dz + (V0 * length + 0.5 * weight * length**2) * compliance
    return dx, dz


def hanging_jacobian(H, V0, V1, weight, compliance):
    """Partials of (dx, dz) of a hanging stretch w.r.t. (H, V0, V1) at fixed end forces, as a 2x3 array."""
    T0, T1 = math.hypot(H, V0), math.hypot(H, V1)
    A = float(asinh_difference(H, V0, V1))
    w, c = weight, compliance
    return np.array([
        [(A - V1 / T1 + V0 / T0) / w + (V1 - V0) / w * c, -H / (w * T0) - H / w * c, H / (w * T1) + H / w * c],
        [(H / T1 - H / T0) / w, -V0 / (w * T0) - V0 / w * c, V1 / (w * T1) + V1 / w * c],
    ])


@dataclass(frozen=True)
class LyingPart:
    """The straight stretch on the seabed plane: s in [0, slack) slack, [slack, length) tensioned [m].

    ``touchdown_tension`` [N] is the tension at s = length. A slack stretch lies
    straight and unstretched when ``held``, else it is piled at the anchor.
    """

    length: float
    touchdown_tension: float
    slack: float
    held: bool

    @property
    def taut(self):
        """Unstretched length of the tensioned stretch [m]."""
        return self.length - self.slack

    def tension(self, s, gradient):
        """Tension [N] at unstretched arc lengths s (n,) within the lying part."""
        t = np.clip(np.asarray(s, dtype=float) - self.slack, 0.0, self.taut)
        low = self.touchdown_tension - gradient * self.taut
        return np.where(np.asarray(s) < self.slack, 0.0, low + gradient * t)

    def distance(self, s, gradient, compliance):
        """Stretched distance [m] along the plane from the anchor at unstretched arc lengths s (n,)."""
        s = np.asarray(s, dtype=float)
        t = np.clip(s - self.slack, 0.0, self.taut)
        low = self.touchdown_tension - gradient * self.taut
        start = np.minimum(s, self.slack) if self.held else 0.0
        return start + t + (low * t + 0.5 * gradient * t**2) * compliance


def lying_part(length, touchdown_tension, setting):
    """The lying part of unstretched ``length`` [m] with ``touchdown_tension`` [N] at its upper end."""
    g = setting.gradient
    if g > 0.0 and touchdown_tension < g * length:
        return LyingPart(length, touchdown_tension, length - touchdown_tension / g, setting.slack_held)
    return LyingPart(length, touchdown_tension, 0.0, True)


def lying_distance_jacobian(part, setting):
    """(D, dD/dlength, dD/dtouchdown_tension) of a lying part, D its stretched extent [m]."""
    g, c, T = setting.gradient, setting.compliance, part.touchdown_tension
    D = float(part.distance(part.length, g, c))
    if part.slack > 0.0 and part.held:  # D = length + T^2/(2 g EA)
        return D, 1.0, T / g * c
    if part.slack > 0.0:  # piled: D = T/g + T^2/(2 g EA), whatever the length
        return D, 0.0, 1.0 / g + T / g * c
    return D, 1.0 + (T - g * part.length) * c, part.length * c


def fairlead_offset(H, V, setting, with_jacobian=False):
    """Fairlead position (x, z) [m] for fairlead forces (H, V) [N], H > 0, and optionally d(x,z)/d(H,V)."""
    w, L, c = setting.weight, setting.length, setting.compliance
    ca, sa = math.cos(setting.slope), math.sin(setting.slope)
    ta = sa / ca
    if setting.seabed and V - w * L < H * ta:  # touchdown: V0 = H tan(alpha)
        V0 = H * ta
        hang = max((V - V0) / w, 0.0)
        part = lying_part(L - hang, H / ca, setting)
        D, dD_dlength, dD_dtension = lying_distance_jacobian(part, setting)
        dx, dz = hanging_offset(H, V0, hang, w, c)
        x, z = D * ca + float(dx), D * sa + float(dz)
        if not with_jacobian:
            return x, z
        Jh = hanging_jacobian(H, V0, V0 + w * hang, w, c)
        dD_dH = dD_dlength * ta / w + dD_dtension / ca
        dD_dV = -dD_dlength / w
        J = np.array([[ca * dD_dH, ca * dD_dV], [sa * dD_dH, sa * dD_dV]])
        J[:, 0] += Jh[:, 0] + ta * Jh[:, 1]
        J[:, 1] += Jh[:, 2]
        return x, z, J
    dx, dz = hanging_offset(H, V - w * L, L, w, c)
    if not with_jacobian:
        return float(dx), float(dz)
    Jh = hanging_jacobian(H, V - w * L, V, w, c)
    return float(dx), float(dz), np.column_stack([Jh[:, 0], Jh[:, 1] + Jh[:, 2]])


def _touchdown_guess(X, Z, setting):
    """(H, V) [N] of an inextensible line on a flat bed in the plane's frame, or None if it would not touch down."""
    w, L, a = setting.weight, setting.length, setting.slope
    q, p = Z * math.cos(a) - X * math.sin(a), X * math.cos(a) + Z * math.sin(a)
    if not (0.0 < q < L and p > 0.0 and math.hypot(p, q) < L):
        return None

    def along(H):  # along-plane reach of a line touching down with horizontal tension H (Irvine 1981)
        return L - math.sqrt(q * q + 2.0 * q * H / w) + H / w * math.acosh(1.0 + w * q / H)

    low, high = 1e-12 * w * L, w * (L * L - q * q) / (2.0 * q)
    if along(high) <= p:
        return None
    for _ in range(60):  # bisection on log H: a guess needs no more
        mid = math.sqrt(low * high)
        low, high = (mid, high) if along(mid) < p else (low, mid)
    H = low * math.cos(a)
    return H, H * math.tan(a) + w * math.sqrt(q * q + 2.0 * q * low / w)


def initial_guess(X, Z, setting):
    """(H, V) [N] to start Newton from: Irvine's touchdown line, else Peyrot & Goulois (1979) as in FAST."""
    w, L = setting.weight, setting.length
    if setting.seabed:
        guess = _touchdown_guess(X, Z, setting)
        if guess is not None:
            return guess
    if L <= math.hypot(X, Z):
        lam = 0.2
    else:
        lam = math.sqrt(3.0 * ((L * L - Z * Z) / (X * X) - 1.0)) if X > 0 else 1e6
    lam = min(max(lam, 1e-3), 1e6)
    H, V = max(0.5 * w * X / lam, 1e-9 * w * L), 0.5 * w * (Z / math.tanh(lam) + L)
    chord = math.hypot(X, Z)
    if chord > L and setting.compliance > 0:  # taut: the stretch of a straight line carries the load
        T = (chord / L - 1.0) / setting.compliance
        H, V = max(H, T * X / chord), T * Z / chord + 0.5 * w * L
    return H, V


def newton(X, Z, setting, H, V, tolerance, max_iterations=100):
    """Newton with a backtracking line search; (H, V) [N] or None if it stalls.

    The unknowns are log H and, with a seabed, log of the virtual hanging length
    (V - H tan(alpha))/w, which is > 0 in every admissible state, so no step can
    leave them; without a seabed V itself.
    """
    w, L = setting.weight, setting.length
    ta = math.tan(setting.slope) if setting.seabed else 0.0

    def state(u, v):
        H = math.exp(u)
        V = H * ta + w * math.exp(v) if setting.seabed else v
        x, z, J = fairlead_offset(H, V, setting, with_jacobian=True)
        if setting.seabed:
            Ju = np.column_stack([H * (J[:, 0] + ta * J[:, 1]), (V - H * ta) * J[:, 1]])
        else:
            Ju = J * [H, 1.0]
        return (H, V), np.array([x - X, z - Z]), Ju

    u = math.log(H)
    v = math.log(max(V - H * ta, 1e-3 * w * L) / w) if setting.seabed else V
    limits = (2.0, 2.0 if setting.seabed else 2.0 * w * L)
    forces, r, J = state(u, v)
    for _ in range(max_iterations):
        norm = math.hypot(*r)
        if norm <= tolerance:
            return forces
        try:
            du, dv = np.linalg.solve(J, -r)
        except np.linalg.LinAlgError:
            return None
        if not (math.isfinite(du) and math.isfinite(dv)):
            return None
        step = min(1.0, limits[0] / max(abs(du), 1e-300), limits[1] / max(abs(dv), 1e-300))
        for _ in range(40):
            trial = state(u + step * du, v + step * dv)
            if math.hypot(*trial[1]) < (1.0 - 1e-4 * step) * norm:
                u, v = u + step * du, v + step * dv
                forces, r, J = trial
                break
            step *= 0.5
        else:
            return None
    return forces if math.hypot(*r) <= tolerance else None


def _bisect(f, low, high):
    """Root of f on [low, high] to machine precision (Brent)."""
    return brentq(f, low, high, xtol=1e-300, rtol=1e-15, maxiter=500)


def widen(f, value, step, sign):
    """Move ``value`` by ``step(value)`` until sign * f(value) >= 0; ValueError after 400 tries."""
    for _ in range(400):
        if sign * f(value) >= 0.0:
            return value
        value = step(value)
    raise ValueError("no bracket")


def _touchdown_bracketed(X, Z, setting):
    """(H, V) [N] of a touchdown solution by a 1-D search over H, or None if the line hangs free."""
    w, L, c, a = setting.weight, setting.length, setting.compliance, setting.slope
    ca, sa, ta = math.cos(a), math.sin(a), math.tan(a)
    q = Z * ca - X * sa

    def normal_rise(H, length):  # height gained normal to the plane by a hang leaving it tangentially
        dx, dz = hanging_offset(H, H * ta, length, w, c)
        return float(dz) * ca - float(dx) * sa

    low = 1e-12 * w * L
    if normal_rise(low, L) <= q:
        return None
    high = widen(lambda H: q - normal_rise(H, L), w * L, lambda H: 4.0 * H, 1.0)
    high = _bisect(lambda H: normal_rise(H, L) - q, low, high)

    def force(H):
        return H * ta + w * _bisect(lambda hang: normal_rise(H, hang) - q, 0.0, 2.0 * L)

    def mismatch(H):
        return fairlead_offset(H, force(H), setting)[0] - X

    if mismatch(high) < 0.0 or mismatch(low) > 0.0:
        return None
    H = _bisect(mismatch, low, high)
    return H, force(H)


def _hanging_bracketed(X, Z, setting):
    """(H, V) [N] of the freely hanging line by a 1-D search over H, inner 1-D search over V."""
    w, L = setting.weight, setting.length
    free = Setting(w, L, setting.EA, 0.0, 0.0, False)

    def force(H):
        def rise(V):
            return fairlead_offset(H, V, free)[1] - Z
        high = widen(rise, w * L, lambda V: 2.0 * V, 1.0)
        return _bisect(rise, widen(rise, -w * L, lambda V: 2.0 * V, -1.0), high)

    def mismatch(H):
        return fairlead_offset(H, force(H), free)[0] - X

    high = widen(mismatch, w * L, lambda H: 4.0 * H, 1.0)
    H = _bisect(mismatch, 1e-12 * w * L, high)
    return H, force(H)


def bracketed(X, Z, setting):
    """(H, V) [N] by bracketed 1-D searches: a touchdown solution if one exists, else the hanging line."""
    found = _touchdown_bracketed(X, Z, setting) if setting.seabed else None
    return found or _hanging_bracketed(X, Z, setting)


def solve(X, Z, setting):
    """Fairlead forces (H, V) [N] with H > 0 that put the fairlead at (X, Z) [m]; ConvergenceError if none."""
    scale = max(setting.length, math.hypot(X, Z))
    tolerance = 1e-13 * scale
    H, V = initial_guess(X, Z, setting)
    found = newton(X, Z, setting, H, V, tolerance)
    if found is None:
        try:
            found = bracketed(X, Z, setting)
            found = newton(X, Z, setting, *found, tolerance, max_iterations=5) or found
        except ValueError:  # no sign change where one was expected: report how far the guess is
            found = (H, V)
    x, z = fairlead_offset(*found, setting)
    miss = math.hypot(x - X, z - Z)
    if not miss <= 1e-9 * scale:
        raise ConvergenceError(f"catenary missed the fairlead by {miss:.3g} m", residual=miss)
    return found
