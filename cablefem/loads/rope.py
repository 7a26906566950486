"""Axial tension of a line type with a law of its own (``cablefem.model.axial``): a strain-tension
table with a constant or tabulated internal damping, MoorDyn-C's viscoelastic rope (static and
dynamic stiffness, the dynamic one constant or rising with the mean load) and its SYROPE working
curves. The other axial law, T = EA (e + beta de/dt), is ``cablefem.loads.tension``; a line type has
one or the other (the tension load carries EA = 0 on a rope's elements).

The internal force is the flux N = T t, T = T_e + T_d (an elastic and a damping part), as in
``cablefem.loads.tension``, with the same two slack laws (``damping_when_slack``) and the same
branch hold. The viscoelastic and SYROPE laws keep history per reduced point: the slow strain
e_1 and SYROPE's highest mean tension T_max, stepped by backward Euler over a step of h
(``State.inv_h``, the compiled context's ``inv_h``; ``cablefem.loads.rope_laws``), relaxed in
statics (1/h = 0), and the tension, for the samples of frames and the static JSON. Their
derivatives with respect to e and de/dt come from the implicit function theorem on the step's
equation R(e_1; e, de/dt) = 0. A history law evaluated in a run without a step size gives NaN, a
loud failure (the steps pass h with their factors).

The numpy face is the reference: the table by ``Curve.at``, the viscoelastic rope by a Newton
over all points at once, SYROPE point by point on ``AxialLaw.working_curve`` by bisection of R.
"""

import math

import numpy as np
from numba import njit

from cablefem.loads import LoadSpec, Terms, identity_like, outer, unit_tangent
from cablefem.loads._small import unit_divisor
from cablefem.loads.rope_laws import (SYROPE, TABLE, VISCOELASTIC, curve_at, damping, syrope, table, viscoelastic,
                                      working_rows)
from cablefem.loads.tension import SLACK_STIFFNESS
from cablefem.model.axial import MAX_ROWS, WORKING_ROWS

LAWS = {"table": TABLE, "viscoelastic": VISCOELASTIC, "syrope": SYROPE}
#: rows of SYROPE's curve at a point: the working curve, the original curve's rows above it, one more
CURVE_ROWS = WORKING_ROWS + MAX_ROWS + 1


