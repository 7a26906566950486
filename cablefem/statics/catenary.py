"""Closed-form static lines: the references the FEM starts from and is verified against.

``elastic_catenary`` is the elastic catenary with a flat seabed through the
anchor and Coulomb friction on the lying part (Jonkman 2007, the model of
FAST, MAP++ and MoorPy). ``inclined_catenary`` puts the anchor on a plane
seabed of any inclination (Batista & Perkovic 2019, the analytical
verification of desire2023 Sec. 3, Tables 2-4), inextensible or elastic.
Both solve the fairlead forces (H, V) by Newton from the Peyrot & Goulois
guess, with a bracketed 1-D search as fallback, to ~1e-13 of the line
length; the shape formulas are in ``cablefem.statics._catenary_core``.

Frame: 2-D vertical plane of the line, anchor (s = 0) at the origin, the
fairlead (s = L) at (X, Z), z up; s is unstretched arc length from the anchor;
tension T = EA * strain.

Batista & Perkovic, as desire2023 Sec. 3 uses them (``inclined_catenary_from_force``)
-------------------------------------------------------------------------------
H is the horizontal tension at the fairlead (B&P's "horizontal tension at the
suspension point"), with the fairlead held at a fixed height h above the
anchor and its horizontal span following from H. The line is inextensible and
frictionless, and the 15 deg seabed falls from the anchor towards the
fairlead: the anchor is upslope (slope = -15 deg here). Table 4's H column
only makes sense read in reverse order against T_A (our inference; the paper
does not say so). As printed, T_A = 4454 kN < H = 4.5 MN, which no line can
give: T >= H along the whole line, whatever the geometry, weight or slope
direction. Read with H reversed (3.5 MN -> 4454 kN, 3.7 -> 4637, 4.0 -> 4912,
4.3 -> 5188, 4.5 -> 5373), this model gives 4453.95, 4636.78, 4911.98,
5188.25 and 5372.97 kN: all five match to the printed kN, with a worst
relative error of 4.8e-5. That needs h = 83.766 m with the submerged weight
(835.4 - 1025 pi 0.3539^2/4) * 9.8 = 7198.8 N/m (h = 83.513 m at g = 9.81).
Table 4 fixes only a combination of w and h: the dry weight with h = 53.82 m
fits just as well. With H in the printed order, no model we tried comes
close: fixed h, fixed span, fixed depth under the fairlead or fixed height
above the plane; H at the fairlead or the anchor; dry or submerged weight;
either slope direction. The best misses by 19 %. The rising slope
(+15 deg) misses by 1.7 % even with H reversed.
"""

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from cablefem.statics import _catenary_core as core
from cablefem.errors import InputError

#: the largest strain a line may need to reach its fairlead before it is an input error
MAX_STRAIN = 0.2

#: regimes: "suspended" (no seabed contact), "touchdown" (lies from the anchor, hangs to the
#: fairlead), "lying" (all on the seabed), "slack" (H = 0: hangs vertically from the fairlead,
#: the surplus piled on the seabed below it), "vertical" (X = 0, no surplus: hangs straight)
REGIMES = ("suspended", "touchdown", "lying", "slack", "vertical")


