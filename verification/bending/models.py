"""The bending study's lines, their static solves, natural frequencies and free vibrations.

Every line is one segment on Hermite elements, clamped at its anchor (the origin of its frame) along
+x unless said otherwise. The static beams stand in air 1 m above the still water with a mass of
1e-9 kg/m (their weight 1e-8 N/m against loads of ~1 N); the vibrating ones are neutrally buoyant,
50 m down (no weight, no drag or added mass: the statics' loads). Newton is cablefem's
(``cablefem.statics.newton``, the watchdog of a bending line), its residual relative to the case's
own force scale.
"""

import numpy as np
from scipy.linalg import eig

from cablefem.fem import clamp
from cablefem.fem.system import LineSystem
from cablefem.geometry import Horizontal
from cablefem.model.line import Joint, Line, LineType, Segment
from cablefem.model.scene import Contact, Environment
from cablefem.statics.newton import newton

GRAVITY = 9.81  # m/s^2
WATER_DENSITY = 1025.0  # kg/m^3
ENVIRONMENT = Environment(water_density=WATER_DENSITY, gravity=GRAVITY)
SEABED = Horizontal(1000.0)  # far below every line: no contact
IN_AIR = np.array([0.0, 0.0, 1.0])  # the static beams' clamp
IN_WATER = np.array([0.0, 0.0, -50.0])  # the vibrating ones'
WEIGHTLESS = 1e-9  # kg/m
TOLERANCE = 1e-12  # Newton's residual relative to the case's force scale


def neutral_mass(diameter):
    """The mass per length [kg/m] of a line of ``diameter`` [m] that floats in the water at any depth."""
    return WATER_DENSITY * np.pi * diameter**2 / 4.0


def line_system(n, L, EI, EA, mass, origin=IN_AIR, diameter=0.01, tangents=((1.0, 0.0, 0.0), None),
                free_end=True, tip_mass=0.0, end=None):
    """The ``LineSystem`` of a line of n Hermite elements and length L [m] from ``origin`` along +x
    (to ``end`` if given: a prescribed fairlead), EI [N m^2], EA [N], mass [kg/m], with a point of
    ``tip_mass`` [kg] at a free end; on the kernel (the compiled face)."""
    kind = LineType("beam", diameter, mass, EA, EI=EI)
    end = origin + np.array([L, 0.0, 0.0]) if end is None else np.asarray(end, dtype=float)
    joints = ((1, Joint("tip", mass=tip_mass)),) if tip_mass else ()
    line = Line("beam", origin, end, (Segment(kind, L, n),), element="hermite", tangents=tangents,
                prescribed=(True, not free_end), joints=joints)
    return LineSystem(line, SEABED, Contact(), ENVIRONMENT)


def straight(system):
    """The state (N, 3) of the line straight from its anchor to its fairlead, uniformly stretched."""
    line = system.line
    chord = (line.fairlead - line.anchor) / line.unstretched_length
    return clamp.satisfy(system.clamps, system.fem.interpolate(lambda s: line.anchor + s[:, None] * chord))


def solve(system, X, scale):
    """Newton from X (N, 3), the residual relative to ``scale`` [N]: (X, iterations, converged)."""
    X, iterations, _, _, converged = newton(system, X, TOLERANCE, max_iterations=100, scale=scale)
    return X, iterations, converged


def tip(system, X):
    """The free end's position (3,) relative to the clamp."""
    return X[system.fem.fairlead_dof] - system.line.anchor


def clamp_curvature(system, X):
    """The curvature [1/m] at the anchor (the clamp), from the first element's r''."""
    from cablefem.runs.curvature import curvature_at

    return float(curvature_at(system, X, np.array([0.0]))[0])


def _linearised(system, X):
    """The statics' tangent and the consistent mass on the free rows at X (dense), the mass's clamped
    rows projected as the loads' are (``cablefem.fem.clamp``)."""
    fem = system.fem
    _, blocks = system.evaluate(system.state(X))
    M = fem.vector_mass(system.props["mass"])
    if system.clamps:
        M = clamp.project(system.clamps, M, fem)
    return system.matrix(blocks).toarray(), M.toarray()


def frequencies(system, X, count):
    """The ``count`` lowest natural frequencies [rad/s] of the line linearised at X (N, 3): the
    generalised eigenvalues of the statics' tangent and the consistent mass on the free rows (a clamped
    tangent's constraint rows have no mass: their eigenvalues are infinite and dropped)."""
    values = eig(*_linearised(system, X), right=False)
    finite = np.isfinite(values) & (np.abs(values.imag) <= 1e-9 * np.abs(values.real).max())
    omega2 = np.sort(values[finite].real)
    return np.sqrt(np.abs(omega2[:count])) * np.sign(omega2[:count])


def first_mode(system, X, axis=2):
    """The eigenvector (N, 3) of the lowest mode of the line linearised at X that moves along ``axis``
    (the modes come in pairs, one in each plane through the line), zero on fixed rows, its largest
    displacement 1."""
    fem = system.fem
    values, vectors = eig(*_linearised(system, X))
    shapes = vectors.real.T.reshape(len(values), -1, 3)
    along = np.abs(shapes[:, :, axis]).max(axis=1) > 0.5 * np.abs(shapes).max(axis=(1, 2))
    finite = np.isfinite(values) & (values.real > 0) & along
    k = np.flatnonzero(finite)[np.argmin(values.real[finite])]
    mode = np.zeros((fem.n_dofs, 3))
    mode[fem.free_dofs] = shapes[k]
    positions = mode[: fem.n_vertices]
    return mode / np.abs(positions).max()


def free_vibration(system, X0, integrator, dt, duration, **options):
    """The tip's displacement along z (m,) [m] at each step of a free vibration from rest at X0 (N, 3)
    with ``integrator`` (a class of ``cablefem.dynamics.registry.INTEGRATORS``), compiled; and the times (m,)."""
    fixed = system.line.fairlead.copy()
    zero = np.zeros(3)
    integ = integrator(system, X0, lambda t: (fixed, zero, zero), dt=dt, tolerance=1e-10, **options)
    rest = system.line.anchor[2]
    times = dt * np.arange(1, int(round(duration / dt)) + 1)
    heights = []
    for t in times:
        integ.march(np.array([t]))
        heights.append(integ.X[system.fem.fairlead_dof, 2] - rest)
    return np.array(heights), times


def period(signal, times):
    """The mean period [s] of a signal (m,) at ``times`` from its upward zero crossings (linearly
    interpolated); None with fewer than two."""
    up = np.flatnonzero((signal[:-1] < 0.0) & (signal[1:] >= 0.0))
    crossings = times[up] - signal[up] * (times[up + 1] - times[up]) / (signal[up + 1] - signal[up])
    return float(np.mean(np.diff(crossings))) if len(crossings) >= 2 else None


def clamp_moment(system, X):
    """The magnitude [N m] of the moment the anchor's clamp exerts (``clamp.reaction_moments``)."""
    return float(np.linalg.norm(clamp.reaction_moments(system, X)[0]))
