"""The compiled evaluation of a line's step residual and banded tangent, composed from the load
catalog (numba; docs/architecture.md, "The compiled path").

For the loads of ``cablefem.loads.catalog`` and the consistent mass, ``assemble`` computes the
residual M A + G and the tangent g_x (K + v_x C + a_x (M + M_a)) in one loop over elements and
quadrature points, straight into LAPACK's banded storage with the unknowns ordered along the line.
At each point it fills a context record (``CONTEXT``: position, its derivatives, velocity,
acceleration, the unit tangent, the seabed's projection, the step's factors, and each load's named
scratch) and calls the loads of the point's rule that the line has, in catalog order
(``full_point``, ``reduced_point``: a loop over the addresses of the catalog's point kernels, 0 for
a load the line has not, ``cablefem.compiled.calls``: a kernel is compiled once, where a scene has
its load, and not again inside the loop; a load a scene does not use costs a test, not a call,
and no compilation). Each load reads its parameters by name from the element's record
(``p.drag.normal``), works in its own scratch in the context (``ctx.drag.w``; another load's only
where its spec ``reads`` it: friction reads the contact's ``ctx.contact.normal_force``), writes its
branch state to the point's state record, reads its holds and its committed history, writes its
trial history, and adds its force and Jacobian blocks to the output record (``OUT``: f,
A = -(f_r + v_x f_v + a_x f_a), B = -f_dr at full points; the flux N and D = N_dr + v_x N_dv at
reduced ones). On a line on Hermite elements with bending (``cablefem.loads.bending``;
``Points.ddphi`` not empty) the full points also read r'' (``ctx.ddr``, ``_second_kinematics``) and
take a flux N and a moment Q against phi', phi'' with the blocks D = N_r', E = N_r'', F = Q_r',
G = Q_r'' (``_add_second``); a clamped end's tangent row is made its constraint in the end element's
rows (``_clamp``, ``cablefem.fem.clamp``): ``cablefem.compiled.hermite``. The element loop is compiled twice, with and without
these (``_elements``), so that a line without bending runs no test for them per point, and its
basis and clamps ride in ``Points``, not ``Mesh``, whose arrays the per-point calls copy.

The kernels run with numba's reference counting off (``_nrt=False``: they allocate nothing; with
it on, every scratch view and array argument costs an atomic increment and decrement, which was
3/4 of a point's time). The reference is the numpy face of each load assembled through
scikit-fem (``cablefem.fem.system``); ``tests/test_catalog.py`` and ``tests/test_fused.py`` hold them
equal to round-off.
"""

import warnings
from collections import namedtuple

import numpy as np
from numba import from_dtype, literal_unroll, njit, types
from numba import uint64 as _index
from numba.core.errors import NumbaExperimentalFeatureWarning
from numba.extending import overload

from cablefem.compiled import calls, progress  # noqa: F401 (progress: a compilation says so on stderr, once)
from cablefem.compiled.hermite import CLAMP_SCALE, _add_second, _clamp, _second_kinematics
from cablefem.loads import catalog
from cablefem.waves.compiled import NONE as NO_WATER, water_cached

# numba marks the catalog's tuple of functions "first-class", an experimental feature; literal_unroll
# resolves each call statically (measured: as fast as direct calls)
warnings.filterwarnings("ignore", category=NumbaExperimentalFeatureWarning)

LAYOUT = catalog.layout()
FULL_KERNELS, REDUCED_KERNELS, NODE_KERNELS = LAYOUT.full_kernels, LAYOUT.reduced_kernels, LAYOUT.node_kernels
FULL_RULES, REDUCED_RULES = LAYOUT.full_rules, LAYOUT.reduced_rules

