"""The loads at one quadrature point, compiled (numba): the force per unit length and its
Jacobian blocks of weight, seabed contact with friction, drag and added mass
(``_point_loads``), and the axial tension flux with its Jacobian (``_tension``).

These are the physics of ``cablefem.loads`` line for line (same equations, same Jacobians),
written for one point at a time on 3 x 3 blocks; ``cablefem.fused`` loops them over elements and
quadrature points into the step residual and banded tangent, and ``tests/test_fused.py`` holds
both equal to the reference assembly to round-off. They run with numba's reference counting
off (``_nrt=False``: they allocate nothing; see ``cablefem.fused``). Where the branch
corrections of Newton hold a point's loads on a branch, ``_point_loads`` evaluates that branch
(``cablefem.branches``).
"""

import numpy as np
from numba import njit

from .branches import CLOSING, DAMPER_ON, DAMPERS, STICK, TOUCH_ON, TOUCHES, TOUCHING
from .loads.contact import DEGENERATE_AXIS
from .loads.tension import SLACK_STIFFNESS


@njit(cache=True, inline="always", _nrt=False)
def _add_outer(M, a, b, scale):
    """M += scale a b^T (3 x 3)."""
    for i in range(3):
        for j in range(3):
            M[i, j] += scale * a[i] * b[j]


@njit(cache=True, inline="always", _nrt=False)
def _add_matmul(M, A, B, scale):
    """M += scale A B (3 x 3)."""
    for i in range(3):
        for j in range(3):
            acc = 0.0
            for k in range(3):
                acc += A[i, k] * B[k, j]
            M[i, j] += scale * acc


@njit(cache=True, inline="always", _nrt=False)
def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(cache=True, _nrt=False)
def _submerged(z, diameter):
    """Submerged fraction of the cross-section centred at height z and d/dz of it
    (cablefem.loads.gravity.submerged_fraction)."""
    if z <= -0.5 * diameter:
        return 1.0, 0.0
    if z >= 0.5 * diameter:
        return 0.0, 0.0
    h = 0.5 * diameter - z
    theta = 2.0 * np.arccos(min(max(1.0 - 2.0 * h / diameter, -1.0), 1.0))
    width = 8.0 * np.sqrt(max(h * (diameter - h), 0.0)) / (np.pi * diameter * diameter)
    return (theta - np.sin(theta)) / (2.0 * np.pi), -width


@njit(cache=True, _nrt=False)
def _saturation(w, vc, scale, phi, dphi, stick):
    """phi(w) and dphi/dw of the saturated-damping law (cablefem.loads.friction.saturation);
    with ``stick``, of its ramp (the sticking branch) at any speed."""
    speed = np.sqrt(_dot(w, w))
    ramp = speed < vc or stick
    gain = scale / vc if ramp else 1.0 / speed
    for a in range(3):
        phi[a] = gain * w[a]
        for b in range(3):
            dphi[a, b] = (gain if a == b else 0.0) - (0.0 if ramp else w[a] * w[b] / speed ** 3)