class Rope:
    """The axial laws of a line's elements: ``laws`` (nel,) AxialLaw or None (an element the
    tension load carries), ``EA`` (nel,) their reference stiffness [N] (the slack stiffness, and the
    slope of a push), ``slack_damping`` (nel,) MoorDyn-C's slack law, ``initial`` (nel, 2) SYROPE's
    initial highest and present mean tension (Tmax0, Tmean0) [N] (0 elsewhere), ``rod`` (nel,) the
    elements that push (a line type that bends: its law carried into compression at the slope EA,
    as ``Tension``'s rod)."""

    name = "rope"
    rule = "reduced"

    def __init__(self, laws, EA, slack_damping=None, initial=None, rod=None):
        self.laws = list(laws)
        nel = len(self.laws)
        self.EA = np.asarray(EA, dtype=float)[:, None]
        self.slack_damping = np.zeros((nel, 1), bool) if slack_damping is None else \
            np.asarray(slack_damping, dtype=bool)[:, None]
        self.initial = np.zeros((nel, 2)) if initial is None else np.asarray(initial, dtype=float)
        self.kind = np.array([0 if law is None else LAWS[law.kind] for law in self.laws])
        self.compression = False  # the statics' start-up aid, as ``Tension.compression``
        self.rod = np.zeros((nel, 1), bool) if rod is None else np.asarray(rod, dtype=bool)[:, None]

    def initial_history(self, state):
        """SYROPE's initial condition: the highest mean tension Tmax0 and the slow strain of the mean
        tension Tmean0 on its working curve (MoorDyn-C's ``Line::initialize``); zero elsewhere (the
        viscoelastic rope's statics relax it)."""
        shape = state.dr.shape[1:]
        peak, slow = np.zeros(shape), np.zeros(shape)
        for i in np.flatnonzero(self.kind == SYROPE):
            x, y, z = self.laws[i].working_curve(self.initial[i, 0])
            peak[i], slow[i] = self.initial[i, 0], np.interp(self.initial[i, 1], y, z)
        return {"peak": peak, "slow": slow, "tension": np.zeros(shape)}

    # ------------------------------------------------------------------ the laws at the points
    def _parts(self, e, rate, state):
        """Elastic and damping tensions (Te, Td) and their derivatives in e and de/dt, each (nel, nq),
        the slow strain and the peak after the step."""
        nel, nq = e.shape
        out = {name: np.zeros((nel, nq)) for name in ("Te", "Td", "Te_e", "Te_r", "Td_e", "Td_r", "slow", "peak")}
        old = state.old["rope"] if state.old is not None else np.zeros((nel, nq), [("slow", "f8"), ("peak", "f8")])
        inv_h = float(getattr(state, "inv_h", 0.0))
        for k in np.unique(self.kind):
            rows = self.kind == k
            if k == TABLE:
                self._table(rows, e, rate, out)
            elif k == VISCOELASTIC:
                self._viscoelastic(rows, e, rate, old, inv_h, out)
            elif k == SYROPE:
                self._syrope(rows, e, rate, old, inv_h, out)
        return out

    def _table(self, rows, e, rate, out):
        for i in np.flatnonzero(rows):
            law = self.laws[i]
            x = np.asarray(law.curve.x)
            on = e[i] > 0.0
            out["Te"][i] = np.where(on, law.curve.at(e[i]), self.EA[i, 0] * e[i])
            k = np.clip(np.searchsorted(x, e[i], side="right") - 1, 0, len(x) - 2)
            slope = np.diff(law.curve.y)[k] / np.diff(x)[k]
            out["Te_e"][i] = np.where(on, slope, self.EA[i, 0])
            if law.damping_curve is None:
                out["Td"][i], out["Td_r"][i] = law.damping * rate[i], law.damping
                continue
            curve = law.damping_curve
            mirror = curve.x[0] >= 0.0
            r = np.abs(rate[i]) if mirror else rate[i]
            sign = np.sign(rate[i]) if mirror else 1.0
            xs = np.asarray(curve.x)
            k = np.clip(np.searchsorted(xs, r, side="right") - 1, 0, len(xs) - 2)
            out["Td"][i] = sign * curve.at(r)
            out["Td_r"][i] = (np.diff(curve.y)[k] / np.diff(xs)[k])

    def _viscoelastic(self, rows, e, rate, old, inv_h, out):
        idx = np.flatnonzero(rows)
        law = [self.laws[i] for i in idx]
        col = lambda values: np.array(values)[:, None]  # noqa: E731
        EA, alpha, beta = col([l.static_EA for l in law]), col([l.dynamic_EA for l in law]), \
            col([l.dynamic_slope for l in law])
        BA, BA_D = col([l.damping for l in law]), col([l.dynamic_damping for l in law])
        e, rate, e1n = e[idx], rate[idx], old["slow"][idx]
        c = (BA + BA_D) * inv_h

        def parts(e1):
            """EA_2, dEA_2/de_1 (the larger root of EA_2^2 - B EA_2 + alpha EA = 0), EA_1, dEA_1/de_1."""
            B = EA + alpha + beta * EA * e1
            root = np.sqrt(np.maximum(B * B - 4.0 * alpha * EA, 0.0))
            loaded = (e1 > 0.0) & (beta > 0.0)
            fast = np.where(loaded, 0.5 * (B + root), alpha)
            dfast = np.where(loaded, 0.5 * beta * EA * (1.0 + B / np.where(root > 0, root, 1.0)), 0.0)
            slow = fast * EA / (fast - EA)
            return fast, dfast, slow, -EA * EA / (fast - EA) ** 2 * dfast

        def residual(e1):
            fast, dfast, slow, dslow = parts(e1)
            R = c * (e1 - e1n) + slow * e1 - fast * (e - e1) - BA_D * rate
            return R, c + slow + dslow * e1 + fast + dfast * (e1 - e)

        # Newton from the committed slow strain, all points at once; R rises with e_1
        e1 = e1n.copy()
        for _ in range(100):
            R, dR = residual(e1)
            step = R / dR
            e1 = e1 - step
            if np.all(np.abs(step) <= 1e-14 * (np.abs(e1) + np.abs(e) + 1e-300)):
                break
        R, dR = residual(e1)
        fast, dfast, slow, dslow = parts(e1)
        de1_de, de1_dr = fast / dR, BA_D / dR
        dTm = slow + dslow * e1
        self._history_parts(idx, slow * e1, dTm, e1, e1n, BA, inv_h, de1_de, de1_dr, out)
        out["peak"][idx] = old["peak"][idx]

    def _syrope(self, rows, e, rate, old, inv_h, out):
        for i in np.flatnonzero(rows):
            law = self.laws[i]
            for g in range(e.shape[1]):
                peak = float(old["peak"][i, g])
                x, y, z = self.curve_rows(law, peak)
                c = (law.damping + law.dynamic_damping) * inv_h
                alpha, beta = law.dynamic_EA, law.dynamic_slope

                def curve(e1):  # T_m, x and their slopes in e_1: zero tension with x = e_1 below the curve
                    if e1 <= z[0]:
                        return 0.0, e1, 0.0, 1.0
                    k = min(np.searchsorted(z, e1, side="right") - 1, len(z) - 2)
                    sy, sx = (y[k + 1] - y[k]) / (z[k + 1] - z[k]), (x[k + 1] - x[k]) / (z[k + 1] - z[k])
                    return y[k] + sy * (e1 - z[k]), x[k] + sx * (e1 - z[k]), sy, sx

                if inv_h == 0.0:  # statics: the slow strain held, the fast part the dynamic spring's
                    e1 = float(old["slow"][i, g])
                    Tm, xm, _, _ = curve(e1)
                    share = law.damping / (law.damping + law.dynamic_damping)
                    at = (np.array([i]), np.array([g]))
                    out["Te"][at], out["slow"][at], out["peak"][i, g] = Tm, e1, peak
                    out["Td"][at] = share * ((e[i, g] - xm) * (alpha + beta * Tm) + law.dynamic_damping * rate[i, g])
                    out["Td_e"][at], out["Td_r"][at] = share * (alpha + beta * Tm), share * law.dynamic_damping
                    continue

                def residual(e1):
                    Tm, xm, _, _ = curve(e1)
                    return c * (e1 - old["slow"][i, g]) - (e[i, g] - xm) * (alpha + beta * Tm) \
                        - law.dynamic_damping * rate[i, g]

                lo, hi = min(z[0], e[i, g]) - 1.0, max(z[-1], e[i, g]) + 1.0
                while residual(hi) < 0.0:
                    hi += 2.0 * (hi - lo)
                for _ in range(200):  # bisection: R rises with e_1
                    mid = 0.5 * (lo + hi)
                    if residual(mid) > 0.0:
                        hi = mid
                    else:
                        lo = mid
                    if hi - lo <= 1e-16 * max(1.0, abs(mid)):
                        break
                e1 = 0.5 * (lo + hi)
                Tm, xm, sy, sx = curve(e1)
                dR = c + sx * (alpha + beta * Tm) - (e[i, g] - xm) * beta * sy
                e1 -= residual(e1) / dR  # one Newton step polishes the bisection's last digits
                Tm, xm, sy, sx = curve(e1)
                dR = c + sx * (alpha + beta * Tm) - (e[i, g] - xm) * beta * sy
                de1_de, de1_dr = (alpha + beta * Tm) / dR, law.dynamic_damping / dR
                at = (np.array([i]), np.array([g]))
                self._history_parts(at, Tm, sy, e1, old["slow"][i, g], law.damping, inv_h, de1_de, de1_dr, out)
                out["peak"][i, g] = max(peak, Tm)

    @staticmethod
    def curve_rows(law, peak):
        """SYROPE's curve below and above ``peak``: the working curve's rows, then the original
        curve's rows above it, or one row at twice the peak on its last slope (x, y, z)."""
        x, y, z = law.working_curve(peak)
        ox, oy = np.asarray(law.curve.x), np.asarray(law.curve.y)
        oz = law.slow_strain(ox, oy)
        above = (oy > peak) & (oz > z[-1])
        if not above.any():
            top = np.array([2.0 * peak])
            ax = law.curve.inverse(top)
            return np.append(x, ax), np.append(y, top), np.append(z, law.slow_strain(ax, top))
        return np.append(x, ox[above]), np.append(y, oy[above]), np.append(z, oz[above])

    @staticmethod
    def _history_parts(at, Tm, dTm, e1, e1n, BA, inv_h, de1_de, de1_dr, out):
        """The elastic part T_m and the damping part BA de_1/dt of a law with a slow strain."""
        out["Te"][at], out["Te_e"][at], out["Te_r"][at] = Tm, dTm * de1_de, dTm * de1_dr
        out["Td"][at] = BA * (e1 - e1n) * inv_h
        out["Td_e"][at], out["Td_r"][at] = BA * inv_h * de1_de, BA * inv_h * de1_dr
        out["slow"][at] = e1

    # ------------------------------------------------------------------ the load
    def tension(self, state):
        """T [N], its derivatives in e and de/dt, the elastic and damping switches, each (nel, nq),
        and the trial history (slow, peak) of the points of ``state`` (reduced points)."""
        dr, dv = state.dr, state.dv
        t, stretch, divisor = unit_tangent(dr)
        e = stretch - 1.0
        rate = np.einsum("ceq,ceq->eq", t, dv) if dv is not None else np.zeros_like(e)
        p = self._parts(e, rate, state)
        active_law = (self.kind != 0)[:, None]
        extend = np.broadcast_to(self.rod | self.compression, e.shape)
        elastic_on = (e > 0.0) | extend
        Te = np.where(elastic_on, p["Te"], 0.0)
        total = Te + p["Td"]
        moordyn = self.slack_damping & ~extend
        active = extend | ((e > 0.0) & (total > 0.0))
        elastic = np.where(moordyn, elastic_on, active).astype(float)
        damped = np.where(moordyn, True, active).astype(float)
        T = np.where(moordyn, total, np.where(active, total, 0.0))
        dT_de = elastic * p["Te_e"] + damped * p["Td_e"]
        dT_dr = elastic * p["Te_r"] + damped * p["Td_r"]
        off = ~active_law
        for value in (T, dT_de, dT_dr, elastic):
            value[np.broadcast_to(off, value.shape)] = 0.0
        return T, dT_de, dT_dr, elastic, (t, divisor, rate), p

    def evaluate(self, state, jacobian=True):
        T, dT_de, dT_dr, elastic, (t, divisor, rate), p = self.tension(state)
        if state.new is not None:
            new = state.new["rope"]
            new["slow"], new["peak"], new["tension"] = p["slow"], p["peak"], T
        terms = Terms(flux=T * t)
        if not jacobian:
            return terms
        dv = state.dv if state.dv is not None else np.zeros_like(state.dr)
        dT_ddr = dT_de * t + dT_dr * (dv - rate * t) / divisor
        eye = identity_like(t)
        law = (self.kind != 0)[:, None].astype(float)
        terms.flux_dr = outer(t, dT_ddr) + (T / divisor) * (eye - outer(t, t)) \
            + (SLACK_STIFFNESS * self.EA * law * (1.0 - elastic)) * eye
        terms.flux_dv = outer(t, dT_dr * t)
        return terms

    def energy(self, state):
        """Strain energy density [J/m] (nel, nq) of the relaxed elastic part: int_0^e T de of the
        table, EA_s e^2 / 2 of the viscoelastic rope, the SYROPE curve of the committed peak."""
        e = np.linalg.norm(state.dr, axis=0) - 1.0
        out = np.where((e < 0.0) & (self.rod | self.compression), 0.5 * self.EA * e * e, 0.0)
        for i, law in enumerate(self.laws):
            if law is None:
                continue
            if law.kind == "viscoelastic":
                x, y = np.array([0.0, 1.0]), np.array([0.0, law.static_EA])
                out[i] += _integral(x, y, np.maximum(e[i], 0.0))
                continue
            if law.kind == "table":
                out[i] += _integral(np.asarray(law.curve.x), np.asarray(law.curve.y), np.maximum(e[i], 0.0))
                continue
            for g in range(e.shape[1]):
                out[i, g] += self._syrope_energy(i, law, state.old["rope"][i, g], e[i, g])
        return out

    def _syrope_energy(self, i, law, old, e):
        """The statics' SYROPE energy at strain e of a point with committed history ``old``: T =
        T_m + s S (e - x) with the slow strain held (S = alpha + beta T_m, s = BA / (BA + BA_D)),
        under the element's slack law (no tension for e <= 0 or T <= 0; MoorDyn-C's: T_m for e > 0
        and the fast part always; pushing: both always)."""
        x, y, z = self.curve_rows(law, float(old["peak"]))
        slow = float(old["slow"])
        Tm = float(np.interp(slow, z, y)) if slow > z[0] else 0.0
        xm = float(np.interp(slow, z, x)) if slow > z[0] else slow
        b = law.damping / (law.damping + law.dynamic_damping) * (law.dynamic_EA + law.dynamic_slope * Tm)
        if self.compression or self.rod[i, 0]:
            return Tm * e + 0.5 * b * (e - xm) ** 2 - 0.5 * b * xm ** 2
        if self.slack_damping[i, 0]:
            return Tm * max(e, 0.0) + 0.5 * b * (e - xm) ** 2 - 0.5 * b * xm ** 2
        a = Tm - b * xm  # T = a + b e where positive, for e > 0
        start = max(0.0, -a / b)
        return 0.0 if e <= start else (a * (e - start) + 0.5 * b * (e * e - start * start))

    def params(self):
        """The compiled face's parameters per element (``SPEC.params``)."""
        nel = len(self.laws)
        record = {name: np.zeros((nel,) + (tuple(shape[0]) if shape else ())) for name, _, *shape in PARAMS}
        record["law"] = self.kind.astype(np.uint8)
        record["EA"] = self.EA[:, 0]
        record["pushes"] = self.rod[:, 0] | self.compression
        record["slack_damping"] = self.slack_damping[:, 0]
        for i, law in enumerate(self.laws):
            if law is None:
                continue
            if law.curve is not None:
                n = len(law.curve.x)
                record["rows"][i] = n
                record["x"][i, :n], record["y"][i, :n] = law.curve.x, law.curve.y
                if law.kind == "syrope":
                    record["z"][i, :n] = law.slow_strain(np.asarray(law.curve.x), np.asarray(law.curve.y))
            if law.damping_curve is not None:
                n = len(law.damping_curve.x)
                record["damping_rows"][i] = n
                record["rate"][i, :n], record["force"][i, :n] = law.damping_curve.x, law.damping_curve.y
                record["mirror"][i] = law.damping_curve.x[0] >= 0.0
            record["BA"][i], record["BA_D"][i] = law.damping, law.dynamic_damping
            record["static"][i] = law.static_EA
            record["alpha"][i], record["beta"][i] = law.dynamic_EA, law.dynamic_slope
            if law.syrope is not None:
                record["form"][i], record["k1"][i], record["k2"][i] = law.syrope.code, law.syrope.k1, law.syrope.k2
        return {name: record[name].astype(dtype) for name, dtype, *_ in PARAMS}