#: what a point kernel sees of its point (set by ``assemble``); t, stretch and P at full points only
#: (P, the normal projector I - t t^T, only when a tangent is assembled); the evaluation time and, on a
#: line in waves, the water's elevation above the point, its velocity and acceleration and (with a
#: tangent) their gradients, and whether the point is below the surface (``cablefem.waves.compiled``,
#: ``water_at``; a line in still water leaves them alone); which loads of each rule the
#: line has, the addresses of their kernels (``Points.full_calls``, ``reduced_calls``; 0: the line has not
#: that load; read from the context, not passed, because
#: an argument more per point cost more instructions than the calls it saves); inv_h: 1 / the step's
#: size [1/s] (0 without a step: statics), for a load whose history evolves in time (``loads.rope``)
POINT = [("r", "f8", (3,)), ("dr", "f8", (3,)), ("v", "f8", (3,)), ("dv", "f8", (3,)),
         ("a", "f8", (3,)), ("t", "f8", (3,)), ("stretch", "f8"), ("P", "f8", (3, 3)),
         ("gap", "f8"), ("n", "f8", (3,)), ("grad_gap", "f8", (3,)), ("dn", "f8", (3, 3)),
         ("curved", "?"), ("v_x", "f8"), ("a_x", "f8"), ("inv_h", "f8"), ("jac", "?"), ("held", "?"), ("time", "f8"),
         ("wet", "?"), ("eta", "f8"), ("water_u", "f8", (3,)), ("water_a", "f8", (3,)),
         ("water_du", "f8", (3, 3)), ("water_da", "f8", (3, 3)),
         ("full_calls", "i8", (len(FULL_KERNELS),)), ("reduced_calls", "i8", (len(REDUCED_KERNELS),)),
         ("ddr", "f8", (3,))]  # r'' of a Hermite line with bending (``_second_kinematics``)
_clash = {name for name, _ in LAYOUT.scratch} & {entry[0] for entry in POINT}
if _clash:
    raise ValueError(f"load name(s) {sorted(_clash)} clash with the point context's own fields")
#: the point context: ``POINT`` and, under each load's name, its scratch (``LoadSpec.scratch``)
CONTEXT = np.dtype(POINT + list(LAYOUT.scratch), align=True)
#: what a point kernel adds to
OUT = np.dtype([("f", "f8", (3,)), ("A", "f8", (3, 3)), ("B", "f8", (3, 3)), ("N", "f8", (3,)),
                ("D", "f8", (3, 3)), ("Q", "f8", (3,)), ("E", "f8", (3, 3)), ("F", "f8", (3, 3)),
                ("G", "f8", (3, 3))], align=True)
#: what a point kernel takes, as numba types: the context, the element's parameters, the point's committed
#: and trial history, branch state and holds, and the output (``point_calls``; full and reduced points)
FULL_TYPES, REDUCED_TYPES = (tuple(from_dtype(d) for d in (CONTEXT, LAYOUT.params, history, history, state, hold, OUT))
                             for history, state, hold in ((LAYOUT.full_history, LAYOUT.full_state, LAYOUT.full_hold),
                                                          (LAYOUT.reduced_history, LAYOUT.reduced_state,
                                                           LAYOUT.reduced_hold)))
#: the calls of the point kernels by address (``point_calls``), one function of each signature
_full_kernel, _reduced_kernel = calls.at(FULL_TYPES, types.none), calls.at(REDUCED_TYPES, types.none)

#: a line's mesh as the loop reads it: element DOFs (nel, nloc), band positions (N,), basis values,
#: derivatives and weights at the full and reduced points, mass per length (nel,), band widths, the
#: first and last band position of an unknown (1 and N - 2 between two prescribed ends, 0 and N - 1
#: between two free ones), and the vertices of the node loads (k,)
Mesh = namedtuple("Mesh", "dofs position phi dphi dx rphi rdphi rdx mass kl ku lo hi nodes")
#: the seabed at the full points: a plane (nx, ny, nz, offset), or an empty plane and the
#: projection's gap (nel, nq), normal, its gradient (nel, nq, 3) and the normal's (nel, nq, 3, 3)
Bed = namedtuple("Bed", "plane gap normal grad_gap dnormal")
#: the records of ``cablefem.loads.catalog``: parameters (nel,), and per full (nel, nq) and reduced
#: (nel, nr) point the committed and trial history, the branch state and the holds; the node loads'
#: parameters (k,); which full and reduced loads of the catalog the line has (bool, in catalog
#: order: the point loops call only those, so that a load a scene does not use costs no call); the
#: second derivatives of the basis at the full points (nloc, nel, nq) where a load reads r''
#: (bending on Hermite elements; (0, 0, 0) otherwise); and the clamped ends (2, 8): per end its
#: direction d (0:3) and constraint scale k (3; 0: not clamped), the local DOF of its tangent row in
#: its element (4), and (5:8, written by every evaluation of an end element) the row M A + G of the
#: clamped tangent before the constraint replaces it: the clamp's reaction
#: (``cablefem.fem.clamp.reaction_moments``). Not in ``Mesh``: the per-point calls that take the mesh
#: copy each of its arrays, which lines without bending would pay for
Points = namedtuple("Points", "params full_old full_new full_state full_hold "
                              "reduced_old reduced_new reduced_state reduced_hold nodes full_calls reduced_calls "
                              "ddphi clamp")
