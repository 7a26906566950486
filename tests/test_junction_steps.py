"""Dynamics of strings that meet at a junction (issue 18, ``cablefem.dynamics.group``): at rest from
the network's statics nothing moves, every accepted step solves the coupled equations (each
string's interior and the junction's balance), and the compiled evaluation gives the numpy path's
numbers."""

import numpy as np
import pytest

from cablefem.dynamics.registry import INTEGRATORS
from cablefem.io import load_scene
from cablefem.model.network import dynamic_lines
from cablefem.model.network import anchor_path, boundary_path
from cablefem.fem.system import build_system
from cablefem.dynamics.group import junction_groups
from cablefem.statics.scene import start_states
from cablefem.dynamics.registry import integrator_options

CROWFOOT = """\
name = "crowfoot"
[line_types.chain]
diameter = 0.1
mass = 60.0
EA = 5e8
damping = 0.01
Cd_normal = 1.2
Ca_normal = 1.0
Cd_tangential = 0.4
[points.f]
kind = "coupled"
position = [-10.0, 0.0, -10.0]
[points.j]
kind = "free"
position = [-160.0, 0.0, -80.0]
mass = 2000.0
volume = 1.0
CdA = 2.0
Ca = 1.0
[points.a1]
kind = "fixed"
position = [-400.0, 150.0, -180.0]
[points.a2]
kind = "fixed"
position = [-400.0, -150.0, -180.0]
[[lines]]
name = "upper"
anchor = "j"
fairlead = "f"
segments = [{ type = "chain", length = 185.0, elements = 8 }]
[[lines]]
name = "leg1"
anchor = "a1"
fairlead = "j"
segments = [{ type = "chain", length = 320.0, elements = 10 }]
[[lines]]
name = "leg2"
anchor = "a2"
fairlead = "j"
segments = [{ type = "chain", length = 320.0, elements = 12 }]
[seabed]
kind = "horizontal"
depth = 1000.0
[solver]
dt = 0.05
"""
SURGE = """
[motion]
kind = "harmonic"
amplitude = [4.0, 1.0, 1.0]
period = 8.0
ramp = 4.0
"""


def start(tmp_path, text, compiled=True):
    path = tmp_path / "crowfoot.toml"
    path.write_text(text)
    scene = load_scene(path)
    systems = [build_system(scene, line) for line in dynamic_lines(scene)]
    states, _ = start_states(scene, systems=systems)
    options = {**integrator_options(scene.solver), "compiled": compiled}
    integrators = [INTEGRATORS["bdf2"](s, X, boundary_path(scene, line), dt=scene.solver.dt,
                                       anchor=anchor_path(scene, line), **options)
                   for s, line, X in zip(systems, scene.lines, states)]
    return scene, integrators, junction_groups(scene, integrators)[0], states


def march(integrators, duration, dt=0.05):
    times = np.arange(1, int(round(duration / dt)) + 1) * dt
    return np.array([integ.march(times) for integ in integrators])


def test_at_rest_from_the_network_statics_nothing_moves(tmp_path):
    """The junction's weight, buoyancy and the strings' ends balance in statics as in dynamics."""
    _, integrators, _, states = start(tmp_path, CROWFOOT)
    march(integrators, 2.0)
    for integ, X0 in zip(integrators, states):
        assert np.abs(integ.X - X0).max() < 1e-6


def test_every_step_solves_the_coupled_equations(tmp_path):
    """Under a surging fairlead: at the end of the run each string's interior rows and the
    junction's balance (the sum of the strings' end rows) are below the tolerance's force; the
    junction has moved and the strings' ends there agree."""
    scene, integrators, group, states = start(tmp_path, CROWFOOT + SURGE)
    march(integrators, 6.0)
    balance, interior = np.zeros(3), 0.0
    for k, integ in enumerate(integrators):
        rows, _ = integ.rows_and_tangent(*integ.point(integ.X), integ.t, *integ.factors[:2], False)
        free = integ.fem.free_dofs
        ends = [dof for _, _, _, dof in group.ends[k]]
        interior = max(interior, float(np.abs(rows[np.setdiff1d(free, ends)]).max()))
        balance += sum(rows[dof] for dof in ends)
    scale = group.scale
    assert interior <= 1e-6 * scale and np.abs(balance).max() <= 1e-6 * scale
    at = [integ.X[(integ.fem.anchor_dof, integ.fem.fairlead_dof)[end]] for k, integ in enumerate(integrators)
          for end, _, name, _ in group.ends[k]]
    assert np.abs(np.array(at) - at[0]).max() < 1e-12
    assert np.linalg.norm(at[0] - states[0][0]) > 0.1  # the junction moved
    assert all(integ.rejected == 0 for integ in integrators)


