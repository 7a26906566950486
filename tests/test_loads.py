"""Dynamic loads: drag, added mass, seabed friction. Exact Jacobians against central finite
differences (pointwise and through the assembled LineSystem tangent) and closed-form values.

Finite differences are only valid away from the loads' kinks (gap = 0, v_n = 0, |w| = v_c,
grid lines, e = 0): every FD test state is drawn until all its points keep a margin of at least
``MARGIN`` (1e-4 m or m/s) from each of them, more than the largest step any difference takes
there (1e-5 m in r |delta| <~ 4e-5 m; 150 x 1e-7 x |delta| <~ 6e-5 m/s in v).
"""

from dataclasses import replace

import numpy as np
import pytest

from cablefem import LineType
from cablefem.errors import InputError
from cablefem.geometry import Plane, Projection, Seabed
from cablefem.loads import State, Terms, add
from cablefem.loads.added_mass import AddedMass
from cablefem.loads.contact import SeabedContact
from cablefem.loads.drag import Drag, tangential_drag_from_moordyn
from cablefem.loads.friction import (AnisotropicFriction, IsotropicFriction, SeabedFriction, friction_law,
                                     saturation)
from cablefem.model.scene import Contact, Environment, Friction
from cablefem.fem.system import LineSystem
from cablefem.loads.contact import contact_damping

from conftest import make_line

try:
    from cablefem.geometry.grid import DepthGrid
except ImportError:  # the grid seabed is optional here: plane and bowl cover the contact laws
    DepthGrid = None

RHO = 1025.0
MARGIN = 1e-4


class Bowl(Seabed):
    """Test seabed: the inside of a sphere (centre c, radius R [m]), curved everywhere, with
    exact closed-form projection d_G = R - |r - c|, d_P = (c - r)/|r - c|."""

    def __init__(self, centre, radius):
        self.centre, self.radius = np.asarray(centre, dtype=float), float(radius)

    def project(self, points):
        rel = np.asarray(points, dtype=float) - self.centre
        dist = np.linalg.norm(rel, axis=1)
        d = -rel / dist[:, None]
        gap = self.radius - dist
        grad = -(np.eye(3) - d[:, :, None] * d[:, None, :]) / dist[:, None, None]
        return Projection(gap, d, points - gap[:, None] * d, d, grad)

    def elevation(self, xy):
        rel = np.asarray(xy, dtype=float) - self.centre[:2]
        return self.centre[2] - np.sqrt(self.radius**2 - np.sum(rel**2, axis=1))


def seabeds():
    """An inclined plane (20 deg), an analytic curved bowl and, if present, a bilinear grid."""
    beds = [pytest.param(Plane.from_slope([-600.0, 0.0, -100.0], np.radians(20.0), np.pi / 2), id="plane"),
            pytest.param(Bowl([-300.0, 0.0, 4900.0], 5000.0), id="bowl")]
    if DepthGrid is not None:
        x, y = np.arange(-700.0, 101.0, 50.0), np.arange(-60.0, 61.0, 20.0)
        z = -100.0 + 0.2 * y[:, None] + 4.0 * np.sin(x / 90.0)[None, :] * np.cos(y / 45.0)[:, None]
        beds.append(pytest.param(DepthGrid(x, y, z), id="grid"))
    return beds


def normal_of(seabed, r):
    """Projection of quadrature-shaped points r (3, nel, nq): gap (nel, nq), d_P (3, nel, nq)."""
    proj = seabed.project(r.reshape(3, -1).T)
    return proj.gap.reshape(r.shape[1:]), proj.direction.T.reshape(r.shape)