@njit(cache=True, _nrt=False)
def _point_loads(r, dr, v, acc, p, bed, gap, n, grad_gap, dn, curved, v_x, a_x, jac, f, Ab, Bb, M, u, hold,
                 slip):
    """Force f (3,) per unit length at one full quadrature point and the blocks A = -(f_r +
    v_x f_v + a_x f_a), B = -(f_dr) of the weak form (loads: weight, contact with friction,
    drag, added mass; p holds the element's parameters, bed the friction law; M (16, 3, 3)
    and u (16, 3) are scratch; ``curved``: the normal n varies, with gradient dn, which a plane's
    does not: its terms are skipped). ``hold``: branches held whatever the state (the branch
    corrections of ``cablefem.dynamics.Integrator._newton``): STICK friction on its ramp,
    TOUCH_ON / TOUCH_OFF the seabed spring acting or not (on: -k d_G also above the seabed),
    DAMPER_ON / DAMPER_OFF its damper acting or not; slip (3,) receives the slip velocity w (zero
    off the seabed or without friction). Returns the contact state (TOUCHING, CLOSING bits)."""
    dry, buoy, k, c, drag_n, drag_t, cur0, cur1, cur2, am_n, am_t, diameter = p
    model, mu, mu_a, mu_t, fscale, vc = bed
    submerged, dsubmerged = _submerged(r[2], diameter)  # weight and buoyancy (loads.gravity)
    f[0] = 0.0
    f[1] = 0.0
    f[2] = -(dry - buoy * submerged)
    if jac:
        Ab[:, :] = 0.0
        Bb[:, :] = 0.0
        Ab[2, 2] = -buoy * dsubmerged
    eye, P, tmp, dphi, dphia, dF_dw, dF_dq, dw_dr, In, dq_dp, dp_dn, dg = (
        M[0], M[1], M[2], M[3], M[4], M[5], M[6], M[7], M[8], M[9], M[10], M[11])
    t, w, phi, phia, q, dp_dr, dp_dv, dN, un, per, pv, va = (
        u[0], u[1], u[2], u[3], u[4], u[5], u[6], u[7], u[8], u[9], u[10], u[11])
    stretch = np.sqrt(_dot(dr, dr))
    divisor = stretch if stretch > 0.0 else np.inf  # coincident points: t = 0 (loads.unit_tangent)
    for i in range(3):
        t[i] = dr[i] / divisor
    if jac:
        for i in range(3):
            for j in range(3):
                eye[i, j] = 1.0 if i == j else 0.0
                P[i, j] = eye[i, j] - t[i] * t[j]
    # seabed contact (desire2023 Eq. 11) and friction (Eq. 12; housner2022 Eq. 5-13)
    touching = gap < 0.0 if (hold & TOUCHES) == 0 else (hold & TOUCH_ON) != 0
    pressure = -k * gap if touching else 0.0
    vn = _dot(v, n)
    closing = touching and c > 0.0 and ((hold & DAMPER_ON) != 0 if (hold & DAMPERS) != 0 else vn < 0.0)
    stick = (hold & STICK) != 0
    if closing:
        pressure -= c * vn
    for i in range(3):
        f[i] += pressure * n[i]
    if jac:
        on = (1.0 if gap <= 0.0 else 0.0) if (hold & TOUCHES) == 0 else (1.0 if touching else 0.0)
        for j in range(3):
            dp_dr[j] = -k * on * grad_gap[j]
            dp_dv[j] = 0.0
        if closing:
            for j in range(3):
                if curved:
                    dp_dr[j] -= c * (v[0] * dn[0, j] + v[1] * dn[1, j] + v[2] * dn[2, j])
                dp_dv[j] = -c * n[j]
            _add_outer(Ab, n, dp_dv, -v_x)
        _add_outer(Ab, n, dp_dr, -1.0)
        if curved:
            for i in range(3):
                for j in range(3):
                    Ab[i, j] -= pressure * dn[i, j]
    slip[0], slip[1], slip[2] = 0.0, 0.0, 0.0
    rubbing = touching and gap < 0.0  # a point held on the seabed's spring above it has no friction
    if model == 1 and rubbing:  # isotropic: dphi = gain I - ramp_off w w^T / |w|^3, w on the bed
        for i in range(3):
            w[i] = v[i] - vn * n[i]
            slip[i] = w[i]
        speed = np.sqrt(_dot(w, w))
        ramp = speed < vc or stick
        gain = fscale / vc if ramp else 1.0 / speed
        bend = 0.0 if ramp else 1.0 / (speed * speed * speed)
        for i in range(3):
            dN[i] = -mu * gain * w[i]
            f[i] += pressure * dN[i]
        if jac:
            # F = p dN(w), w = (I - n n^T) v: Ab -= v_x dF_dw In + dN (dp_dr + v_x dp_dv)^T, and
            # dF_dw In = -mu p (gain In - bend w w^T) since w is normal to n
            scale = v_x * mu * pressure
            for i in range(3):
                for j in range(3):
                    Ab[i, j] += scale * ((gain if i == j else 0.0) - gain * n[i] * n[j] - bend * w[i] * w[j]) \
                        - dN[i] * (dp_dr[j] + v_x * dp_dv[j])
            if curved:  # dw/dr through the normal's gradient
                for i in range(3):
                    for j in range(3):
                        dphi[i, j] = -mu * pressure * ((gain if i == j else 0.0) - bend * w[i] * w[j])
                        tmp[i, j] = -(n[i] * v[j] + (vn if i == j else 0.0))
                dw_dr[:, :] = 0.0
                _add_matmul(dw_dr, tmp, dn, 1.0)
                _add_matmul(Ab, dphi, dw_dr, -1.0)
    elif model == 2 and rubbing:
        for i in range(3):
            w[i] = v[i] - vn * n[i]
            slip[i] = w[i]
        # anisotropic: along the line's direction on the bed and across it
        tn = _dot(t, n)
        for i in range(3):
            pv[i] = t[i] - tn * n[i]
        size = np.sqrt(_dot(pv, pv))
        if size < DEGENERATE_AXIS:
            size = np.inf
            q[:] = 0.0
        else:
            for i in range(3):
                q[i] = pv[i] / size
        along = _dot(w, q)
        for i in range(3):
            va[i] = along * q[i]
            un[i] = w[i] - va[i]  # the transverse velocity
        _saturation(va, vc, fscale, phia, dphia, stick)
        _saturation(un, vc, fscale, phi, dphi, stick)
        for i in range(3):
            dN[i] = -(mu_a * phia[i] + mu_t * phi[i])
        for i in range(3):
            f[i] += pressure * dN[i]
        if jac:
            # dF/dw = -N (ga q q^T + gt (I - q q^T)); dF/dq = -N (ga - gt)(q w^T + (w.q) I)
            for i in range(3):
                for j in range(3):
                    tmp[i, j] = q[i] * q[j]
            dF_dw[:, :] = 0.0
            _add_matmul(dF_dw, dphia, tmp, -pressure * mu_a)
            for i in range(3):
                for j in range(3):
                    tmp[i, j] = eye[i, j] - q[i] * q[j]
            _add_matmul(dF_dw, dphi, tmp, -pressure * mu_t)
            for i in range(3):
                for j in range(3):
                    tmp[i, j] = q[i] * w[j] + (along if i == j else 0.0)
            dF_dq[:, :] = 0.0
            _add_matmul(dF_dq, dphia, tmp, -pressure * mu_a)
            _add_matmul(dF_dq, dphi, tmp, pressure * mu_t)
            for i in range(3):
                for j in range(3):
                    In[i, j] = eye[i, j] - n[i] * n[j]
                    tmp[i, j] = -(n[i] * v[j] + (vn if i == j else 0.0))
            dw_dr[:, :] = 0.0
            _add_matmul(dw_dr, tmp, dn, 1.0)
            _add_matmul(Ab, dF_dw, dw_dr, -1.0)
            _add_outer(Ab, dN, dp_dr, -1.0)
            _add_matmul(Ab, dF_dw, In, -v_x)
            _add_outer(Ab, dN, dp_dv, -v_x)
            if size < np.inf:
                for i in range(3):
                    for j in range(3):
                        dq_dp[i, j] = (eye[i, j] - q[i] * q[j]) / size
                tmp[:, :] = 0.0
                _add_matmul(tmp, dq_dp, In, 1.0 / divisor)
                _add_matmul(Bb, dF_dq, tmp, -1.0)
                tn = _dot(n, t)
                for i in range(3):
                    for j in range(3):
                        dp_dn[i, j] = -(n[i] * t[j] + (tn if i == j else 0.0))
                tmp[:, :] = 0.0
                _add_matmul(tmp, dp_dn, dn, 1.0)
                dg[:, :] = 0.0
                _add_matmul(dg, dq_dp, tmp, 1.0)
                _add_matmul(Ab, dF_dq, dg, -1.0)
    # Morison drag on the velocity relative to the current (desire2023 Eq. 3)
    if drag_n > 0.0 or drag_t > 0.0:
        w[0], w[1], w[2] = cur0 - v[0], cur1 - v[1], cur2 - v[2]  # u
        along = _dot(w, t)
        for i in range(3):
            un[i] = w[i] - along * t[i]
        speed = np.sqrt(_dot(un, un))
        for i in range(3):
            per[i] = drag_n * speed * un[i] + drag_t * abs(along) * along * t[i]
            f[i] += stretch * per[i]
        if jac:
            # with dg = Dn (|un| I + un un^T / |un|), and P un = un, t^T un = 0:
            # A -= v_x f_v: Ab += v_x |r'| (dg P + 2 Dt |u.t| t t^T), dg P = Dn (|un| P + un un^T / |un|)
            # B -= f_dr: Bb -= per t^T + dF_dw P, dF_dw P = -Dn (|un| t un^T + (u.t)(|un| P + un un^T / |un|))
            #                                               + Dt |u.t| (2 t un^T + (u.t) P)
            inverse = 1.0 / speed if speed > 0.0 else 0.0
            axial = drag_t * abs(along)
            for i in range(3):
                for j in range(3):
                    dgP = drag_n * (speed * P[i, j] + un[i] * un[j] * inverse)
                    Ab[i, j] += v_x * stretch * (dgP + 2.0 * axial * t[i] * t[j])
                    Bb[i, j] += drag_n * speed * t[i] * un[j] + along * dgP \
                        - axial * (2.0 * t[i] * un[j] + along * P[i, j]) - per[i] * t[j]
    # added mass, normal and tangential
    if am_n > 0.0 or am_t > 0.0:
        along = _dot(acc, t)
        diff = am_t - am_n
        for i in range(3):
            per[i] = am_n * acc[i] + diff * along * t[i]
            f[i] -= stretch * per[i]
        if jac:
            # Bb += per t^T + diff ((a.t) I + t a^T) P = per t^T + diff ((a.t) P + t a_perp^T)
            for i in range(3):
                for j in range(3):
                    Ab[i, j] += a_x * stretch * ((am_n if i == j else 0.0) + diff * t[i] * t[j])
                    Bb[i, j] += per[i] * t[j] + diff * (along * P[i, j] + t[i] * (acc[j] - along * t[j]))
    return (TOUCHING if touching else 0) | (CLOSING if closing else 0)