def test_compiled_and_numpy_evaluations_give_the_same_junction_steps(tmp_path):
    forces = [march(start(tmp_path, CROWFOOT + SURGE, compiled)[1], 4.0) for compiled in (True, False)]
    np.testing.assert_allclose(forces[0], forces[1], rtol=0, atol=1e-7 * np.abs(forces[1]).max())


def test_the_strings_forces_at_the_junction_are_their_own(tmp_path):
    """The force each string exerts on the junction is its own: at t = 0 the network statics' (the
    run starts at rest, nothing accelerates; before, each member's own initial acceleration put a
    leg's force 13 % off at t = 0 in validation/junction's crowfoot, and the string carrying the
    junction's clump reported the clump's load with its force: 2.2 % low at rest in tensions.csv),
    and under a surge the strings' forces balance the clump's weight, buoyancy, drag and inertia
    (written out here)."""
    from cablefem.statics.network import solve_network
    from cablefem.runs.results import end_forces

    scene, integrators, group, _ = start(tmp_path, CROWFOOT + SURGE)
    statics = solve_network(scene, lambda line: build_system(scene, line, dynamic=False))
    scale = group.scale
    for k, integ in enumerate(group.members):
        static = end_forces(statics.systems[k], statics.states[k])
        np.testing.assert_allclose(group.reactions()[k], static, rtol=0, atol=1e-6 * scale)
        assert np.abs(integ.A).max() == 0.0
    march(integrators, 4.0)
    total, junction = np.zeros(3), None
    for k, integ in enumerate(group.members):
        for end, _, _, dof in group.ends[k]:
            total += group.reactions()[k][1 - end]
            junction = (integ.X[dof], integ.V[dof], integ.A[dof])
    mass, volume, cda, ca, rho, g = 2000.0, 1.0, 2.0, 1.0, 1025.0, 9.81
    _, v, a = junction
    clump = np.array([0.0, 0.0, (rho * volume - mass) * g]) - 0.5 * rho * cda * np.linalg.norm(v) * v \
        - (mass + ca * rho * volume) * a
    assert np.linalg.norm(a) > 0.1 and np.linalg.norm(v) > 0.1  # a junction in motion
    np.testing.assert_allclose(total + clump, 0.0, atol=1e-6 * scale)


def test_the_compiled_loop_gives_the_python_steps(tmp_path):
    """The group's compiled steps (``cablefem.compiled.steps``, in one numba call) against the policy on
    the Python ops (``cablefem.dynamics.python_ops``) on the same compiled evaluations: the same
    iterations and evaluations, forces (the junction ends' without the clump riding on one of them)
    equal to round-off (the same arithmetic in another order; 1e-10 of the largest force leaves room
    for other machines), and against the numpy loads' path (1e-7: their quadrature sums in another
    order)."""
    runs, counters = [], []
    for compiled, loop in ((True, True), (True, False), (False, False)):
        _, integrators, group, _ = start(tmp_path, CROWFOOT + SURGE, compiled)
        assert (group.packer is not None) == compiled
        if not loop:
            group.packer = None
        runs.append(march(integrators, 4.0))
        counters.append([integ.counters.tolist() for integ in integrators])
    scale = np.abs(runs[1]).max()
    np.testing.assert_allclose(runs[0], runs[1], rtol=0, atol=1e-10 * scale)
    assert counters[0] == counters[1]
    np.testing.assert_allclose(runs[1], runs[2], rtol=0, atol=1e-7 * scale)