#: scratch: a context (the loads' scratch in it) and an output record, an element's rows (nloc, 3)
#: and matrix (nloc, 3, nloc, 3)
Work = namedtuple("Work", "ctx out Re Ke")


def records(dtype, shape):
    """A zeroed record array of ``dtype`` and ``shape``."""
    return np.zeros(shape, dtype=dtype)


def points(params, history, nq, nr, nodes, ddphi, clamp):
    """Per-point records (``Points``) for ``params`` (nel,) with nq full and nr reduced points: the
    history of a ``LineSystem`` (``system.history``, shared: the compiled and the numpy path commit
    the same records), fresh branch state and holds; ``nodes``: the node loads' parameters (k,);
    ``ddphi``, ``clamp``: the bending's basis and the clamped ends (``Points``)."""
    L, nel = LAYOUT, params.shape[0]
    (full_old, full_new), (reduced_old, reduced_new) = history["full"], history["reduced"]
    return Points(params, full_old, full_new, records(L.full_state, (nel, nq)), records(L.full_hold, (nel, nq)),
                  reduced_old, reduced_new, records(L.reduced_state, (nel, nr)), records(L.reduced_hold, (nel, nr)),
                  nodes, point_calls(params, L.full, FULL_TYPES), point_calls(params, L.reduced, REDUCED_TYPES),
                  ddphi, clamp)


def active(params, specs):
    """Which of ``specs`` the parameter records ``params`` (nel,) hold a load of (their ``active``
    flags, set by ``fused.pack_params``), bool (len(specs),)."""
    return np.array([bool(params[s.name]["active"].any()) for s in specs], dtype=np.bool_)


def point_calls(params, specs, argtypes, every=False):
    """The addresses of the point kernels of ``specs`` that the parameter records ``params`` (nel,)
    hold a load of (``active``; ``every``: all of them), 0 for the others, int64 (len(specs),):
    each compiled (or loaded from numba's cache) here, for the point's ``argtypes``
    (``FULL_TYPES``, ``REDUCED_TYPES``), so a scene compiles the kernels of its loads alone."""
    has = active(params, specs)
    return np.array([calls.address(s.kernel, argtypes, types.none) if every or has[k] else 0
                     for k, s in enumerate(specs)], dtype=np.int64)


def work(nloc):
    """Fresh scratch (``Work``) for elements of nloc DOFs."""
    return Work(records(CONTEXT, 1), records(OUT, 1), np.zeros((nloc, 3)), np.zeros((nloc, 3, nloc, 3)))


def inverse_step(factors):
    """1 / h [1/s] of a step's factors (v_x, a_x, h); 0 for (v_x, a_x) or h <= 0 (statics: no step)."""
    return 1.0 / factors[2] if len(factors) > 2 and factors[2] > 0.0 else 0.0


@overload(inverse_step, jit_options={"cache": True})
def _inverse_step(factors):
    """``inverse_step`` compiled for either length of the factors' tuple."""
    if len(factors) > 2:
        return lambda factors: 1.0 / factors[2] if factors[2] > 0.0 else 0.0
    return lambda factors: 0.0