def kink_margins(seabed, law, state):
    """Distances [m, m/s] of every touching point from the gap, v_n and |w| = v_c kinks."""
    gap, n = normal_of(seabed, state.r)
    touching = gap < 0
    vn = np.einsum("ceq,ceq->eq", state.v, n)
    w = state.v - vn * n
    parts = [w]
    if law.uses_axis:
        p = state.dr - np.einsum("ceq,ceq->eq", state.dr, n) * n
        q = p / np.linalg.norm(p, axis=0)
        parts = [np.einsum("ceq,ceq->eq", w, q) * q]
        parts.append(w - parts[0])
    speeds = [np.linalg.norm(part, axis=0)[touching] for part in parts]
    margins = {"gap": np.abs(gap).min(), "v_n": np.abs(vn[touching]).min(),
               "v_c": min(np.abs(s - law.v_threshold).min() for s in speeds)}
    if hasattr(seabed, "x"):  # a bilinear grid's normal jumps on grid lines
        xy = state.r[:2].reshape(2, -1)
        margins["grid"] = min(np.abs(xy[0][:, None] - seabed.x).min(),
                              np.abs(xy[1][:, None] - seabed.y).min())
    regimes = [np.count_nonzero(s < law.v_threshold) for s in speeds] + \
              [np.count_nonzero(s > law.v_threshold) for s in speeds]
    return margins, touching, regimes


def away_from_kinks(draw, seabed, law, attempts=20):
    """The first draw() = (State, ...) whose touching points all keep MARGIN from every kink and
    that has points on and off the seabed, inside and beyond the ramp (retries are rare)."""
    for _ in range(attempts):
        drawn = draw()
        margins, touching, regimes = kink_margins(seabed, law, drawn[0])
        if min(margins.values()) > MARGIN and touching.any() and (~touching).any() \
                and min(regimes[:1] + regimes[-1:]) > 0:
            return drawn
    raise AssertionError(f"no test state away from the kinks in {attempts} draws: {margins}, {regimes}")


def point_state(rng, seabed, law, nel=6, nq=4):
    """Points within 0.05-0.5 m above or below ``seabed``, random tangents and accelerations,
    velocities spread over 0.1-10 v_c so that both sides of the ramp are sampled."""
    shape = (nel, nq)
    xy = np.stack([rng.uniform(-500.0, -100.0, shape), rng.uniform(-30.0, 30.0, shape)])
    offset = rng.choice([-1.0, 1.0], shape) * rng.uniform(0.05, 0.5, shape)
    z = seabed.elevation(xy.reshape(2, -1).T).reshape(shape) + offset
    r = np.concatenate([xy, z[None]])
    dr = rng.standard_normal((3, *shape))
    dr *= rng.uniform(1.01, 1.1, shape) / np.linalg.norm(dr, axis=0)
    v = rng.standard_normal((3, *shape))
    v *= law.v_threshold * 10.0 ** rng.uniform(-1.0, 1.0, shape) / np.linalg.norm(v, axis=0)
    return State(r, dr, v, 0.1 * rng.standard_normal((3, *shape)), rng.standard_normal((3, *shape)))


def fd_block(load, state, name, h):
    """Central-difference d(force)/d(state.name), (3, 3, nel, nq), perturbing all points at once
    (every load here is pointwise in r, r', v, a)."""
    base = getattr(state, name)
    columns = []
    for b in range(3):
        step = np.zeros_like(base)
        step[b] = h
        plus = load.evaluate(replace(state, **{name: base + step}), jacobian=False).force
        minus = load.evaluate(replace(state, **{name: base - step}), jacobian=False).force
        columns.append((plus - minus) / (2 * h))
    return np.stack(columns, axis=1)


def assert_block(block, fd, tolerance):
    block = np.zeros_like(fd) if block is None else block
    scale = max(np.abs(fd).max(), np.abs(block).max(), 1e-300)
    np.testing.assert_allclose(block, fd, rtol=0, atol=tolerance * scale)


class Rubbing:
    """The seabed contact and its friction (``law``) evaluated at the same points in catalog order,
    their terms summed as ``LineSystem.evaluate`` sums a line's loads: friction reads the contact's
    normal force (``State.handed``)."""

    def __init__(self, seabed, stiffness, damping, law):
        self.seabed = seabed
        self.contact = SeabedContact(seabed, stiffness, damping)
        self.friction = SeabedFriction(law)

    def evaluate(self, state, jacobian=True):
        first = self.contact.evaluate(state, jacobian)
        second = self.friction.evaluate(state, jacobian)
        return Terms(**{name: add(getattr(first, name), getattr(second, name)) for name in Terms.__dataclass_fields__})


