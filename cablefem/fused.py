"""A fused, compiled evaluation of a line's step residual and banded tangent (numba).

The reference assembly (``LineSystem.evaluate`` / ``matrix``, one numpy
module per load, and scikit-fem's forms) spends most of a time step in
Python overhead on small arrays. For the loads a time-domain run uses
(tension with internal damping, weight, seabed contact with friction, drag,
added mass) and the consistent mass, this module computes the same residual
M A + G and tangent g_x (K + v_x C + a_x (M + M_a)) in one compiled loop over
elements and quadrature points, straight into LAPACK's banded storage with
the unknowns ordered along the line, and factors it with ``dgbtrf``. The
physics is that of ``cablefem.loads`` line for line (same equations, same
Jacobians); ``tests/test_fused.py`` checks that both agree to round-off.
A system with any other load, or a lumped mass, keeps the reference path.

The per-point functions and the element loop are compiled with numba's
reference counting off (``_nrt=False``; they allocate nothing): with it on,
every scratch view and array argument costs an atomic increment and
decrement, which was 3/4 of a point's time. With that and the gap of a plane
seabed computed in the loop, a residual evaluation of 80 P2 elements went
from ~185 to ~45 us (verification/work_precision/README.md).
"""

import numpy as np
from numba import njit
from scipy.linalg import lapack

from .branches import CLOSING, DAMPER_ON, DAMPERS, STICK, TOUCH_ON, TOUCHES, TOUCHING
from .geometry import Plane
from .loads.added_mass import AddedMass
from .loads.contact import DEGENERATE_AXIS
from .loads.drag import Drag
from .loads.friction import AnisotropicFriction, IsotropicFriction
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
    dry, buoy, k, c, drag_n, drag_t, cur0, cur1, cur2, am_n, am_t = p
    model, mu, mu_a, mu_t, fscale, vc = bed
    f[0] = 0.0
    f[1] = 0.0
    f[2] = -(dry - (buoy if r[2] < 0.0 else 0.0))
    if jac:
        Ab[:, :] = 0.0
        Bb[:, :] = 0.0
    eye, P, tmp, dphi, dphia, dF_dw, dF_dq, dw_dr, In, dq_dp, dp_dn, dg = (
        M[0], M[1], M[2], M[3], M[4], M[5], M[6], M[7], M[8], M[9], M[10], M[11])
    t, w, phi, phia, q, dp_dr, dp_dv, dN, un, per, pv, va = (
        u[0], u[1], u[2], u[3], u[4], u[5], u[6], u[7], u[8], u[9], u[10], u[11])
    stretch = np.sqrt(_dot(dr, dr))
    for i in range(3):
        t[i] = dr[i] / stretch
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
                _add_matmul(tmp, dq_dp, In, 1.0 / stretch)
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
    t0, t1, t2 = dr[0] / stretch, dr[1] / stretch, dr[2] / stretch
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
                dT = EA * on * t[j] + EA * beta * on * (dv[j] - rate * t[j]) / stretch
                delta = 1.0 if i == j else 0.0
                Dblk[i, j] = t[i] * dT + (T / stretch) * (delta - t[i] * t[j]) \
                    + SLACK_STIFFNESS * EA * (1.0 - on) * delta + v_x * EA * beta * on * t[i] * t[j]
    return e > 0.0 and T > 0.0


@njit(cache=True)
def _assemble(X, V, Acc, dofs, position, phi, dphi, dx, rphi, rdphi, rdx, params, tension, mass,
              bed, plane, gap, normal, grad_gap, dnormal, v_x, a_x, jac, rows, band, kl, ku, hold, pull, use_stick,
              slip, taut, contact):
    """Residual rows (N, 3) incl. inertia, and the banded tangent of the free unknowns. On a plane
    seabed ``plane`` is (nx, ny, nz, offset) and the gap is computed here (gap, normal, grad_gap
    and dnormal are then not read); otherwise ``plane`` is empty and they hold the projection.
    With ``use_stick``, the full points' loads keep the branches ``hold`` (nel, nq) holds (see
    ``_point_loads``) and the line pulls (and pushes) at the reduced points where ``pull``
    (nel, nr) is set; slip (nel, nq, 3) receives the slip velocities, taut (nel, nr) whether the
    reduced points are taut and contact (nel, nq) the contact states (TOUCHING, CLOSING bits)."""
    nloc = dofs.shape[1]
    _assemble_loop(X, V, Acc, dofs, position, phi, dphi, dx, rphi, rdphi, rdx, params, tension, mass,
                   bed, plane, gap, normal, grad_gap, dnormal, v_x, a_x, jac, rows, band, kl, ku, position.max(),
                   np.zeros((7, 3)), np.zeros((4, 3, 3)), np.zeros((nloc, 3)), np.zeros((nloc, 3, nloc, 3)),
                   np.zeros((12, 3, 3)), np.zeros((12, 3)), np.arange(dofs.shape[0]), hold, pull, use_stick, slip,
                   taut, contact)