@njit(cache=True, inline="always", _nrt=False)
def full_point(ctx, p, old, new, state, hold, out):
    """The full-point loads of the catalog the line has (``ctx.full_calls``), in order, into
    ``out`` (f, A, B zeroed first; N, Q, D, E, F, G by ``_second_kinematics`` where they are read)."""
    out.f[:] = 0.0
    if ctx.jac:
        out.A[:, :] = 0.0
        out.B[:, :] = 0.0
    for k in range(ctx.full_calls.shape[0]):
        if ctx.full_calls[k] != 0:
            _full_kernel(ctx.full_calls[k], (ctx, p, old, new, state, hold, out))


@njit(cache=True, _nrt=False)
def reduced_point(ctx, p, old, new, state, hold, out):
    """The reduced-point loads of the catalog the line has (``ctx.reduced_calls``), in order, into
    ``out`` (N, D zeroed first)."""
    out.N[:] = 0.0
    if ctx.jac:
        out.D[:, :] = 0.0
    for k in range(ctx.reduced_calls.shape[0]):
        if ctx.reduced_calls[k] != 0:
            _reduced_kernel(ctx.reduced_calls[k], (ctx, p, old, new, state, hold, out))


@njit(cache=True, _nrt=False)
def node_point(ctx, p, out):
    """Every node load of the catalog, in order, into ``out`` (f, A zeroed first)."""
    out.f[:] = 0.0
    if ctx.jac:
        out.A[:, :] = 0.0
    for kernel in literal_unroll(NODE_KERNELS):
        kernel(ctx, p, p, p, p, p, out)


@njit(cache=True, _nrt=False)
def assemble_nodes(mesh, water, pts, work, state, factors, jac, rows, band):
    """The node loads at their vertices (``mesh.nodes``): -f added to the rows (N, 3) and, with
    ``jac``, the 3 x 3 block A to the band's diagonal (unknown vertices only); state (X, V, A, t)."""
    X, V, Acc, time = state
    ctx, out = work.ctx[0], work.out[0]
    ctx.v_x, ctx.a_x, ctx.inv_h = factors[0], factors[1], inverse_step(factors)
    ctx.jac, ctx.time = jac, time
    kl, ku = mesh.kl, mesh.ku
    for k in range(mesh.nodes.shape[0]):
        i = mesh.nodes[k]
        for a in range(3):
            ctx.r[a], ctx.v[a], ctx.a[a] = X[i, a], V[i, a], Acc[i, a]
        if water.kind != NO_WATER:  # the cache's rows after the full points'
            _water(ctx, water, mesh.dx.shape[0] * mesh.dx.shape[1] + k)
        node_point(ctx, pts.nodes[k], out)
        for a in range(3):
            rows[i, a] -= out.f[a]
        pi = mesh.position[i]
        if not jac or pi < mesh.lo or pi > mesh.hi:
            continue
        for a in range(3):
            for b in range(3):
                row = 3 * (pi - mesh.lo) + a
                col = 3 * (pi - mesh.lo) + b
                band[kl + ku + row - col, col] += out.A[a, b]


@njit(cache=True, _nrt=False)
def subtract_node_loads(mesh, water, pts, work, state, vertex, force):
    """``force`` (3,) less the node loads at vertex ``vertex`` at the state (X, V, A, t): a line's own
    force on a point that rides on its end (``LineSystem.end_point_loads``)."""
    X, V, Acc, time = state
    ctx, out = work.ctx[0], work.out[0]
    ctx.jac, ctx.time = False, time
    for k in range(mesh.nodes.shape[0]):
        if mesh.nodes[k] != vertex:
            continue
        for a in range(3):
            ctx.r[a], ctx.v[a], ctx.a[a] = X[vertex, a], V[vertex, a], Acc[vertex, a]
        if water.kind != NO_WATER:
            _water(ctx, water, mesh.dx.shape[0] * mesh.dx.shape[1] + k)
        node_point(ctx, pts.nodes[k], out)
        for a in range(3):
            force[a] -= out.f[a]


