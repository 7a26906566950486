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

The per-point loads (``cablefem.point_loads``) and the element loop are compiled with numba's
reference counting off (``_nrt=False``; they allocate nothing): with it on,
every scratch view and array argument costs an atomic increment and
decrement, which was 3/4 of a point's time. With that and the gap of a plane
seabed computed in the loop, a residual evaluation of 80 P2 elements went
from ~185 to ~45 us (verification/work_precision/README.md).
"""

import numpy as np
from numba import njit
from scipy.linalg import lapack

from .geometry import Plane
from .loads.added_mass import AddedMass
from .loads.drag import Drag
from .loads.friction import AnisotropicFriction, IsotropicFriction
from .point_loads import _dot, _point_loads, _tension


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
        params = np.zeros((nel, 12))
        params[:, 0] = system.weight.dry[:, 0]
        params[:, 1] = system.weight.buoyancy[:, 0]
        params[:, 11] = system.weight.diameter[:, 0]
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