@dataclass(frozen=True)
class CatenarySolution:
    """A solved static line: end forces [N], seabed contact [m], and its shape via ``profile``/``tension``."""

    fairlead_horizontal: float  # HF >= 0, the line pulls the fairlead towards the anchor
    fairlead_vertical: float  # VF, + = the line pulls the fairlead down
    anchor_horizontal: float  # HA, + = the line pulls the anchor towards the fairlead
    anchor_vertical: float  # VA, + = the line pulls the anchor up
    lying_length: float  # unstretched length on the seabed [m]
    touchdown_s: float | None  # arc length where the line leaves the seabed [m]
    regime: str
    horizontal_span: float
    vertical_span: float
    length: float
    EA: float
    weight: float
    slope: float = 0.0
    friction: float = 0.0
    seabed: bool = True
    lying: core.LyingPart | None = field(default=None, repr=False)

    @property
    def fairlead_tension(self):
        """Tension magnitude at the fairlead [N]."""
        return math.hypot(self.fairlead_horizontal, self.fairlead_vertical)

    @property
    def anchor_tension(self):
        """Tension magnitude at the anchor [N]."""
        return math.hypot(self.anchor_horizontal, self.anchor_vertical)

    @property
    def _setting(self):
        return core.Setting(self.weight, self.length, self.EA, self.slope, self.friction, self.seabed)

    @property
    def _hanging_start(self):
        """(s, x, z, V) where the hanging part starts: touchdown point, or the anchor when suspended."""
        V0 = self.fairlead_vertical - self.weight * (self.length - self.lying_length)
        if self.lying is None:
            return 0.0, 0.0, 0.0, V0
        d = float(self.lying.distance(self.lying.length, self._setting.gradient, 1.0 / self.EA))
        return self.lying_length, d * math.cos(self.slope), d * math.sin(self.slope), V0

    def profile(self, s):
        """Positions (x, z) [m], two arrays of shape (n,), at unstretched arc lengths s (n,) [m]."""
        s = np.atleast_1d(np.asarray(s, dtype=float))
        s0, x0, z0, V0 = self._hanging_start
        dx, dz = core.hanging_offset(self.fairlead_horizontal, V0, np.maximum(s - s0, 0.0),
                                     self.weight, 1.0 / self.EA)
        x, z = x0 + dx, z0 + dz
        if self.lying is not None:
            d = self.lying.distance(np.minimum(s, self.lying.length), self._setting.gradient, 1.0 / self.EA)
            on = s <= s0
            x = np.where(on, d * math.cos(self.slope), x)
            z = np.where(on, d * math.sin(self.slope), z)
        return x, z

    def tension(self, s):
        """Tension [N], shape (n,), at unstretched arc lengths s (n,) [m]."""
        s = np.atleast_1d(np.asarray(s, dtype=float))
        s0, _, _, V0 = self._hanging_start
        hanging = np.hypot(self.fairlead_horizontal, V0 + self.weight * np.maximum(s - s0, 0.0))
        if self.lying is None:
            return hanging
        lying = np.where(s <= self.lying.length, self.lying.tension(s, self._setting.gradient), 0.0)
        return np.where(s <= s0, lying, hanging)