@njit(cache=True, _nrt=False)
def _kinematics(ctx, mesh, X, V, Acc, e, g):
    """Position, its derivative, velocity and acceleration at full point g of element e, and the
    unit tangent, the stretch and (with a tangent) the normal projector."""
    r, dr, v, acc = ctx.r, ctx.dr, ctx.v, ctx.a
    r[:] = 0.0
    dr[:] = 0.0
    v[:] = 0.0
    acc[:] = 0.0
    for l in range(mesh.dofs.shape[1]):
        i = _index(mesh.dofs[e, l])
        for a in range(3):
            r[a] += mesh.phi[l, e, g] * X[i, a]
            dr[a] += mesh.dphi[l, e, g] * X[i, a]
            v[a] += mesh.phi[l, e, g] * V[i, a]
            acc[a] += mesh.phi[l, e, g] * Acc[i, a]
    stretch = np.sqrt(dr[0] * dr[0] + dr[1] * dr[1] + dr[2] * dr[2])
    ctx.stretch = stretch
    divisor = stretch if stretch > 0.0 else np.inf  # coincident points: t = 0 (loads.unit_tangent)
    for i in range(3):
        ctx.t[i] = dr[i] / divisor
    if ctx.jac:
        for i in range(3):
            for j in range(3):
                ctx.P[i, j] = (1.0 if i == j else 0.0) - ctx.t[i] * ctx.t[j]


@njit(cache=True, _nrt=False)
def _seabed(ctx, bed, e, g):
    """The seabed's projection at full point g of element e: computed on a plane, read otherwise
    (a point on a flat part of a mesh or grid has no normal gradient: ``curved`` is off)."""
    if bed.plane.shape[0] == 4:
        r = ctx.r
        ctx.gap = (bed.plane[0] * r[0] + bed.plane[1] * r[1] + bed.plane[2] * r[2]) - bed.plane[3]
        for a in range(3):
            ctx.n[a] = bed.plane[a]
            ctx.grad_gap[a] = bed.plane[a]
            for b in range(3):
                ctx.dn[a, b] = 0.0
        ctx.curved = False
        return
    ctx.gap = bed.gap[e, g]
    curved = False
    for a in range(3):
        ctx.n[a] = bed.normal[e, g, a]
        ctx.grad_gap[a] = bed.grad_gap[e, g, a]
        for b in range(3):
            ctx.dn[a, b] = bed.dnormal[e, g, a, b]
            curved = curved or ctx.dn[a, b] != 0.0
    ctx.curved = curved


@njit(cache=True, _nrt=False)
def _water(ctx, water, index):
    """The water's kinematics at the point ``ctx.r`` and time ``ctx.time`` into the context, the point's
    row ``index`` of the water's cache (``cablefem.waves.compiled.water_cached``)."""
    ctx.eta, ctx.wet = water_cached(water, index, ctx.r, ctx.time, ctx.water_u, ctx.water_a, ctx.water_du,
                                    ctx.water_da)


@njit(cache=True, _nrt=False)
def assemble(mesh, bed, water, pts, work, state, factors, jac, held, rows, band, elements):
    """Residual rows M A + G over ``elements`` added to ``rows`` (N, 3) and, with ``jac``, the
    banded tangent of the free unknowns added to ``band`` (LAPACK's layout); state: (X, V, A, t),
    each (N, 3) and the time [s]; water: the line's sea (``cablefem.waves.compiled.Water``);
    factors: (v_x, a_x) or (v_x, a_x, h) with the step's size h [s] (``inverse_step``); held: the
    loads keep the branches the hold records hold (Newton's corrections). Kernel, so over 12
    arguments' worth of data comes in named tuples."""
    ctx = work.ctx[0]
    ctx.v_x, ctx.a_x, ctx.inv_h = factors[0], factors[1], inverse_step(factors)
    ctx.jac, ctx.held, ctx.time = jac, held, state[3]
    for k in range(pts.full_calls.shape[0]):
        ctx.full_calls[k] = pts.full_calls[k]
    for k in range(pts.reduced_calls.shape[0]):
        ctx.reduced_calls[k] = pts.reduced_calls[k]
    if pts.ddphi.shape[0] > 0 or pts.clamp[0, CLAMP_SCALE] > 0.0 or pts.clamp[1, CLAMP_SCALE] > 0.0:
        _elements(mesh, bed, water, pts, work, state, jac, rows, band, elements, True)
    else:  # the loop compiled without the bending's branches
        _elements(mesh, bed, water, pts, work, state, jac, rows, band, elements, False)