def drag_and_added_mass(nel, current=(0.3, -0.2, 0.05)):
    d = np.full(nel, 0.3539)
    drag = Drag(d, np.full(nel, 2.5), np.full(nel, 0.5), RHO, current)
    return drag, AddedMass(d, np.full(nel, 3.8), np.full(nel, 0.7), RHO)


def test_drag_and_added_mass_jacobians_match_finite_differences(rng):
    slope = Plane.from_slope([0.0, 0.0, -100.0], 0.2)
    state = point_state(rng, slope, IsotropicFriction(0.3, v_threshold=0.1))  # |v| 0.01-1 m/s
    # nearly at rest relative to the current, |u| = 1e-3 m/s >> h (|u| u is only C1 at u = 0,
    # where FD would be off by O(h); the value there is checked exactly below)
    state.v[:, 0, 0] = (0.3, -0.2 + 1e-3, 0.05)
    drag, added_mass = drag_and_added_mass(6)
    # the loads are smooth there: FD error O(h^2) ~ 1e-12 of the block
    for load, names in ((drag, ("r", "dr", "v")), (added_mass, ("r", "dr", "a"))):
        terms = load.evaluate(state)
        for name in names:
            block = getattr(terms, "force_" + name)
            assert_block(block, fd_block(load, state, name, 1e-6), 1e-7)


@pytest.mark.parametrize("law", [IsotropicFriction(0.3, static_scale=1.0, v_threshold=0.02),
                                 IsotropicFriction(0.3, static_scale=1.4, v_threshold=0.02),
                                 AnisotropicFriction(0.69, 1.0, static_scale=1.33, v_threshold=0.02)],
                         ids=["isotropic", "isotropic-static", "anisotropic"])
@pytest.mark.parametrize("seabed", seabeds())
def test_contact_with_friction_jacobian_matches_finite_differences(rng, seabed, law):
    nel = 6
    contact = Rubbing(seabed, np.full(nel, 3e5 * 0.3539), np.full(nel, 2e4), law)
    state, = away_from_kinks(lambda: (point_state(rng, seabed, law, nel=nel),), seabed, law)
    terms = contact.evaluate(state)
    # piecewise smooth; on each piece the FD error, O(h^2 F''') plus round-off ~ 1e-16 k |r| / h
    # (|r| ~ 2000 m on the bowl), stays below 1e-7 of the largest entry
    for name, h in (("r", 1e-5), ("dr", 1e-5), ("v", 1e-7)):
        assert_block(getattr(terms, "force_" + name), fd_block(contact, state, name, h), 1e-7)


def test_drag_on_a_line_moving_normally_is_half_rho_d_cd_v_squared_times_stretch():
    t = np.array([np.cos(0.4), np.sin(0.4), 0.0])
    stretch = 1.03
    v = 0.7 * np.array([-np.sin(0.4), np.cos(0.4), 0.0]) + 0.2 * np.array([0.0, 0.0, 1.0])
    state = State(np.zeros((3, 1, 1)), (stretch * t)[:, None, None], v[:, None, None])
    drag = Drag([0.1], [1.2], [0.3], RHO)
    expected = -stretch * 0.5 * RHO * 0.1 * 1.2 * np.linalg.norm(v) * v
    np.testing.assert_allclose(drag.evaluate(state).force[:, 0, 0], expected, rtol=1e-14)


def test_drag_vanishes_for_a_line_moving_with_the_current(rng):
    current = np.array([0.5, -0.3, 0.1])
    dr = rng.standard_normal((3, 4, 3))
    state = State(np.zeros((3, 4, 3)), dr, np.broadcast_to(current[:, None, None], (3, 4, 3)).copy())
    terms = drag_and_added_mass(4, current)[0].evaluate(state)
    assert np.all(terms.force == 0.0)
    assert np.all(terms.force_v == 0.0)  # d(|w| w)/dw = 0 at w = 0: no spurious damping


