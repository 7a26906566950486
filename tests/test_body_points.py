"""Lines that share a point of a free body (``cablefem.model.network.coupling``): the body's pose
places that point, so each line end there is linked to the body alone, never to a junction too.

MoorDyn's body_tests/rotatingBody.txt (six lines from one body point) and
local_euler/complex_system.txt (three lines at one body point) stopped in Newton at their first
step: the point was also a junction, its line ends linked twice (the strings' end stiffness
singular, a NaN step) and the junction's balance (the lines' pull, which the body holds) a
residual no step could close."""

import numpy as np
import pytest

from cablefem.errors import ConvergenceError
from cablefem.io import load_scene
from cablefem.model.network import coupling
from test_body_dynamics import start

#: EA [N] and unstretched length [m] of the spokes (1 m from the body's point to their anchors), the body's mass [kg]
EA, L0, MASS = 25152.0, 0.9, 10.0


def spokes(tmp_path, shared, gravity=0.0, anchors=None, body="", point_z=0.0):
    """A free body held by lines to fixed ``anchors`` (six at 1 m along +-x, +-y, +-z by default),
    every line on one point of the body (``shared``) or each on a point of its own at the same place;
    lines of negligible mass, no drag, added mass or damping."""
    anchors = anchors if anchors is not None else [
        [1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]
    text = [(f'name = "spokes"\n[environment]\nwater_density = 1025.0\ngravity = {gravity}\n'
            '[seabed]\nkind = "horizontal"\ndepth = 100.0\n'
            f'[line_types.spoke]\ndiameter = 0.01\nmass = 1e-3\nEA = {EA}\ndamping = 0.0\n'
            'Cd_normal = 0.0\nCd_tangential = 0.0\nCa_normal = 0.0\nCa_tangential = 0.0\n'
            f'[bodies.b]\nkind = "free"\nposition = [0.0, 0.0, -20.0]\nmass = {MASS}\n'
            f'inertia = [5.0, 5.0, 5.0]\n{body}\n')]
    for k, anchor in enumerate(anchors):
        name = "p" if shared else f"p{k}"
        if k == 0 or not shared:
            text.append(f'[points.{name}]\nbody = "b"\nposition = [0.0, 0.0, {point_z}]\n')
        text.append(f'[points.a{k}]\nkind = "fixed"\nposition = [{anchor[0]}, {anchor[1]}, {anchor[2] - 20.0 + point_z}]\n'
                    f'[[lines]]\nname = "spoke{k}"\nanchor = "a{k}"\nfairlead = "{name}"\n'
                    f'segments = [{{ type = "spoke", length = {L0}, elements = 1 }}]\n')
    path = tmp_path / f"spokes_{'shared' if shared else 'apart'}.toml"
    path.write_text("".join(text))
    return load_scene(path)


def path_of(group, steps, dt):
    """The body's reference point (steps + 1, 3) [m] over ``steps`` steps of dt [s]."""
    body = group.bodies[0]
    out = [body.absolute(body.X)[:3]]
    for _ in range(steps):
        group.step(dt)
        out.append(body.absolute(body.X)[:3])
    return np.array(out)


def test_a_point_on_a_free_body_is_no_junction_however_many_lines_meet_there(tmp_path):
    """The coupling unknowns of six lines on one body point are the body's pose alone."""
    scene = spokes(tmp_path, shared=True)
    assert coupling(scene.lines, scene.points, scene.bodies) == ([], ["b"])


def test_six_lines_on_one_body_point_oscillate_at_the_closed_form_period_as_on_points_of_their_own(tmp_path):
    """MoorDyn's rotatingBody.txt without its drive: a 10 kg body in g = 0 on six pre-stretched lines
    (0.9 m to 1 m) from one of its points, pushed along x, oscillates at 2 pi sqrt(M / k) with
    k = 2 EA / L0 + 4 T / L (the two lines along x stretch, the four across turn at their tension T):
    the period measured from the zero crossings of x over three periods within 0.2 % of it (the
    trapezoidal rule's period error (w h)^2 / 12 is 6e-4 at h = 1 ms, the lines' mass 2e-4 of the
    body's; a line linked to nothing, or twice, moves k by a sixth), and the same run with each line on
    a point of its own at the same place gives the same path to round-off."""
    dt, steps = 1e-3, 240
    paths = []
    for shared in (True, False):
        _, group, _ = start(spokes(tmp_path, shared), "generalized-alpha", dt, rho_inf=1.0)
        group.set_velocity(group.bodies[0], [[0.01, 0.0, 0.0], [0.0, 0.0, 0.0]])
        paths.append(path_of(group, steps, dt))
    tension = EA * (1.0 - L0) / L0
    period = 2 * np.pi * np.sqrt(MASS / (2 * EA / L0 + 4 * tension))
    x = paths[0][:, 0] - paths[0][0, 0]
    k = np.nonzero((x[:-1] > 0) != (x[1:] > 0))[0][1:]  # sign changes after the start's
    crossings = (k - x[k] / (x[k + 1] - x[k])) * dt
    measured = 2 * np.mean(np.diff(crossings))
    assert len(crossings) >= 6
    assert abs(measured / period - 1) < 2e-3
    assert np.max(np.abs(paths[0][:, 1:] - paths[0][0, 1:])) < 1e-9  # nothing pushes it across
    np.testing.assert_allclose(paths[0], paths[1], rtol=0, atol=1e-12)


def test_a_body_hanging_from_lines_at_one_point_starts_at_rest_at_its_statics(tmp_path):
    """MoorDyn's complex_system.txt's cause: a heavy free body (weight less buoyancy 9.81 * (10 -
    1025 * 0.004) N) hung from three lines at one of its points, above its centre of gravity. The run
    starts at the statics' equilibrium, so its steps converge and nothing moves: after 20 BDF2 steps
    the body is within 1e-9 m of its statics' pose, and the lines' vertical pull on the point equals
    the body's net weight to 1e-9 of it (the junction the point wrongly was had that pull as a residual
    no step could close: 4.6e-3 relative in complex_system)."""
    anchors = [[1.0, 0.0, 0.3], [-0.5, 0.866, 0.3], [-0.5, -0.866, 0.3]]
    scene = spokes(tmp_path, True, gravity=9.81, anchors=anchors, body="volume = 0.004\ncg = [0.0, 0.0, -0.2]",
                   point_z=0.2)
    _, group, network = start(scene, "bdf2", 0.01)
    pose = network.poses["b"]
    path = path_of(group, 20, 0.01)
    assert np.max(np.abs(path - pose[:3])) < 1e-9
    net_weight = 9.81 * (MASS - 1025.0 * 0.004)
    pull = sum(m.reactions()[0][2] for m in group.members)  # each line's force on its fairlead (the body's point)
    assert abs(pull - net_weight) < 1e-9 * net_weight


def test_a_step_that_is_not_finite_is_reported_as_such_not_as_a_residual(tmp_path, monkeypatch):
    """Where every Newton of a step stops at a step that is not finite (a singular coupling system),
    the run's error says so, not "did not converge" with the residual it had before."""
    _, group, _ = start(spokes(tmp_path, shared=True), "generalized-alpha", 1e-3)
    monkeypatch.setattr(group, "condense", lambda steps: None)
    with pytest.raises(ConvergenceError, match="Newton's step is not finite .* is singular"):
        group.step(1e-3)
