"""The load catalog (issue 15): for every load in it, the compiled face equals the numpy face
(residual and tangent to round-off) and the numpy face's tangent equals finite differences; the
records and the loads' scratch are laid out by name, a load reads another's scratch only where it
says so, the line's potential energy is what the catalog's loads give, and a load the catalog does
not know is refused loudly."""

from dataclasses import replace

import numpy as np
import pytest

from cablefem.compiled import kernels
from cablefem.compiled.evaluator import FusedEvaluator, pack_params
from cablefem.geometry import Plane
from cablefem.loads import catalog
from cablefem.model.line import Joint, Segment
from cablefem.loads.current import CurrentProfile
from cablefem.loads.friction import IsotropicFriction
from cablefem.model.scene import Contact, Friction
from cablefem.fem.system import LineSystem
from cablefem.loads.morison import Morison
from cablefem.waves import Sea
from cablefem.waves.grid import CurrentGrid

from rope_cases import rope_state, rope_system
from test_loads import (ROPE, assert_tangent_matches_finite_differences, line_state, soil_state, soil_system,
                        system_with_all_loads)

#: the rope's laws besides its table with a constant BA (``tests/rope_cases.py``), MoorDyn-C's slack law, and
#: the table on a line that bends, compressed (a rod pushes: its law carried into compression at the slope EA)
ROPE_VARIANTS = ["damping_table", "viscoelastic", "load_dependent", "syrope", "syrope_exp", "slack", "rod"]

#: every catalog load, the two that see the current once more in a current varying with depth, the
#: contact and its friction with the seabed's damper acting on points moving out too, and engaging over
#: a depth that holds most of the penetrating points inside its ramp, in waves (the
#: Morison load is the line's in waves; points see the waves too), with a current on a grid varying in
#: time besides (MoorDyn-C's Currents 5), and the rope's laws
NAMES = [spec.name for spec in catalog.CATALOG] + ["drag+profile", "points+profile", "contact+opening",
                                                   "friction+opening", "contact+ramp", "friction+ramp",
                                                   "morison+profile", "points+waves",
                                                   "points+waves-profile", "morison+grid", "points+waves-grid"] \
    + [f"rope+{kind}" for kind in ROPE_VARIANTS]
#: the step of the tests' evaluations [s]: a rope's slow strain steps over it (``cablefem.loads.rope``)
H = 0.05
#: two components over the test line (its top at the surface: some points there are above the crests)
SEA = Sea.from_components([1.5, 0.6], [2 * np.pi / 9.0, 1.1], [0.35, -0.5], [0.4, 2.0], 100.0)
#: the same sea with a current on a grid over the test line (x, z) and beyond it in y (held), three times
_AXES = (np.array([-900.0, -500.0, -200.0, 50.0]), np.array([-20.0, 20.0]), np.array([-130.0, -60.0, -20.0, 5.0]))
SEA_GRID = replace(SEA, current=CurrentGrid(*_AXES, 4.0, np.random.default_rng(7).uniform(-0.8, 0.8, (4, 2, 4, 3, 3))))
#: a sheared current over the test line's heights (about -100 m to the surface, the clump near the
#: seabed and the buoy at the surface both on a sloping piece), bending at four heights
PROFILE = CurrentProfile.from_arrays([-130.0, -70.0, -30.0, 5.0],
                                     [[0.1, 0.0, 0.0], [0.4, -0.2, 0.02], [0.9, 0.3, 0.0], [1.4, 0.1, -0.05]], "test")
SEABED = Plane.from_slope([-600.0, 0.0, -100.0], np.radians(20.0), np.pi / 2)
LAW = IsotropicFriction(0.3, 1.2, 0.05)
#: the element kinds every load is held on: Lagrange P1-P3 and the C1 cubic Hermite
ORDERS = [1, 2, 3, "hermite"]
#: the soft rope bending: EI of the order of its tension times an element's length squared, so that
#: the bending's share of the tangent is not swamped
BENT_ROPE = replace(ROPE, EI=2.0e4)