@njit(cache=True, inline="always", _nrt=False)
def _elements(mesh, bed, water, pts, work, state, jac, rows, band, elements, bends):
    """``assemble``'s loop over ``elements``; ``bends``, a constant at each call (the compiler
    drops its branches where it is False): r'' read at the full points (a Hermite line with
    bending) and the clamped ends' rows made their constraints."""
    X, V, Acc = state[0], state[1], state[2]
    ctx, out, Re, Ke = work.ctx[0], work.out[0], work.Re, work.Ke
    second = bends and pts.ddphi.shape[0] > 0
    first_clamped = bends and pts.clamp[0, CLAMP_SCALE] > 0.0
    last_clamped = bends and pts.clamp[1, CLAMP_SCALE] > 0.0
    last = mesh.dofs.shape[0] - 1
    nq, nr = mesh.dx.shape[1], mesh.rdx.shape[1]
    for element in elements:
        e = _index(element)  # unsigned: no wrap-around fix-up on the many accesses by e (banded.py)
        Re[:] = 0.0
        if jac:
            Ke[:] = 0.0
        p = pts.params[e]
        for g in range(nq):
            _kinematics(ctx, mesh, X, V, Acc, e, g)
            if second:
                _second_kinematics(ctx, out, mesh, pts.ddphi, X, e, g)
            _seabed(ctx, bed, e, g)
            if water.kind != NO_WATER:
                _water(ctx, water, element * nq + g)
            full_point(ctx, p, pts.full_old[e, g], pts.full_new[e, g], pts.full_state[e, g],
                       pts.full_hold[e, g], out)
            _add_full(Re, Ke, mesh, out, ctx, e, g, jac)
            if second:
                _add_second(Re, Ke, mesh, pts.ddphi, out, e, g, jac)
        for g in range(nr):
            _reduced_kinematics(ctx, mesh, X, V, e, g)
            reduced_point(ctx, p, pts.reduced_old[e, g], pts.reduced_new[e, g], pts.reduced_state[e, g],
                          pts.reduced_hold[e, g], out)
            _add_reduced(Re, Ke, mesh, out, e, g, jac)
        if first_clamped and e == 0:
            _clamp(Re, Ke, mesh, pts.clamp, X, e, 0, jac)
        if last_clamped and e == last:
            _clamp(Re, Ke, mesh, pts.clamp, X, e, 1, jac)
        _scatter(Re, Ke, mesh, e, jac, rows, band)


@njit(cache=True, inline="always", _nrt=False)  # a call would copy the mesh's arrays per point
def _add_full(Re, Ke, mesh, out, ctx, e, g, jac):
    """A full point's force and blocks, and the inertia m a, into the element's rows and matrix."""
    w = mesh.dx[e, g]
    m = mesh.mass[e]
    nloc = mesh.dofs.shape[1]
    f, acc, a_x = out.f, ctx.a, ctx.a_x
    for l in range(nloc):
        for a in range(3):
            Re[l, a] += w * mesh.phi[l, e, g] * (m * acc[a] - f[a])
        if jac:
            for mm in range(nloc):
                c_v = w * mesh.phi[l, e, g] * mesh.phi[mm, e, g]
                c_d = w * mesh.phi[l, e, g] * mesh.dphi[mm, e, g]
                for a in range(3):
                    for b in range(3):
                        Ke[l, a, mm, b] += c_v * out.A[a, b] + c_d * out.B[a, b]
                    Ke[l, a, mm, a] += c_v * a_x * m


