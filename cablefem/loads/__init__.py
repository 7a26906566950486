"""Loads on a line: one module per physical force, composed by a scene.

A load is an object with ``evaluate(state, jacobian) -> Terms``: it takes the
kinematics at the quadrature points and returns a force per unit unstretched
length (entering the weak form as -int f . phi ds) and/or a flux (the
internal force, entering as int N . phi' ds) and, on Hermite elements, a
moment (entering as int Q . phi'' ds: the bending load), with their
derivatives when ``jacobian`` is true. The solver knows nothing of which
loads exist.
"""

from dataclasses import dataclass, field

import numpy as np


@dataclass
class State:
    """Kinematics at quadrature points, each (3, n_elements, n_quadrature) [SI].

    r: position, dr: dr/ds; v, dv: velocity and its s-derivative (None in
    statics); a: acceleration (None unless an integrator supplies it); t: time [s]; ddr:
    d^2 r/ds^2 at the full points of a line on Hermite elements (None otherwise); X: the state's
    rows (N, 3) it was interpolated from (the clamped ends' constraint reads them).
    A load evaluated at the reduced quadrature (``rule = "reduced"``) gets ``reduced``, a load at
    vertices (``rule = "node"``) ``nodes``: the same kinematics (3, k) at the line's joints.
    old, new: the history of the points (record arrays (nel, nq) of the catalog's history
    dtype, ``cablefem.loads.catalog``): a load with history reads its committed values from
    ``old[name]`` and writes its trial values to ``new[name]``.
    handed: what a load hands to the loads after it at these points, under its name (the numpy
    twin of its scratch in the compiled point context; ``LoadSpec.reads``): the contact's
    ``NormalForce``, which friction reads. inv_h: 1 / the size [1/s] of the step being taken (0 in
    statics), for a load whose history evolves in time (``cablefem.loads.rope``).
    """

    r: np.ndarray
    dr: np.ndarray
    v: np.ndarray | None = None
    dv: np.ndarray | None = None
    a: np.ndarray | None = None
    t: float = 0.0
    reduced: "State | None" = None  # the same kinematics at the reduced quadrature points
    nodes: "State | None" = None  # at the vertices of the line's joints (3, k)
    old: np.ndarray | None = None
    new: np.ndarray | None = None
    handed: dict = field(default_factory=dict)
    inv_h: float = 0.0
    ddr: np.ndarray | None = None
    X: np.ndarray | None = None


@dataclass
class Terms:
    """What a load contributes at quadrature points.

    force, flux, moment: (3, nel, nq) (the moment against phi'', Hermite elements only). Jacobian
    blocks (3, 3, nel, nq), block[a, b] = d(component a) / d(variable b): force_r, force_dr,
    force_v, force_dv, force_a, flux_dr, flux_dv, flux_ddr, moment_dr, moment_ddr (ddr: r'').
    None means zero.
    """

    force: np.ndarray | None = None
    flux: np.ndarray | None = None
    force_r: np.ndarray | None = None
    force_dr: np.ndarray | None = None
    force_v: np.ndarray | None = None
    force_dv: np.ndarray | None = None
    force_a: np.ndarray | None = None
    flux_dr: np.ndarray | None = None
    flux_dv: np.ndarray | None = None
    moment: np.ndarray | None = None
    flux_ddr: np.ndarray | None = None
    moment_dr: np.ndarray | None = None
    moment_ddr: np.ndarray | None = None


def unit_tangent(dr):
    """Unit tangent t = r'/|r'| (3, ...), the stretch |r'| (...) and |r'| as a divisor (...) of
    dr/ds (3, ...): where two points of the line coincide (|r'| = 0: a fold, a coincident start)
    the divisor is infinite, so t and every quotient by it are 0 there and a load that scales with
    the stretch or acts along t gives nothing."""
    stretch = np.sqrt(np.einsum("c...,c...->...", dr, dr))
    divisor = np.where(stretch > 0.0, stretch, np.inf)
    return dr / divisor, stretch, divisor


def outer(a, b):
    """Pointwise outer products of (3, ...) arrays, shape (3, 3, ...)."""
    return a[:, None] * b[None, :]


def compose(a, b):
    """Pointwise matrix product of (3, 3, ...) blocks."""
    return np.einsum("ab...,bc...->ac...", a, b)


def identity_like(x):
    """The 3x3 identity broadcast to the trailing shape of x (3, ...)."""
    eye = np.eye(3).reshape((3, 3) + (1,) * (x.ndim - 1))
    return np.broadcast_to(eye, (3, 3) + x.shape[1:])


def add(a, b):
    """Sum of two optional arrays (None is zero)."""
    if a is None:
        return b
    if b is None:
        return a
    return a + b


@dataclass(frozen=True)
class LoadSpec:
    """How a load presents itself to the compiled path and to the rest of the code.

    name: its key in every record (``p.<name>.<field>``); rule: "full" or "reduced" (the
    quadrature its points use, ``cablefem.fem.discretisation.LineFEM``) or "node" (a concentrated force at
    vertices, parameters per vertex: ``cablefem.loads.points``); params: numpy dtype fields of its
    per-element (per-vertex) parameters (an ``active`` flag is added); kernel: the compiled point function
    ``kernel(ctx, p, old, new, state, hold, out)`` that adds the load at one point (see
    ``cablefem.compiled.kernels``); state / hold / history: dtype fields per point (written each
    evaluation / read / read from ``old`` and written to ``new``, committed on accepted steps);
    hold_rule: compiled ``rule(base, state, hold, p, again) -> (held, changed)`` choosing the
    holds after a rejected Newton step, or None; scratch: dtype fields of the kernel's working
    values at a point, laid in the point context under its name (``ctx.<name>.<field>``): a kernel
    writes only its own scratch, and reads another load's only where it names that load in
    ``reads`` (what that load hands on, documented at its scratch); reads: the loads of the same
    rule, earlier in the catalog, whose scratch it reads at a point (friction reads the contact's
    normal force): it is built only for a line that has them; reference: the numpy face's class,
    whose optional ``energy(state)`` is the load's potential energy [J/m] per point (nel, nq) (a
    node load's [J] per vertex (k,)), summed by ``LineSystem.energy`` for statics' line search;
    frames: history fields written to VTK frames;
    build: ``build(setting) -> load or None``, the load a line of a scene gets
    (``cablefem.fem.system.Setting``; None: the scene does not need it); section and keys: the scene
    table the load reads (``[section]`` in TOML) and its keys with their converters
    (``cablefem.io.validate``), which ``setting.keys`` holds; required: the keys that table must have."""

    name: str
    rule: str
    params: tuple
    kernel: object
    reference: type
    state: tuple = ()
    hold: tuple = ()
    history: tuple = ()
    hold_rule: object = None
    scratch: tuple = ()
    reads: tuple = ()
    frames: tuple = field(default=())
    build: object = None
    section: str | None = None
    keys: dict = field(default_factory=dict)
    required: tuple = ()