def _integral(x, y, e):
    """int_x[0]^e y dx of the piecewise-linear y(x) through rows x, y (y[0] = 0), carried on beyond
    the last row with its slope; 0 below x[0] (e array)."""
    e = np.maximum(np.asarray(e, dtype=float), x[0])
    areas = np.concatenate([[0.0], np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(x))])
    k = np.clip(np.searchsorted(x, e, side="right") - 1, 0, len(x) - 2)
    slope = (y[k + 1] - y[k]) / (x[k + 1] - x[k])
    d = e - x[k]
    return areas[k] + y[k] * d + 0.5 * slope * d * d


@njit(cache=True, _nrt=False)
def rope_point(ctx, p, old, new, state, hold, out):
    """The compiled face: the flux N = T t at one reduced point and D = N_dr + v_x N_dv, with the
    line pulling (the law carried into compression at the slope EA) where Newton's taut correction
    holds it (``hold.rope.pull``); the trial history into ``new.rope``."""
    q = p.rope
    if not q.active or q.law == 0:  # an element the tension load carries
        return
    dr, dv, N, D = ctx.dr, ctx.dv, out.N, out.D
    stretch = np.sqrt(dr[0] * dr[0] + dr[1] * dr[1] + dr[2] * dr[2])
    divisor = unit_divisor(stretch)
    t0, t1, t2 = dr[0] / divisor, dr[1] / divisor, dr[2] / divisor
    e = stretch - 1.0
    rate = t0 * dv[0] + t1 * dv[1] + t2 * dv[2]
    extend = q.pushes or (ctx.held and hold.rope.pull)
    elastic_on = e > 0.0 or extend
    slow, peak = old.rope.slow, old.rope.peak
    xm, share = 0.0, 0.0
    if q.law == TABLE:
        if e > 0.0:
            Te, Te_e = table(q.x, q.y, q.rows, e)
        else:
            Te, Te_e = q.EA * e, q.EA
        Te_r, Td_e = 0.0, 0.0
        Td, Td_r = damping(q, rate)
    else:
        inv_h = ctx.inv_h
        c = (q.BA + q.BA_D) * inv_h
        if q.law == VISCOELASTIC:
            e1, Tm, dTm, dR = viscoelastic(q, e, rate, old.rope.slow, c)
            fast = _fast(q, e1)
        else:
            s = ctx.rope
            m = working_rows(q, peak, s.x, s.y, s.z)
            if c == 0.0:  # statics: the slow strain held, the fast part the dynamic spring's
                Tm, xm, _, _ = curve_at(s.x, s.y, s.z, m, slow)
                share = q.BA / (q.BA + q.BA_D)
                fast = q.alpha + q.beta * Tm
                e1, dTm, dR = slow, 0.0, np.inf
            else:
                e1, Tm, dTm, dR = syrope(q, e, rate, slow, c, s.x, s.y, s.z, m)
                fast = q.alpha + q.beta * Tm
                peak = max(peak, Tm)
        if q.law == SYROPE and c == 0.0:
            Te, Te_e, Te_r = Tm, 0.0, 0.0
            Td, Td_e, Td_r = share * ((e - xm) * fast + q.BA_D * rate), share * fast, share * q.BA_D
        else:
            de1_de, de1_dr = fast / dR, q.BA_D / dR
            Te, Te_e, Te_r = Tm, dTm * de1_de, dTm * de1_dr
            Td, Td_e, Td_r = q.BA * (e1 - old.rope.slow) * inv_h, q.BA * inv_h * de1_de, q.BA * inv_h * de1_dr
        slow = e1
    if not elastic_on:
        Te = 0.0
    if q.slack_damping and not extend:  # MoorDyn-C: the damping part acts in slack segments too
        elastic = 1.0 if elastic_on else 0.0
        damped = 1.0
        T = elastic * Te + Td
        taut = e > 0.0
    else:
        active = extend or (e > 0.0 and Te + Td > 0.0)
        elastic = damped = 1.0 if active else 0.0
        T = Te + Td if active else 0.0
        taut = e > 0.0 and T > 0.0
    if q.law != TABLE and ctx.inv_h == 0.0 and ctx.v_x > 0.0:  # a run that gave no step size: fail loudly
        T = np.nan
    dT_de = elastic * Te_e + damped * Td_e
    dT_dr = elastic * Te_r + damped * Td_r
    N[0] += T * t0
    N[1] += T * t1
    N[2] += T * t2
    if ctx.jac:
        t = (t0, t1, t2)
        for i in range(3):
            for j in range(3):
                delta = 1.0 if i == j else 0.0
                D[i, j] += t[i] * (dT_de * t[j] + dT_dr * (dv[j] - rate * t[j]) / divisor) \
                    + (T / divisor) * (delta - t[i] * t[j]) + SLACK_STIFFNESS * q.EA * (1.0 - elastic) * delta \
                    + ctx.v_x * dT_dr * t[i] * t[j]
    new.rope.slow, new.rope.peak, new.rope.tension = slow, peak, T
    state.rope.taut = taut