@njit(cache=True, _nrt=False)
def _reduced_kinematics(ctx, mesh, X, V, e, g):
    """dr/ds and dv/ds at reduced point g of element e."""
    dr, dv = ctx.dr, ctx.dv
    dr[:] = 0.0
    dv[:] = 0.0
    for l in range(mesh.dofs.shape[1]):
        i = _index(mesh.dofs[e, l])
        for a in range(3):
            dr[a] += mesh.rdphi[l, e, g] * X[i, a]
            dv[a] += mesh.rdphi[l, e, g] * V[i, a]


@njit(cache=True, _nrt=False)
def _add_reduced(Re, Ke, mesh, out, e, g, jac):
    """A reduced point's flux and its block into the element's rows and matrix."""
    w = mesh.rdx[e, g]
    nloc = mesh.dofs.shape[1]
    for l in range(nloc):
        for a in range(3):
            Re[l, a] += w * mesh.rdphi[l, e, g] * out.N[a]
        if jac:
            for mm in range(nloc):
                c_dd = w * mesh.rdphi[l, e, g] * mesh.rdphi[mm, e, g]
                for a in range(3):
                    for b in range(3):
                        Ke[l, a, mm, b] += c_dd * out.D[a, b]


@njit(cache=True, _nrt=False)
def _scatter(Re, Ke, mesh, e, jac, rows, band):
    """An element's rows into the residual and its matrix into the band (prescribed ends left out)."""
    nloc = mesh.dofs.shape[1]
    kl, ku, lo, hi = mesh.kl, mesh.ku, mesh.lo, mesh.hi
    for l in range(nloc):
        i = _index(mesh.dofs[e, l])
        for a in range(3):
            rows[i, a] += Re[l, a]
        pi = mesh.position[i]
        if not jac or pi < lo or pi > hi:
            continue
        for mm in range(nloc):
            pj = mesh.position[_index(mesh.dofs[e, mm])]
            if pj < lo or pj > hi:
                continue
            for a in range(3):
                for b in range(3):
                    row = 3 * (pi - lo) + a
                    col = 3 * (pj - lo) + b
                    band[_index(kl + ku + row - col), _index(col)] += Ke[l, a, mm, b]


@njit(cache=True, _nrt=False)
def hold_points(pts, base_full, base_reduced, again):
    """Newton's branch corrections (``cablefem.dynamics.policy``): set the holds of ``pts`` by every load's
    hold rule at every point, comparing its branch state with the base's (``base_full``,
    ``base_reduced``: the state records where the rejected Newton step started); ``again``: keep
    what is held already too. Returns whether anything is held and the holds changed (or not
    ``again``)."""
    held, changed = False, False
    for e in range(pts.full_state.shape[0]):
        p = pts.params[e]
        for g in range(pts.full_state.shape[1]):
            h, c = _hold_full(base_full[e, g], pts.full_state[e, g], pts.full_hold[e, g], p, again)
            held, changed = held or h, changed or c
        for g in range(pts.reduced_state.shape[1]):
            h, c = _hold_reduced(base_reduced[e, g], pts.reduced_state[e, g], pts.reduced_hold[e, g], p, again)
            held, changed = held or h, changed or c
    return held and (changed or not again)


# one literal_unroll per function: numba mixes up two in one loop nest
@njit(cache=True, _nrt=False)
def _hold_full(base, state, hold, p, again):
    """Every full-point load's hold rule at one point: (anything held, holds changed)."""
    held, changed = False, False
    for rule in literal_unroll(FULL_RULES):
        h, c = rule(base, state, hold, p, again)
        held, changed = held or h, changed or c
    return held, changed


@njit(cache=True, _nrt=False)
def _hold_reduced(base, state, hold, p, again):
    """Every reduced-point load's hold rule at one point: (anything held, holds changed)."""
    held, changed = False, False
    for rule in literal_unroll(REDUCED_RULES):
        h, c = rule(base, state, hold, p, again)
        held, changed = held or h, changed or c
    return held, changed


def byte_view(records_array):
    """A record array's bytes as a flat uint8 view (copied by compiled loops, no record types)."""
    return records_array.reshape(-1).view(np.uint8)