def _number(value, key, low=None, strict=True, allow_inf=False):
    """A float checked for NaN, infinity and a lower bound; InputError naming ``key`` otherwise."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise InputError(f"expected a number, got {value!r}", key=key)
    value = float(value)
    if math.isnan(value) or (math.isinf(value) and not (allow_inf and value > 0)):
        raise InputError(f"must be finite, got {value}", key=key)
    if low is not None and (value <= low if strict else value < low):
        raise InputError(f"must be {'>' if strict else '>='} {low:g}, got {value:g}", key=key)
    return value


def _check_reach(X, Z, length, EA, seabed_normal_height):
    """InputError when the fairlead is below the seabed or beyond a sane stretch of the line."""
    if seabed_normal_height < -1e-12 * length:
        raise InputError(f"fairlead is {-seabed_normal_height:.6g} m below the seabed", key="vertical_span")
    chord = math.hypot(X, Z)
    on_seabed = seabed_normal_height <= 1e-12 * length
    if math.isinf(EA) and (chord > length or (chord == length and not on_seabed)):
        raise InputError(f"an inextensible line of {length:g} m cannot span {chord:.6g} m", key="length")
    if chord > (1.0 + MAX_STRAIN) * length:
        raise InputError(f"a line of {length:g} m would need {chord / length - 1:.0%} strain "
                         f"to reach a fairlead {chord:.6g} m away", key="length")


def _solution(X, Z, setting, H, V, regime, lying=None):
    """Assemble a CatenarySolution from fairlead forces (H, V) [N] and the lying part."""
    if lying is None:
        HA, VA = H, V - setting.weight * setting.length
        lying_length, touchdown = 0.0, None
    else:
        anchor = float(lying.tension(0.0, setting.gradient)) if lying.length > 0 else 0.0
        HA, VA = anchor * math.cos(setting.slope), anchor * math.sin(setting.slope)
        lying_length = setting.length - max(V - H * math.tan(setting.slope), 0.0) / setting.weight
        touchdown = lying_length
    return CatenarySolution(H, V, HA, VA, lying_length, touchdown, regime, X, Z, setting.length, setting.EA,
                            setting.weight, setting.slope, setting.friction, setting.seabed, lying)


def _vertical(X, Z, setting):
    """H = 0 and no surplus on the seabed: the line hangs straight (or folds, without seabed)."""
    w, L = setting.weight, setting.length

    def rise(V):
        return float(core.hanging_offset(0.0, V - w * L, L, w, setting.compliance)[1]) - Z

    high = core.widen(rise, 2.0 * w * L, lambda V: 2.0 * V, 1.0)
    low = w * L if setting.seabed else core.widen(rise, -w * L, lambda V: 2.0 * V, -1.0)
    V = brentq(rise, low, high, xtol=1e-300, rtol=1e-15) if rise(low) < 0.0 else low
    return _solution(X, Z, setting, 0.0, V, "vertical")


def _slack(X, Z, setting):
    """H = 0 with a surplus on the seabed, or None: hangs vertically, lies from the anchor to below the fairlead."""
    ca, ta, g, c = math.cos(setting.slope), math.tan(setting.slope), setting.gradient, setting.compliance
    if X > 0.0 and g > 0.0 and not setting.slack_held:
        return None  # a frictionless upslope never lies slack: it slides to the anchor
    height, along = Z - X * ta, X / ca
    hang = 2.0 * height / (1.0 + math.sqrt(1.0 + 2.0 * setting.weight * c * height))
    if g >= 0.0:
        lying = core.LyingPart(along, 0.0, along, True)
    else:
        taut = 2.0 * along / (1.0 + math.sqrt(1.0 + 2.0 * -g * c * along))
        lying = core.LyingPart(taut, 0.0, 0.0, True)
    if setting.length < hang + lying.length:
        return None
    return _solution(X, Z, setting, 0.0, setting.weight * hang, "slack" if hang > 0 else "lying", lying)


def _lying(X, Z, setting):
    """Fairlead on the seabed: the whole line lies along the plane, pulled straight or slack."""
    ca, sa, L = math.cos(setting.slope), math.sin(setting.slope), setting.length
    g, c = setting.gradient, setting.compliance
    along = math.hypot(X, Z)

    def reach(T):
        return float(core.lying_part(L, T, setting).distance(L, g, c)) - along

    if reach(0.0) >= 0.0:
        return _slack(X, Z, setting)
    high = core.widen(reach, max(abs(g), setting.weight) * L, lambda T: 2.0 * T, 1.0)
    T = brentq(reach, 0.0, high, xtol=1e-300, rtol=1e-15)
    return _solution(X, Z, setting, T * ca, T * sa, "lying", core.lying_part(L, T, setting))


def _solve(X, Z, setting):
    """Dispatch on the regime and solve; X, Z, setting already validated."""
    ca, sa = math.cos(setting.slope), math.sin(setting.slope)
    if setting.seabed and Z * ca - X * sa <= 1e-12 * setting.length:
        return _lying(X, Z, setting)
    if setting.seabed:
        slack = _slack(X, Z, setting)
        if slack is not None:
            return slack
    if X == 0.0:
        return _vertical(X, Z, setting)
    H, V = core.solve(X, Z, setting)
    if setting.seabed and V - setting.weight * setting.length < H * math.tan(setting.slope):
        hang = (V - H * math.tan(setting.slope)) / setting.weight
        return _solution(X, Z, setting, H, V, "touchdown", core.lying_part(setting.length - hang, H / ca, setting))
    return _solution(X, Z, setting, H, V, "suspended")


def elastic_catenary(horizontal_span, vertical_span, length, EA, weight, friction=0.0, seabed=True):
    """Elastic line, anchor (0, 0) to fairlead (X, Z) [m], on a flat seabed with friction (or free); forces [N]."""
    # seabed=True: the seabed z = 0 passes through the anchor; on the lying part the tension falls by
    # friction * w per metre towards the anchor and stays zero where it would turn negative (that
    # stretch lies slack, held by friction). seabed=False: no seabed, the sag may pass below the anchor.
    X = _number(horizontal_span, "horizontal_span", low=0.0, strict=False)
    Z = _number(vertical_span, "vertical_span")
    L = _number(length, "length", low=0.0)
    EA = _number(EA, "EA", low=0.0, allow_inf=True)
    w = _number(weight, "weight", low=0.0)
    mu = _number(friction, "friction", low=0.0, strict=False)
    if not isinstance(seabed, (bool, np.bool_)):
        raise InputError(f"expected true or false, got {seabed!r}", key="seabed")
    _check_reach(X, Z, L, EA, Z if seabed else math.inf)
    return _solve(X, Z, core.Setting(w, L, EA, 0.0, mu, bool(seabed)))


def inclined_catenary(horizontal_span, vertical_span, length, weight, slope, EA=np.inf):
    """Line, anchor (0, 0) to fairlead (X, Z) [m], on a frictionless plane seabed at ``slope`` [rad]; forces [N]."""
    # slope > 0: the seabed rises from the anchor towards the fairlead. The line lies straight along
    # the plane to the touchdown and leaves it tangentially, or hangs free when its anchor end is
    # steeper than the plane. A frictionless upslope cannot hold slack chain: it piles at the anchor.
    X = _number(horizontal_span, "horizontal_span", low=0.0, strict=False)
    Z = _number(vertical_span, "vertical_span")
    L = _number(length, "length", low=0.0)
    w = _number(weight, "weight", low=0.0)
    alpha = _number(slope, "slope")
    if abs(alpha) >= 0.5 * math.pi - 1e-9:
        raise InputError(f"must be within (-pi/2, pi/2), got {alpha:g}", key="slope")
    EA = _number(EA, "EA", low=0.0, allow_inf=True)
    _check_reach(X, Z, L, EA, Z * math.cos(alpha) - X * math.sin(alpha))
    return _solve(X, Z, core.Setting(w, L, EA, alpha, 0.0, True))


def inclined_catenary_from_force(horizontal_force, vertical_span, length, weight, slope, EA=np.inf):
    """``inclined_catenary`` with the span X [m] set by the fairlead's horizontal tension H [N] at height Z [m]."""
    # Batista & Perkovic's problem (see the module docstring for how desire2023 Sec. 3 uses it)
    H = _number(horizontal_force, "horizontal_force", low=0.0)
    Z = _number(vertical_span, "vertical_span")
    L = _number(length, "length", low=0.0)
    EA = _number(EA, "EA", low=0.0, allow_inf=True)
    alpha = _number(slope, "slope")
    reach = L if math.isinf(EA) else (1.0 + MAX_STRAIN) * L
    if abs(Z) >= reach:
        raise InputError(f"a line of {L:g} m cannot reach a fairlead {Z:g} m above the anchor", key="vertical_span")
    far = math.sqrt(reach**2 - Z**2) * (1.0 - 1e-12)
    if alpha > 0.0:
        far = min(far, Z / math.tan(alpha))  # the fairlead stays on or above the seabed

    def pull(X):
        return inclined_catenary(X, Z, L, weight, alpha, EA).fairlead_horizontal - H

    if far <= 0.0 or pull(far) < 0.0:
        raise InputError(f"the line cannot carry {H:g} N at a fairlead {Z:g} m above the anchor",
                         key="horizontal_force")
    X = brentq(pull, 0.0, far, xtol=1e-13 * L, rtol=1e-15) if pull(0.0) < 0.0 else 0.0
    return inclined_catenary(X, Z, L, weight, alpha, EA)
