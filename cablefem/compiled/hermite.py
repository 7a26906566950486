"""What a line on Hermite elements with bending adds to the compiled element loop
(``cablefem.compiled.kernels``' ``_elements``; the numpy face is ``cablefem.fem.forms``' moment
terms and ``cablefem.fem.clamp``).

At a full point, r'' from the basis' second derivatives (``_second_kinematics``), and the flux N and
moment Q the bending load gives against phi' and phi'' with their blocks D = N_r', E = N_r'',
F = Q_r', G = Q_r'' into the element's rows and matrix (``_add_second``); at a clamped end, its
tangent row made the clamp's constraint (``_clamp``). ``kernels.Points.clamp`` holds the clamps,
its columns named here.
"""

from numba import njit
from numba import uint64 as _index

#: the columns of ``kernels.Points.clamp``: the direction d (0:3), the constraint scale k, the local
#: DOF of the clamped tangent in its element, the rows it replaced (the clamp's reaction, 3)
CLAMP_SCALE, CLAMP_LOCAL, CLAMP_ROWS = 3, 4, 5


@njit(cache=True, _nrt=False)
def _second_kinematics(ctx, out, mesh, ddphi, X, e, g):
    """r'' at full point g of element e (a load reads it: bending on Hermite elements), and the flux,
    the moment and their blocks it adds to zeroed."""
    ddr = ctx.ddr
    ddr[:] = 0.0
    for l in range(mesh.dofs.shape[1]):
        i = _index(mesh.dofs[e, l])
        for a in range(3):
            ddr[a] += ddphi[l, e, g] * X[i, a]
    out.N[:] = 0.0
    out.Q[:] = 0.0
    if ctx.jac:
        out.D[:, :] = 0.0
        out.E[:, :] = 0.0
        out.F[:, :] = 0.0
        out.G[:, :] = 0.0



@njit(cache=True, _nrt=False)
def _add_second(Re, Ke, mesh, ddphi, out, e, g, jac):
    """A full point's flux N and moment Q against phi', phi'' and their blocks D, E, F, G into the
    element's rows and matrix (a Hermite line with bending)."""
    w = mesh.dx[e, g]
    nloc = mesh.dofs.shape[1]
    for l in range(nloc):
        d_l, s_l = w * mesh.dphi[l, e, g], w * ddphi[l, e, g]
        for a in range(3):
            Re[l, a] += d_l * out.N[a] + s_l * out.Q[a]
        if jac:
            for mm in range(nloc):
                d_m, s_m = mesh.dphi[mm, e, g], ddphi[mm, e, g]
                for a in range(3):
                    for b in range(3):
                        Ke[l, a, mm, b] += (d_l * (out.D[a, b] * d_m + out.E[a, b] * s_m)
                                            + s_l * (out.F[a, b] * d_m + out.G[a, b] * s_m))



@njit(cache=True, _nrt=False)
def _clamp(Re, Ke, mesh, clamp, X, e, end, jac):
    """A clamped end's tangent row in its element's rows and matrix: d (d . R) + k (I - d d^T) X_t
    and d d^T K_t + k (I - d d^T) on its diagonal block (``cablefem.fem.clamp``)."""
    d0, d1, d2, k = clamp[end, 0], clamp[end, 1], clamp[end, 2], clamp[end, CLAMP_SCALE]
    d = (d0, d1, d2)
    l = int(clamp[end, CLAMP_LOCAL])
    i = _index(mesh.dofs[e, l])
    along = d0 * Re[l, 0] + d1 * Re[l, 1] + d2 * Re[l, 2]
    x_along = d0 * X[i, 0] + d1 * X[i, 1] + d2 * X[i, 2]
    for a in range(3):
        clamp[end, CLAMP_ROWS + a] = Re[l, a]
        Re[l, a] = d[a] * along + k * (X[i, a] - d[a] * x_along)
    if not jac:
        return
    nloc = mesh.dofs.shape[1]
    for mm in range(nloc):
        for b in range(3):
            along = d0 * Ke[l, 0, mm, b] + d1 * Ke[l, 1, mm, b] + d2 * Ke[l, 2, mm, b]
            for a in range(3):
                Ke[l, a, mm, b] = d[a] * along
    for a in range(3):
        for b in range(3):
            Ke[l, a, l, b] += k * ((1.0 if a == b else 0.0) - d[a] * d[b])