@njit(cache=True, _nrt=False)
def _assemble_loop(X, V, Acc, dofs, position, phi, dphi, dx, rphi, rdphi, rdx, params, tension, mass, bed,
                   plane, gap, normal, grad_gap, dnormal, v_x, a_x, jac, rows, band, kl, ku, last, vec, blk,
                   Re, Ke, M, u, elements, hold, pull, use_stick, slip, taut, contact):
    """The loop of ``_assemble`` over ``elements`` on zeroed scratch it is given (vec (7, 3), blk
    (4, 3, 3), Re, Ke, M, u): it allocates nothing, so it runs without reference counting (see the
    module docstring)."""
    on_plane = plane.shape[0] == 4
    flat = plane[:3]
    zero = blk[3]  # the normal's gradient on a plane
    nloc = dofs.shape[1]
    nq, nr = dx.shape[1], rdx.shape[1]
    f, N, r, dr, v, acc, dv = vec[0], vec[1], vec[2], vec[3], vec[4], vec[5], vec[6]
    Ab, Bb, Db = blk[0], blk[1], blk[2]
    for e in elements:
        Re[:] = 0.0
        Ke[:] = 0.0
        for g in range(nq):
            r[:] = 0.0
            dr[:] = 0.0
            v[:] = 0.0
            acc[:] = 0.0
            for l in range(nloc):
                i = dofs[e, l]
                for a in range(3):
                    r[a] += phi[l, e, g] * X[i, a]
                    dr[a] += dphi[l, e, g] * X[i, a]
                    v[a] += phi[l, e, g] * V[i, a]
                    acc[a] += phi[l, e, g] * Acc[i, a]
            if on_plane:
                contact[e, g] = _point_loads(r, dr, v, acc, params[e], bed, _dot(flat, r) - plane[3], flat, flat,
                                            zero, False, v_x, a_x, jac, f, Ab, Bb, M, u,
                                            hold[e, g] if use_stick else 0, slip[e, g])
            else:
                dn = dnormal[e, g]
                curved = False  # a point on a flat part of a mesh or grid has no normal gradient
                for a in range(3):
                    for b in range(3):
                        curved = curved or dn[a, b] != 0.0
                contact[e, g] = _point_loads(r, dr, v, acc, params[e], bed, gap[e, g], normal[e, g], grad_gap[e, g],
                                            dn, curved, v_x, a_x, jac, f, Ab, Bb, M, u,
                                            hold[e, g] if use_stick else 0, slip[e, g])
            w = dx[e, g]
            m = mass[e]
            for l in range(nloc):
                for a in range(3):
                    Re[l, a] += w * phi[l, e, g] * (m * acc[a] - f[a])
                if jac:
                    for mm in range(nloc):
                        c_v = w * phi[l, e, g] * phi[mm, e, g]
                        c_d = w * phi[l, e, g] * dphi[mm, e, g]
                        for a in range(3):
                            for b in range(3):
                                Ke[l, a, mm, b] += c_v * Ab[a, b] + c_d * Bb[a, b]
                            Ke[l, a, mm, a] += c_v * a_x * m
        for g in range(nr):
            dr[:] = 0.0
            dv[:] = 0.0
            for l in range(nloc):
                i = dofs[e, l]
                for a in range(3):
                    dr[a] += rdphi[l, e, g] * X[i, a]
                    dv[a] += rdphi[l, e, g] * V[i, a]
            taut[e, g] = _tension(dr, dv, tension[e, 0], tension[e, 1],
                                  tension[e, 2] > 0.0 or (use_stick and pull[e, g]), v_x, jac, N, Db)
            w = rdx[e, g]
            for l in range(nloc):
                for a in range(3):
                    Re[l, a] += w * rdphi[l, e, g] * N[a]
                if jac:
                    for mm in range(nloc):
                        c_dd = w * rdphi[l, e, g] * rdphi[mm, e, g]
                        for a in range(3):
                            for b in range(3):
                                Ke[l, a, mm, b] += c_dd * Db[a, b]
        for l in range(nloc):
            i = dofs[e, l]
            for a in range(3):
                rows[i, a] += Re[l, a]
            pi = position[i]
            if not jac or pi == 0 or pi == last:
                continue
            for mm in range(nloc):
                pj = position[dofs[e, mm]]
                if pj == 0 or pj == last:
                    continue
                for a in range(3):
                    for b in range(3):
                        row = 3 * (pi - 1) + a
                        col = 3 * (pj - 1) + b
                        band[kl + ku + row - col, col] += Ke[l, a, mm, b]