@pytest.mark.parametrize("integrator", ["generalized-alpha", "bdf2 adaptive"])
def test_junction_groups_step_with_every_scheme_and_adaptive_steps(tmp_path, integrator):
    """A junction group is a problem the policy steps like a line (issue 31): generalised-alpha, and
    BDF2's adaptive steps, run the crowfoot; each solves the coupled equations at its last step
    (interior rows and the junction's balance below the tolerance's force), and its forces follow
    BDF2's fixed-step run (the same motion: within 1 % of the largest force)."""
    from cablefem.runs.run import run_scene

    path = tmp_path / "crowfoot.toml"
    name, _, adaptive = integrator.partition(" ")
    path.write_text(CROWFOOT.replace("dt = 0.05", f"dt = 0.05\nintegrator = \"{name}\"\n"
                                     + ("adaptive = true\n" if adaptive else "")) + SURGE
                    + "\n[output]\nevery = 0.1\n")  # frames as measured: adaptive steps land on each
    reference = tmp_path / "reference.toml"
    reference.write_text(CROWFOOT + SURGE)
    series = []
    for each, out in ((reference, "ref"), (path, "run")):
        summary = run_scene(load_scene(each), str(tmp_path / out), duration=6.0, progress=False)
        assert summary["completed"]
        rows = np.loadtxt(tmp_path / out / "tensions.csv", delimiter=",", skiprows=1)
        series.append(rows)
    ref, run = series
    # generalised-alpha's forces are its balance at t_{n+1-alpha_f} carried on to t_{n+1}
    # (``policy.balance_lag``): they follow BDF2 at the same times, 0.34 % of the largest force apart
    # (the balance as it is lags alpha_f dt: 1.02 %, the force rising 137 kN/s); BDF2 adaptive 0.50 %
    # compare at the reference's times (adaptive steps fall elsewhere: interpolate)
    worst = max(np.max(np.abs(np.interp(ref[:, 0], run[:, 0], run[:, column]) - ref[:, column]))
                for column in range(1, ref.shape[1]))
    assert worst <= 0.01 * np.abs(ref[:, 1:]).max(), worst / np.abs(ref[:, 1:]).max()


def test_the_tripod_on_its_hinges_holds_still_with_either_integrator():
    """MoorDyn's tripod.txt as it stands (EI > 0: eleven Hermite strings, eight hinges and the junction
    of the legs, tests/test_moordyn_files.py): from its statics, in still water and with nothing moving
    its ends, both integrators' compiled junction steps keep every node where the statics put it
    (1e-6 m over 0.1 s: the statics' balance to 1e-8 of the weight, nothing else acts)."""
    from pathlib import Path

    scene = load_scene(Path(__file__).parent / "data" / "moordyn" / "tripod.txt")
    assert len(scene.lines) == 11 and all(line.hermite for line in scene.lines)
    states = None
    for scheme in ("bdf2", "generalized-alpha"):
        systems = [build_system(scene, line) for line in dynamic_lines(scene)]
        if states is None:
            states, _ = start_states(scene, systems=systems)
        options = {**integrator_options(scene.solver), "compiled": True}
        integrators = [INTEGRATORS[scheme](s, X, boundary_path(scene, line), dt=0.01,
                                           anchor=anchor_path(scene, line), **options)
                       for s, line, X in zip(systems, scene.lines, states)]
        steps, = junction_groups(scene, integrators)
        steps.march(0.01 * np.arange(1, 11))
        for integ, X0 in zip(integrators, states):
            assert np.abs(integ.X - X0).max() < 1e-6


def test_one_compilation_steps_networks_of_any_number_of_strings(tmp_path):
    """The group's compiled steps take its strings in numba's typed List, whose type leaves out their
    number: the crowfoot's three strings and the same crowfoot with a fourth leg step on one compiled
    function (a tuple of strings compiled the steps again for each number, minutes each)."""
    fourth = CROWFOOT.replace('[[lines]]\nname = "upper"', '[points.a3]\nkind = "fixed"\n'
                              'position = [-450.0, 0.0, -180.0]\n[[lines]]\nname = "upper"') + (
        '[[lines]]\nname = "leg3"\nanchor = "a3"\nfairlead = "j"\n'
        'segments = [{ type = "chain", length = 300.0, elements = 9 }]\n')
    functions = set()
    for text in (CROWFOOT + SURGE, fourth + SURGE):
        _, integrators, group, _ = start(tmp_path, text)
        group.march(0.05 * np.arange(1, 5))
        assert len(group.members) == text.count("[[lines]]") and group.members[0].t == pytest.approx(0.2)
        functions.add(group.packer.functions["steps"])
    steps, = functions
    assert len(steps.signatures) == 1