def test_tangential_drag_from_moordyn_multiplies_by_pi():
    assert tangential_drag_from_moordyn(0.4) == pytest.approx(np.pi * 0.4, rel=1e-15)


def test_added_mass_matrix_is_rho_area_ca_projectors_times_stretch(rng):
    dr = rng.standard_normal((3, 2, 2))
    a = rng.standard_normal((3, 2, 2))
    load = AddedMass([0.2, 0.2], [1.0, 1.0], [0.5, 0.5], RHO)
    terms = load.evaluate(State(np.zeros_like(dr), dr, a=a))
    stretch = np.linalg.norm(dr, axis=0)
    t = dr / stretch
    T = t[:, None] * t[None, :]
    P = np.eye(3)[:, :, None, None] - T
    expected = stretch * RHO * np.pi * 0.04 / 4 * (1.0 * P + 0.5 * T)
    np.testing.assert_allclose(-terms.force_a, expected, rtol=1e-13)
    np.testing.assert_allclose(terms.force, np.einsum("abeq,beq->aeq", terms.force_a, a), rtol=1e-12)
    np.testing.assert_allclose(load.matrix(dr), expected, rtol=1e-13)
    assert load.evaluate(State(np.zeros_like(dr), dr)).force is None  # statics: no added mass


def test_saturation_is_kinetic_beyond_threshold_and_a_linear_ramp_below():
    speeds = np.array([0.001, 0.004, 0.009, 0.011, 0.05, 3.0])
    direction = np.array([0.6, 0.0, 0.8])
    phi, _ = saturation(direction[:, None] * speeds, 0.01, static_scale=1.5)
    expected = np.where(speeds < 0.01, 1.5 * speeds / 0.01, 1.0)
    np.testing.assert_allclose(np.linalg.norm(phi, axis=0), expected, rtol=1e-14)
    np.testing.assert_allclose(phi / np.linalg.norm(phi, axis=0), direction[:, None] + 0 * speeds, rtol=1e-14)


def slope_contact(law, damping=0.0):
    """A 20 deg slope rising towards azimuth 0.7, ground stiffness 1e5 N/m^2 per unit length: the
    seabed, and the contact with friction by ``law`` on it (``Rubbing``)."""
    seabed = Plane.from_slope([0.0, 0.0, -50.0], np.radians(20.0), azimuth=0.7)
    return seabed, Rubbing(seabed, [1e5], [damping], law)


def friction_force(rubbing, r, dr, v):
    """Friction at single points (n, 3): the friction load's force on the contact's normal force, (n, 3)."""
    state = State(r.T[:, :, None], dr.T[:, :, None], v.T[:, :, None])
    rubbing.contact.evaluate(state, jacobian=False)
    return rubbing.friction.evaluate(state, jacobian=False).force[:, :, 0].T


def test_isotropic_friction_is_mu_n_beyond_vc_and_ramps_linearly_below():
    law = IsotropicFriction(0.4, static_scale=1.25, v_threshold=0.05)
    seabed, contact = slope_contact(law)
    n = seabed.normal
    along = np.cross(n, [0.0, 0.0, 1.0])
    along /= np.linalg.norm(along)
    speeds = np.array([0.01, 0.03, 0.049, 0.051, 0.2, 2.0])
    r = np.tile(seabed.point - 0.2 * n, (len(speeds), 1))  # buried 0.2 m: N = 1e5 * 0.2
    F = friction_force(contact, r, np.tile([1.0, 0, 0], (len(speeds), 1)),
                       speeds[:, None] * along + 0.3 * n)  # opening normal velocity: no v_pi part
    N = 1e5 * 0.2
    expected = np.where(speeds < 0.05, 1.25 * 0.4 * N * speeds / 0.05, 0.4 * N)
    np.testing.assert_allclose(np.linalg.norm(F, axis=1), expected, rtol=1e-12)
    np.testing.assert_allclose(F / np.linalg.norm(F, axis=1)[:, None], -np.tile(along, (6, 1)), atol=1e-12)


