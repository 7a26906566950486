"""One scalar root by Brent's method (Brent 1973, Ch. 4): scipy.optimize.brentq's algorithm in Python.

The catenary start shape and the touchdown report need a scalar root a few dozen times per solve;
importing scipy.optimize for it costs ~0.06 s of every ``cablefem`` command's start-up (it also
loads scipy.spatial and more; docs/architecture.md, "Start-up"). This is scipy's C routine
(``scipy/optimize/Zeros/brentq.c``, Charles Harris) with its Python wrapper's checks: the same
operations in the same order on IEEE doubles, so the same root bit for bit
(tests/test_roots.py holds it equal to scipy's on the catenary's functions and on random ones).
"""

import math

#: scipy's defaults: absolute and relative tolerance of the bracket, iteration cap
XTOL, RTOL, MAXITER = 2e-12, 4 * 2.220446049250313e-16, 100


def brentq(f, a, b, xtol=XTOL, rtol=RTOL, maxiter=MAXITER):
    """The root x of f in [a, b] (f(a) and f(b) of opposite signs) to xtol + rtol |x| [units of a]:
    ValueError when the signs agree or f is NaN, RuntimeError after ``maxiter`` iterations (as
    ``scipy.optimize.brentq``)."""
    if xtol <= 0:
        raise ValueError(f"xtol too small ({xtol:g} <= 0)")
    if rtol < RTOL:
        raise ValueError(f"rtol too small ({rtol:g} < {RTOL:g})")
    x_pre, x_cur = float(a), float(b)
    f_pre, f_cur = _value(f, x_pre), _value(f, x_cur)
    if f_pre == 0:
        return x_pre
    if f_cur == 0:
        return x_cur
    if _negative(f_pre) == _negative(f_cur):
        raise ValueError("f(a) and f(b) must have different signs")
    x_blk = f_blk = s_pre = s_cur = 0.0
    for _ in range(maxiter):
        if f_pre != 0 and f_cur != 0 and _negative(f_pre) != _negative(f_cur):
            x_blk, f_blk = x_pre, f_pre
            s_pre = s_cur = x_cur - x_pre
        if abs(f_blk) < abs(f_cur):  # the best estimate is x_cur: swap it with the bracket's end
            x_pre, x_cur, x_blk = x_cur, x_blk, x_cur
            f_pre, f_cur, f_blk = f_cur, f_blk, f_cur
        delta = (xtol + rtol * abs(x_cur)) / 2
        s_bis = (x_blk - x_cur) / 2
        if f_cur == 0 or abs(s_bis) < delta:
            return x_cur
        if abs(s_pre) > delta and abs(f_cur) < abs(f_pre):
            if x_pre == x_blk:  # interpolate (secant)
                s_try = -f_cur * (x_cur - x_pre) / (f_cur - f_pre)
            else:  # extrapolate (inverse quadratic)
                d_pre = (f_pre - f_cur) / (x_pre - x_cur)
                d_blk = (f_blk - f_cur) / (x_blk - x_cur)
                s_try = -f_cur * (f_blk * d_blk - f_pre * d_pre) / (d_blk * d_pre * (f_blk - f_pre))
            bound = abs(s_pre) if abs(s_pre) < 3 * abs(s_bis) - delta else 3 * abs(s_bis) - delta  # C's MIN
            if 2 * abs(s_try) < bound:  # a good short step
                s_pre, s_cur = s_cur, s_try
            else:
                s_pre = s_cur = s_bis
        else:
            s_pre = s_cur = s_bis
        x_pre, f_pre = x_cur, f_cur
        x_cur += s_cur if abs(s_cur) > delta else (delta if s_bis > 0 else -delta)
        f_cur = _value(f, x_cur)
    raise RuntimeError(f"Failed to converge after {maxiter} iterations.")


def _value(f, x):
    """f(x) as a float; ValueError if it is NaN."""
    value = float(f(x))
    if math.isnan(value):
        raise ValueError(f"The function value at x={x} is NaN; solver cannot continue.")
    return value


def _negative(value):
    """C's signbit: True for negative numbers and -0.0."""
    return math.copysign(1.0, value) < 0