def one_load_system(name, order):
    """The soft rope of test_loads with drag, added mass, contact and friction, keeping one load
    and the loads whose scratch it reads (friction: the contact's); for the point loads, the rope
    in two segments with a clump weight at their joint and a buoy at its free fairlead end, half out
    of the water; the soil, whose points lie below the seabed, on its own line
    (``test_loads.soil_system``). '+profile': the same load in a sheared current; '+opening': the
    seabed's damper acting on points moving out too (MoorDyn-C's law); '+ramp': the damper engaging
    over a depth deeper than the points' penetrations; the bending, on Hermite
    elements only, of the rope with EI."""
    name, _, variant = name.partition("+")
    if name == "bending" and order != "hermite":
        pytest.skip("bending needs Hermite elements (a line type with EI > 0 is refused on Lagrange ones)")
    if name == "rope":
        if variant == "rod" and order != "hermite":
            pytest.skip("a line type that bends needs Hermite elements")
        system = rope_system("table" if variant in ("", "slack", "rod") else variant, order, slack=variant == "slack",
                             EI=BENT_ROPE.EI if variant == "rod" else 0.0)
        system.loads = [system.load("rope")]
        return system
    profile = variant in ("profile", "waves-profile")
    system = (soil_system(SEABED, order) if name == "soil"
              else system_with_all_loads(SEABED, LAW, order, profile=PROFILE if profile else None,
                                         line_type=BENT_ROPE if name == "bending" else ROPE))
    if name == "points":
        line = system.line
        seg = line.segments[0]
        half = Segment(seg.type, seg.length / 2, seg.elements // 2)
        joints = ((1, Joint("clump", mass=2e3, volume=0.3, CdA=1.5, Ca=1.0)),
                  (2, Joint("buoy", mass=100.0, volume=2.0, CdA=2.0, Ca=0.5)))
        line = replace(line, segments=(half, half), joints=joints, prescribed=(True, False))
        environment = replace(system.environment, waves=(SEA_GRID if variant == "waves-grid" else SEA)
                              if variant.startswith("waves") else None)
        system = LineSystem(line, SEABED, Contact(stiffness=0.0), environment, dynamic=True)
    if name == "morison":
        env, props = system.environment, system.props
        system.loads.append(Morison(props["diameter"], np.full(len(props["diameter"]), 2.0),
                                    np.full(len(props["diameter"]), 0.4), np.full(len(props["diameter"]), 1.0),
                                    np.full(len(props["diameter"]), 0.5), env.water_density,
                                    SEA_GRID if variant == "grid" else SEA, env.current,
                                    profile=env.current_profile))
    # the last of each: the test's own contact (the catalog's has no stiffness here)
    system.loads = [[load for load in system.loads if catalog.spec_of(load).name == wanted][-1]
                    for wanted in catalog.spec(name).reads + (name,)]
    system.loads[0].opening = variant == "opening"
    if variant == "ramp":  # deeper than the test states' penetrations (``SeabedContact.ramp``)
        system.loads[0].ramp[:] = 1.0
    return system


def load_state(system, name, rng):
    """(state, X, V, A) of a test state for load ``name``, away from its kinks."""
    if name.startswith("rope"):
        X, V, A = rope_state(system, rng, 0.99 if name == "rope+rod" else 1.02)
        return system.state(X, V, A), X, V, A
    return soil_state(system, rng) if name == "soil" else line_state(system, rng, LAW)


def reference(system, X, V, A, v_x, a_x):
    """Rows M A + G and the dense free tangent K + a_x M of the numpy face."""
    fem = system.fem
    M = fem.vector_mass(system.props["mass"], free_only=False)
    R, blocks = system.evaluate(system.state(X, V, A, inv_h=1.0 / H), True, v_x, a_x)
    K = system.matrix(blocks) + a_x * fem.vector_mass(system.props["mass"])
    return R + (M @ A.ravel()).reshape(A.shape), K.toarray()


@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize("name", NAMES)
def test_compiled_face_equals_the_numpy_face(name, order, rng):
    system = one_load_system(name, order)
    state, X, V, A = load_state(system, name, rng)
    fused = FusedEvaluator.for_system(system, system.props["mass"])
    rows_ref, K_ref = reference(system, X, V, A, 150.0, 2.2e4)
    rows, band = fused.evaluate(X, V, A, 150.0, 2.2e4, h=H)
    # the same sums in another order: equal to round-off. SYROPE's BA (5e10 N s) multiplies the round-off
    # of its strain rates, the rows' difference falling with it (on Hermite elements: 2.6e-12 of the
    # largest row at that BA, 1.7e-13 at BA / 10, 1.7e-14 at BA / 100)
    tolerance = 1e-11 if name.startswith("rope+syrope") else 1e-12
    np.testing.assert_allclose(rows, rows_ref, rtol=0, atol=tolerance * np.abs(rows_ref).max())
    np.testing.assert_allclose(fused.dense(band), K_ref, rtol=0, atol=1e-12 * np.abs(K_ref).max())


@pytest.mark.parametrize("order", [1, 2, "hermite"])
@pytest.mark.parametrize("name", NAMES)
def test_numpy_face_tangent_matches_finite_differences(name, order, rng):
    system = one_load_system(name, order)
    state, X, V, A = load_state(system, name, rng)
    directions = rng.standard_normal((2, *X.shape))
    fem = system.fem
    if fem.hermite:  # a tangent row moves points by up to ~0.15 h per unit: the same scale as the positions'
        directions[:, fem.n_vertices:] /= float(np.max(np.diff(fem.mesh.p[0])))
    assert_tangent_matches_finite_differences(system, state, X, V, A, directions)


def test_every_load_has_its_parameters_by_name_in_the_element_record():
    layout = catalog.layout()
    for spec in catalog.CATALOG:
        record = layout.node_params if spec.rule == "node" else layout.params
        fields = record[spec.name].names
        assert fields == ("active",) + tuple(entry[0] for entry in spec.params)
        assert spec.reference.name == spec.name  # the numpy face names its catalog entry


#: the loads whose energy is a potential, its gradient their static residual (the soil's, a load with
#: history, is a merit function of its committed anchors: ``Soil.energy``)
POTENTIALS = [spec.name for spec in catalog.CATALOG if hasattr(spec.reference, "energy") and not spec.history]


@pytest.mark.parametrize("name", POTENTIALS)
def test_the_line_s_energy_is_its_loads_and_its_slope_is_their_static_residual(name, rng):
    # LineSystem.energy sums the loads' own energies (statics' line search takes Armijo's test on it
    # with the slope G . d); central differences, h = 1e-5 m, away from the kinks (line_state):
    # truncation and round-off below 1e-8 of the slope
    system = one_load_system(name, 2)
    _, X, _, _ = load_state(system, name, rng)
    d = rng.standard_normal(X.shape)
    h = 1e-5
    slope = (system.energy(X + h * d) - system.energy(X - h * d)) / (2 * h)
    assert slope == pytest.approx(float(np.sum(system.residual(X) * d)), rel=1e-7)


def test_a_load_reading_the_scratch_of_a_load_not_before_it_is_refused():
    contact = catalog.spec("contact")
    reordered = [spec for spec in catalog.CATALOG if spec is not contact] + [contact]
    with pytest.raises(ValueError, match="'friction' reads the scratch of 'contact'"):
        catalog.Layout(reordered)


def test_a_line_without_seabed_contact_gets_no_friction():
    system = one_load_system("friction", 1)
    setting = replace(system.setting, friction=Friction(model="isotropic"), dynamic=True)
    names = [catalog.spec_of(load).name for load in catalog.build_loads(setting)]
    assert "contact" in names and "friction" in names
    without = replace(setting, sections={"soil": None})  # a line in soil has no contact
    assert not {"contact", "friction"} & {catalog.spec_of(load).name for load in catalog.build_loads(without)}


def test_a_load_declaring_other_parameters_than_it_gives_is_refused():
    system = one_load_system("drag", 1)

    class Renamed(type(system.loads[0])):
        def params(self):
            values = super().params()
            values["normal_typo"] = values.pop("normal")
            return values

    load = system.loads[0]
    load.__class__ = Renamed
    with pytest.raises(ValueError, match="params\\(\\) gives .*normal_typo"):
        pack_params([load], system.fem.n_elements)


def test_registering_a_load_after_the_kernels_were_built_is_refused():
    import cablefem.compiled.kernels  # noqa: F401  (builds them)

    with pytest.raises(RuntimeError, match="register loads before anything compiles"):
        catalog.register(catalog.CATALOG[0])


@pytest.mark.parametrize("name", [spec.name for spec in catalog.CATALOG if spec.rule != "node"])
def test_the_point_loops_call_only_the_lines_loads_and_the_others_would_add_nothing(name, rng):
    system = one_load_system(name, "hermite" if name == "bending" else 2)
    state, X, V, A = load_state(system, name, rng)
    fused = FusedEvaluator.for_system(system, system.props["mass"])
    layout, pts = catalog.layout(), fused.points
    names = {name, *catalog.spec(name).reads}
    np.testing.assert_array_equal(pts.full_calls != 0, [spec.name in names for spec in layout.full])
    np.testing.assert_array_equal(pts.reduced_calls != 0, [spec.name in names for spec in layout.reduced])
    rows, band = (x.copy() for x in fused.evaluate(X, V, A, 150.0, 2.2e4, h=H))
    # every kernel called, each compiled: a load the line has not returns at its flag
    fused.points = pts._replace(full_calls=kernels.point_calls(pts.params, layout.full, kernels.FULL_TYPES, every=True),
                                reduced_calls=kernels.point_calls(pts.params, layout.reduced, kernels.REDUCED_TYPES,
                                                                  every=True))
    every_rows, every_band = fused.evaluate(X, V, A, 150.0, 2.2e4, h=H)
    assert np.array_equal(rows, every_rows) and np.array_equal(band, every_band)
    # only a load that keeps history is committed (the soil's at the full points, the rope's at the reduced)
    assert system.kept_history() == {"soil": {"full"}, "rope": {"reduced"}}.get(name, set())


def test_an_opening_damper_pulls_points_lifting_off_and_friction_reads_its_magnitude(rng):
    # MoorDyn-C's law (``damping_when_opening``): on a point in the seabed moving out, the damper's
    # -c v_n d_P pulls it down; the friction then reads N = |f_n| (MoorDyn-C's |B_z|): the same
    # friction force as a point pressed down by as much
    system = one_load_system("friction+opening", 1)
    contact, law = system.loads[0], system.loads[1].law
    state, X, V, A = load_state(system, "friction", rng)
    V[:, 2] += 0.5  # lifting: every point in the seabed opens, the slowest by ~0.4 m/s
    state = system.state(X, V, A)
    n = contact.seabed.project(state.r.reshape(3, -1).T).direction.T.reshape(state.r.shape)
    gap = contact.seabed.gap_only(state.r.reshape(3, -1).T).reshape(state.r.shape[1:])
    vn = np.einsum("ceq,ceq->eq", state.v, n)
    on = contact.evaluate(state, jacobian=False).force
    friction = system.loads[1].evaluate(state, jacobian=False).force  # on the opening contact's force
    contact.opening = False
    off = contact.evaluate(state, jacobian=False).force
    opening = (gap < 0.0) & (vn > 0.0)
    assert opening.sum() >= 3
    pull = np.einsum("ceq,ceq->eq", on - off, n)  # the normal part: the damper alone
    np.testing.assert_allclose(pull[opening], (-contact.damping * vn)[opening], rtol=1e-9)
    np.testing.assert_array_equal(pull[~opening], 0.0)
    pressure = np.einsum("ceq,ceq->eq", on, n)
    pulled = opening & (pressure < 0.0)
    assert pulled.sum() >= 1
    slip = state.v - vn * n
    # the friction opposes the slip with the magnitude of |f_n| times the law's coefficient
    assert np.all(np.einsum("ceq,ceq->eq", friction, slip)[pulled] < 0.0)
    expected = law.evaluate(slip, np.abs(pressure), None)[0]
    np.testing.assert_allclose(friction[:, pulled], expected[:, pulled], rtol=1e-9)