def test_friction_lies_in_the_seabed_plane_on_a_20_degree_slope(rng):
    seabed, contact = slope_contact(IsotropicFriction(0.3), damping=5e3)
    r = seabed.point + rng.uniform(-20, 20, (30, 3)) * [1, 1, 0]
    r[:, 2] = seabed.elevation(r[:, :2]) - 0.1
    v = rng.standard_normal((30, 3))
    F = friction_force(contact, r, rng.standard_normal((30, 3)), v)
    assert np.abs(F).max() > 1e3  # the friction is really there
    np.testing.assert_allclose(F @ seabed.normal, 0.0, atol=1e-11 * np.abs(F).max())
    v_plane = v - (v @ seabed.normal)[:, None] * seabed.normal
    assert np.all(np.einsum("nc,nc->n", F, v_plane) < 0)  # opposes the sliding


@pytest.mark.parametrize("speed", [0.5, 0.02])  # kinetic, and inside the ramp (v_c = 0.05)
def test_anisotropic_friction_is_mu_axial_along_and_mu_transverse_across_on_a_slope(speed):
    law = AnisotropicFriction(mu_axial=0.5, mu_transverse=1.2, static_scale=1.0, v_threshold=0.05)
    seabed, contact = slope_contact(law)
    n = seabed.normal
    q = np.cross(n, [0.3, 1.0, 0.0])
    q /= np.linalg.norm(q)  # an axial direction in the slope, neither level nor down-slope
    across = np.cross(n, q)
    r = (seabed.point - 0.25 * n)[None]
    dr = (1.05 * (np.cos(0.3) * q + np.sin(0.3) * n))[None]  # the line leaves the slope at 17 deg
    N = 1e5 * 0.25
    scale = min(speed / 0.05, 1.0)
    for direction, mu in ((q, 0.5), (across, 1.2)):
        F = friction_force(contact, r, dr, (speed * direction + 0.1 * n)[None])[0]
        np.testing.assert_allclose(F, -mu * N * scale * direction, atol=1e-9 * N)


def test_anisotropic_friction_on_a_line_normal_to_the_seabed_is_all_transverse():
    law = AnisotropicFriction(mu_axial=0.5, mu_transverse=1.2, v_threshold=0.05)
    seabed, contact = slope_contact(law)
    n = seabed.normal
    state = State((seabed.point - 0.25 * n)[:, None, None], (1.02 * n)[:, None, None],
                  np.array([1.0, 0.0, 0.0])[:, None, None])
    contact.contact.evaluate(state)
    terms = contact.friction.evaluate(state)  # q is undefined: taken as 0, with zero derivatives
    friction = terms.force[:, 0, 0]
    v_plane = np.array([1.0, 0, 0]) - n[0] * n
    np.testing.assert_allclose(friction, -1.2 * 1e5 * 0.25 * v_plane / np.linalg.norm(v_plane), rtol=1e-12)
    assert np.all(np.isfinite(terms.force_r)) and np.all(terms.force_dr == 0.0)


def test_friction_is_absent_in_statics_and_off_the_seabed():
    seabed, contact = slope_contact(IsotropicFriction(0.3))
    n = seabed.normal
    r = np.array([seabed.point - 0.2 * n, seabed.point + 0.2 * n])
    dr = np.tile([1.0, 0.0, 0.0], (2, 1))
    statics = contact.evaluate(State(r.T[:, :, None], dr.T[:, :, None]))
    np.testing.assert_allclose(statics.force[:, 0, 0], 1e5 * 0.2 * n, rtol=1e-12)
    assert statics.force_v is None
    F = friction_force(contact, r, dr, np.tile([1.0, 0.5, 0.0], (2, 1)))
    assert np.linalg.norm(F[0]) > 0 and np.all(F[1] == 0.0)