class FusedEvaluator:
    """Compiled residual and banded tangent of one ``LineSystem`` (see the module docstring)."""

    def __init__(self, system, mass):
        fem = system.fem
        self.system = system
        self.dofs = fem.element_dofs.astype(np.int64)
        # unknowns ordered along the line: each element's left vertex, its interior, its right
        order = []
        for e in range(fem.n_elements):
            for i in (fem.mesh.t[0, e], *self.dofs[e, 2:], fem.mesh.t[1, e]):
                if not order or order[-1] != i:
                    order.append(int(i))
        self.position = np.empty(fem.n_dofs, dtype=np.int64)
        self.position[np.array(order)] = np.arange(len(order))
        nloc = self.dofs.shape[1]
        self.kl = self.ku = 3 * nloc - 1
        self.n = 3 * (fem.n_dofs - 2)
        self.free_order = np.array(order[1:-1])  # free scalar DOFs in band order
        self.band_of_free = self.position[fem.free_dofs] - 1  # band position of fem.free_dofs
        self.mass = np.asarray(mass, dtype=float)
        self.full, self.reduced = fem.full, fem.reduced
        loads = system.loads
        props = system.props
        nel = fem.n_elements
        params = np.zeros((nel, 11))
        params[:, 0] = system.weight.dry[:, 0]
        params[:, 1] = system.weight.buoyancy[:, 0]
        params[:, 2] = system.contact.stiffness[:, 0]
        params[:, 3] = system.contact.damping[:, 0]
        for load in loads:
            if isinstance(load, Drag):
                params[:, 4], params[:, 5] = load.normal[:, 0], load.tangential[:, 0]
                params[:, 6:9] = load.current.ravel()
            elif isinstance(load, AddedMass):
                params[:, 9], params[:, 10] = load.normal[:, 0], load.tangential[:, 0]
        self.params = params
        # EA, beta and whether the line may push (read from ``system.tension`` at each evaluation)
        self.tension = np.column_stack([system.tension.EA[:, 0], props["damping"]
                                        if system.tension.beta is not None else np.zeros(nel), np.zeros(nel)])
        law = system.contact.friction
        if isinstance(law, IsotropicFriction):
            self.bed = (1, law.mu, 0.0, 0.0, law.static_scale, law.v_threshold)
        elif isinstance(law, AnisotropicFriction):
            self.bed = (2, 0.0, law.mu_axial, law.mu_transverse, law.static_scale, law.v_threshold)
        else:
            self.bed = (0, 0.0, 0.0, 0.0, 1.0, 1.0)
        # on a plane the kernel computes the gap itself: no interpolation or projection in numpy
        self.plane = np.zeros(0)
        if isinstance(system.seabed, Plane):
            self.plane = np.append(system.seabed.normal, system.seabed.offset).astype(float)
        self.unused = (np.zeros((1, 1)), np.zeros((1, 1, 3)), np.zeros((1, 1, 3)), np.zeros((1, 1, 3, 3)))
        nq = fem.full.dx.shape[1]
        self.hold = np.zeros((nel, nq), dtype=np.int8)  # branches the full points are held on (bits)
        self.contact = np.zeros((nel, nq), dtype=np.int8)  # contact states of the last evaluation (bits)
        self.slip = np.zeros((nel, nq, 3))  # slip velocities of the last evaluation
        nr = fem.reduced.dx.shape[1]
        self.pull = np.zeros((nel, nr), dtype=bool)  # reduced points held on the taut branch
        self.taut = np.zeros((nel, nr), dtype=bool)  # taut reduced points of the last evaluation

    @classmethod
    def for_system(cls, system, mass):
        """The evaluator of ``system``, or None if it holds a load this kernel does not know."""
        from .loads.contact import SeabedContact
        from .loads.gravity import Weight
        from .loads.tension import Tension

        known = (Tension, Weight, SeabedContact, Drag, AddedMass)
        if not all(isinstance(load, known) for load in system.loads):
            return None
        if sum(isinstance(load, (Drag, AddedMass)) for load in system.loads) > 2:
            return None
        return cls(system, mass)

    def evaluate(self, X, V, A, v_x, a_x, jacobian=True, stick=False):
        """Rows M A + G (N, 3) and, with ``jacobian``, the banded K + a_x M (LAPACK layout); with
        ``stick``, the full points' loads on the branches ``self.hold`` holds and the reduced points
        taut where ``self.pull`` says. The slip velocities, taut points and contact states go to
        ``self.slip``, ``self.taut`` and ``self.contact``."""
        fem = self.system.fem
        self.tension[:, 2] = float(self.system.tension.compression)
        if self.plane.size:
            gap, normal, grad, dn = self.unused
        else:
            shape = fem.full.s.shape
            proj = self.system.seabed.project(fem.full.interpolate(X)[0])
            gap = proj.gap.reshape(shape)
            normal = proj.direction.reshape(shape + (3,))
            grad = proj.gap_gradient.reshape(shape + (3,))
            dn = proj.direction_gradient.reshape(shape + (3, 3))
        rows = np.zeros((fem.n_dofs, 3))
        # Fortran order, as LAPACK and the compiled steps hold it (one compiled kernel for both;
        # the unused band is 2 x 2, since numba would type a 1 x 1 array as C-ordered)
        band = np.zeros((2 * self.kl + self.ku + 1, self.n) if jacobian else (2, 2), order="F")
        _assemble(X, V, A, self.dofs, self.position, self.full.phi, self.full.dphi, self.full.dx,
                  self.reduced.phi, self.reduced.dphi, self.reduced.dx, self.params, self.tension,
                  self.mass, self.bed, self.plane, np.ascontiguousarray(gap), np.ascontiguousarray(normal),
                  np.ascontiguousarray(grad), np.ascontiguousarray(dn), v_x, a_x, jacobian, rows,
                  band, self.kl, self.ku, self.hold, self.pull, stick, self.slip, self.taut, self.contact)
        return rows, (band if jacobian else None)

    def factorize(self, band, scale=1.0):
        """LU factors of scale x band (dgbtrf); None if singular."""
        lu, piv, info = lapack.dgbtrf(scale * band, self.kl, self.ku)
        return None if info != 0 else (lu, piv)

    def solve(self, factors, rows):
        """Increment (N_free, 3) of the free DOFs (in ``fem.free_dofs`` order) for residual rows."""
        lu, piv = factors
        rhs = -rows[self.free_order].ravel()
        x, info = lapack.dgbtrs(lu, self.kl, self.ku, rhs, piv)
        return x.reshape(-1, 3)[self.band_of_free]

    def dense(self, band):
        """The banded tangent as a dense matrix in ``fem.free_vector_dofs`` order (for tests)."""
        n, kl, ku = self.n, self.kl, self.ku
        dense = np.zeros((n, n))
        for j in range(n):
            for i in range(max(0, j - ku), min(n, j + kl + 1)):
                dense[i, j] = band[kl + ku + i - j, j]
        index = (3 * self.band_of_free[:, None] + np.arange(3)).ravel()
        return dense[np.ix_(index, index)]