@njit(cache=True, _nrt=False)
def _fast(q, e1):
    """The viscoelastic rope's fast spring EA_2 [N] at the slow strain e_1 (``rope_laws._dynamic``)."""
    if q.beta == 0.0 or e1 <= 0.0:
        return q.alpha
    B = q.static + q.alpha + q.beta * q.static * e1
    return 0.5 * (B + math.sqrt(B * B - 4.0 * q.alpha * q.static))


@njit(cache=True, _nrt=False)
def rope_hold(base, state, hold, p, again):
    """Hold the taut branch where the trial pulled a point slack at the base taut (and, ``again``,
    where it is held already): Newton's taut correction, as ``tension.tension_hold``."""
    flag = (state.rope.taut and not base.rope.taut) or (again and hold.rope.pull)
    changed = flag != hold.rope.pull
    hold.rope.pull = flag
    return flag, changed


def build(setting):
    """A line with a line type of its own law gets the rope on those elements (the tension load
    carries EA = 0 there); a line type that bends pushes."""
    laws = setting.props.get("axial")
    if laws is None or all(law is None for law in laws):
        return None
    return Rope(laws, setting.props["EA"], setting.props["damping_when_slack"], setting.props["syrope_initial"],
                rod=setting.props["EI"] > 0.0)


#: the compiled parameters per element: the law, its reference EA, the two slack switches, the curve
#: (strain, tension, SYROPE's slow strain), the damping table, BA, BA_D, EA_s, EA_Dc (alpha),
#: EA_D_Lm (beta) and SYROPE's working-curve form, k1, k2
PARAMS = (("law", "u1"), ("EA", "f8"), ("pushes", "?"), ("slack_damping", "?"), ("rows", "i8"),
          ("x", "f8", (MAX_ROWS,)), ("y", "f8", (MAX_ROWS,)), ("z", "f8", (MAX_ROWS,)), ("damping_rows", "i8"),
          ("rate", "f8", (MAX_ROWS,)), ("force", "f8", (MAX_ROWS,)), ("mirror", "?"), ("BA", "f8"),
          ("BA_D", "f8"), ("static", "f8"), ("alpha", "f8"), ("beta", "f8"), ("form", "u1"), ("k1", "f8"),
          ("k2", "f8"))

SPEC = LoadSpec("rope", "reduced", PARAMS, rope_point, Rope,
                state=(("taut", "?"),), hold=(("pull", "?"),),
                history=(("slow", "f8"), ("peak", "f8"), ("tension", "f8")),
                scratch=(("x", "f8", (CURVE_ROWS,)), ("y", "f8", (CURVE_ROWS,)), ("z", "f8", (CURVE_ROWS,))),
                hold_rule=rope_hold, build=build)