def test_friction_law_follows_the_scene_model():
    assert friction_law(Friction()) is None
    assert friction_law(Friction(model="isotropic", mu=0.4)) == IsotropicFriction(0.4, 1.0, 0.01)
    law = friction_law(Friction(model="anisotropic", static_scale=1.33))
    assert (law.mu_axial, law.mu_transverse, law.static_scale) == (0.69, 1.0, 1.33)
    with pytest.raises(InputError, match="v_threshold"):
        friction_law(Friction(model="isotropic", v_threshold=0.0))
    with pytest.raises(InputError, match="friction.model"):
        friction_law(Friction(model="coulomb"))


# ---------------------------------------------------------------- assembled system
ROPE = LineType("rope", diameter=0.15, mass=40.0, EA=2.0e6, damping=0.05, Cd_normal=2.0,
                Cd_tangential=0.4, Ca_normal=1.0, Ca_tangential=0.5)


def system_with_all_loads(seabed, law, order, profile=None, line_type=ROPE):
    """A soft rope (so that tension does not swamp the other loads' share of the tangent) with
    drag in a current (uniform, or ``profile``), added mass and contact with friction; LineSystem's
    own contact is off. ``order`` "hermite": on Hermite elements (with bending where ``line_type``
    has EI > 0)."""
    line = make_line(line_type, order, elements=12, length=590.0)  # taut: every point stretched >= 1.7 %
    env = Environment(current=(0.2, 0.1, 0.0), current_profile=profile)
    nel = line.segments[0].elements
    props = dict(diameter=np.full(nel, ROPE.diameter), mass=np.full(nel, ROPE.mass))
    contact = SeabedContact(seabed, 3e5 * props["diameter"], contact_damping(Contact(), props))
    loads = (Drag(props["diameter"], np.full(nel, 2.0), np.full(nel, 0.4), env.water_density, env.current,
                  profile=profile),
             AddedMass(props["diameter"], np.full(nel, 1.0), np.full(nel, 0.5), env.water_density),
             contact, SeabedFriction(law))
    return LineSystem(line, seabed, Contact(stiffness=0.0), env, extra_loads=loads)


def line_state(system, rng, law):
    """X along the seabed for the first half (up to 0.35 m above or 0.25 m below), rising to the fairlead;
    nodal velocities of 0.03-3 v_c times a normal deviate; random accelerations."""
    fem, seabed = system.fem, system.seabed

    def positions(s):
        f = s / system.line.unstretched_length
        x, y = -600.0 + 600.0 * f, 3.0 * np.sin(3 * np.pi * f)
        bed = seabed.elevation(np.column_stack([x, y]))
        rise = np.clip((f - 0.5) / 0.5, 0.0, None) ** 2 * -seabed.elevation(np.zeros((1, 2)))
        return np.column_stack([x, y, bed + 0.3 * np.sin(8 * np.pi * f) + 0.05 + rise])

    X = fem.interpolate(positions)

    def draw():
        V = rng.standard_normal(X.shape) * law.v_threshold * 10.0 ** rng.uniform(-1.5, 0.5, (len(X), 1))
        A = rng.standard_normal(X.shape)
        return system.state(X, V, A), X, V, A

    return away_from_kinks(draw, seabed, law)


@pytest.mark.parametrize("order", [1, 2])
@pytest.mark.parametrize("seabed", seabeds())
@pytest.mark.parametrize("law", [IsotropicFriction(0.3, 1.2, 0.05),
                                 AnisotropicFriction(0.69, 1.0, 1.33, 0.05)], ids=["isotropic", "anisotropic"])
def test_line_system_tangent_with_all_dynamic_loads_matches_finite_differences(rng, seabed, law, order):
    system = system_with_all_loads(seabed, law, order)
    state, X, V, A = line_state(system, rng, law)
    # tension away from its e = 0 kink (and T > 0: beta de/dt is below 1e-3 here)
    assert np.linalg.norm(state.dr, axis=0).min() > 1.01

    assert_tangent_matches_finite_differences(system, state, X, V, A, rng.standard_normal((3, *X.shape)))