@njit(cache=True, _nrt=False)
def _tension(dr, dv, EA, beta, pushes, v_x, jac, N, Dblk):
    """Flux N = T t at one reduced point and D = N_dr + v_x N_dv (cablefem.loads.tension);
    ``pushes``: the line may push (T = EA e for all e: the statics start-up aid, and the model
    Newton's taut correction, ``cablefem.dynamics``). Returns whether the point is taut."""
    stretch = np.sqrt(_dot(dr, dr))
    divisor = stretch if stretch > 0.0 else np.inf  # coincident points: t = 0 (loads.unit_tangent)
    t0, t1, t2 = dr[0] / divisor, dr[1] / divisor, dr[2] / divisor
    e = stretch - 1.0
    rate = t0 * dv[0] + t1 * dv[1] + t2 * dv[2]
    T = EA * (e + beta * rate)
    active = pushes or (e > 0.0 and T > 0.0)
    if not active:
        T = 0.0
    N[0], N[1], N[2] = T * t0, T * t1, T * t2
    if jac:
        t = (t0, t1, t2)
        on = 1.0 if active else 0.0
        for i in range(3):
            for j in range(3):
                dT = EA * on * t[j] + EA * beta * on * (dv[j] - rate * t[j]) / divisor
                delta = 1.0 if i == j else 0.0
                Dblk[i, j] = t[i] * dT + (T / divisor) * (delta - t[i] * t[j]) \
                    + SLACK_STIFFNESS * EA * (1.0 - on) * delta + v_x * EA * beta * on * t[i] * t[j]
    return e > 0.0 and T > 0.0