def assert_tangent_matches_finite_differences(system, state, X, V, A, directions):
    """The assembled tangent of ``system`` (dG/dX, dG/dV, dG/dA and a BDF2-like combination)
    against central differences of its residual along ``directions`` (k, N, 3)."""

    def residual(dX, dV, dA):
        return system.residual(X + dX, V + dV, A + dA).ravel()

    def tangent(cv, ca):
        return system.matrix(system.evaluate(state, velocity_factor=cv, acceleration_factor=ca)[1],
                             free_only=False).toarray()

    K0 = tangent(0.0, 0.0)
    cv, ca = 150.0, 2.0e4  # BDF2-like factors for dt = 0.01 s
    zero = np.zeros_like(X)
    # steps: 1e-5 where only X or A moves (round-off of |r - c| ~ 5000 m on the bowl needs a
    # large h; the residual is linear in A), 1e-7 where V moves (cv h |d| < MARGIN)
    for matrix, step, h in ((K0, lambda d: (d, zero, zero), 1e-5),
                            (tangent(1.0, 0.0) - K0, lambda d: (zero, d, zero), 1e-7),
                            (tangent(0.0, 1.0) - K0, lambda d: (zero, zero, d), 1e-5),
                            (tangent(cv, ca), lambda d: (d, cv * d, ca * d), 1e-7)):
        for d in directions:
            plus = residual(*(h * x for x in step(d)))
            minus = residual(*(-h * x for x in step(d)))
            fd = (plus - minus) / (2 * h)
            # O(h^2) truncation and ~1e-16 |R| / h round-off, both < 1e-6 of |K d|
            np.testing.assert_allclose(matrix @ d.ravel(), fd, rtol=0, atol=1e-6 * np.abs(fd).max())


# ---------------------------------------------------------------- soil (points below the surface)
#: the soil of the tests: rope bar diameter 0.15 m, su = 2 kPa + 1.5 kPa/m, rui2025's widths and N_c 7.6
SOIL_BAR = 0.15


def soil_system(seabed, order):
    """The soft rope of ``system_with_all_loads`` with the soil as its only load besides tension
    and weight (no contact: a line in soil has none)."""
    from cablefem.loads.soil import Soil

    line = make_line(ROPE, order, elements=12, length=590.0)
    nel = line.segments[0].elements
    soil = Soil(seabed, np.full(nel, 8.0 * SOIL_BAR), np.full(nel, 2.5 * 7.6 * SOIL_BAR), 1.0 / SOIL_BAR,
                2.0 / SOIL_BAR, 2.0e3, 1.5e3, np.full(nel, SOIL_BAR))
    return LineSystem(line, seabed, Contact(stiffness=0.0), Environment(), extra_loads=[soil])


def soil_margins(system, soil):
    """Distances [m] of every point from the soil's kinks: depth 0 and d_b, |e_t| = 1/k_t,
    |e_n| = 1/k_n; and the counts of elastic and plastic points along and across."""
    state = system.state(np.asarray(system._soil_X))
    depth, _ = soil.depth(state.r)
    e_t, _, _, _, _, _, size, _, _ = soil.offsets(state)
    margins = {"surface": np.abs(depth).min(), "engaged": np.abs(depth - soil.ramp).min(),
               "tangential": np.abs(np.abs(e_t) - 1.0 / soil.k_t).min(),
               "normal": np.abs(size - 1.0 / soil.k_n).min()}
    below = depth > 0.0
    counts = [np.count_nonzero(below & (np.abs(soil.k_t * e_t) < 1)), np.count_nonzero(below & (np.abs(soil.k_t * e_t) > 1)),
              np.count_nonzero(below & (soil.k_n * size < 1)), np.count_nonzero(below & (soil.k_n * size > 1)),
              np.count_nonzero(below & (depth < soil.ramp)), np.count_nonzero(~below)]
    return margins, counts


def soil_state(system, rng, attempts=20):
    """X with its first half 0-1.2 m below the seabed (some points inside the top d_b, some above
    the surface), rising to the fairlead; committed anchors offset from the full points by 0.03-3
    yield offsets, so that points are elastic and plastic along and across the line. Returns
    (state, X, V, A) away from the kinks (``soil_margins`` > MARGIN), V and A random."""
    fem, seabed = system.fem, system.seabed
    soil = system.load("soil")

    def positions(s):
        f = s / system.line.unstretched_length
        x, y = -600.0 + 600.0 * f, 3.0 * np.sin(3 * np.pi * f)
        bed = seabed.elevation(np.column_stack([x, y]))
        rise = np.clip((f - 0.5) / 0.5, 0.0, None) ** 2 * -seabed.elevation(np.zeros((1, 2)))
        return np.column_stack([x, y, bed - 0.55 - 0.6 * np.sin(7 * np.pi * f) + rise])

    X = fem.interpolate(positions)
    system._soil_X = X
    r = fem.full.interpolate(X)[0].reshape(fem.full.s.shape + (3,))
    old, new = system.history["full"]
    for _ in range(attempts):
        scale = 10.0 ** rng.uniform(-1.5, 0.5, r.shape[:2] + (1,)) * SOIL_BAR
        old["soil"]["anchor"] = r + scale * rng.standard_normal(r.shape)
        new[...] = old
        margins, counts = soil_margins(system, soil)
        if min(margins.values()) > MARGIN and min(counts) > 0:
            V, A = rng.standard_normal(X.shape), rng.standard_normal(X.shape)
            return system.state(X, V, A), X, V, A
    raise AssertionError(f"no soil test state away from the kinks in {attempts} draws: {margins}, {counts}")


def test_the_seabed_damper_engages_over_its_ramp_and_has_no_jump():
    """f_z = k p + c s(p) |v_z| for a point at penetration p closing at v_z, s = min(p / delta, 1)
    (``cablefem.loads.contact``): no damping at the surface (the force continuous where Eq. 11's jumps
    by c |v_z|), half at delta / 2, all of it below delta; dF/dr and dF/dv are the force's own
    (finite differences), and delta is half the penetration at which the spring carries the weight."""
    from cablefem.loads.contact import ramp_depth

    k, c, delta, vz = 1e5, 2e4, 0.01, -0.1
    seabed = Plane((0.0, 0.0, -100.0), (0.0, 0.0, 1.0))
    contact = SeabedContact(seabed, [k], [c], opening=True, ramp=[delta])

    def force(p, v=vz, jacobian=False):
        state = State(r=np.array([0.0, 0.0, -100.0 - p]).reshape(3, 1, 1),
                      dr=np.array([1.0, 0.0, 0.0]).reshape(3, 1, 1), v=np.array([0.0, 0.0, v]).reshape(3, 1, 1))
        return contact.evaluate(state, jacobian=jacobian)

    for p, share in ((1e-12, 0.0), (delta / 2, 0.5), (0.02, 1.0)):
        assert force(p).force[2, 0, 0] == pytest.approx(k * p + c * share * -vz, rel=1e-6, abs=1e-6)
    terms, h = force(delta / 4, jacobian=True), 1e-7
    slope_r = -(force(delta / 4 + h).force[2, 0, 0] - force(delta / 4 - h).force[2, 0, 0]) / (2 * h)
    slope_v = (force(delta / 4, vz + h).force[2, 0, 0] - force(delta / 4, vz - h).force[2, 0, 0]) / (2 * h)
    assert terms.force_r[2, 2, 0, 0] == pytest.approx(slope_r, rel=1e-6)
    assert terms.force_v[2, 2, 0, 0] == pytest.approx(slope_v, rel=1e-6)
    props = {"mass": np.array([113.35]), "area": np.array([np.pi * 0.0766 ** 2 / 4]), "diameter": np.array([0.0766])}
    weight = (113.35 - 1025.0 * np.pi * 0.0766 ** 2 / 4) * 9.81
    assert ramp_depth(Contact(stiffness=3e6), props, Environment(water_density=1025.0, gravity=9.81))[0] == \
        pytest.approx(weight / (2 * 3e6 * 0.0766), rel=1e-12)
