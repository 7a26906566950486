"""``quadrature_points`` of a line (``[[lines]]`` and ``[moordyn]``): the Gauss points per element
of the full-point loads. The seabed's contact force has a kink where the line touches down; two
points integrate it with an error that jumps as the touchdown crosses elements, more points
integrate it better (verification/work_precision/README.md: the scatter of the slow surge's
error with the element count)."""

from dataclasses import replace

import numpy as np
import pytest

from cablefem.dynamics.generalized_alpha import GeneralizedAlpha
from cablefem.errors import InputError
from cablefem.model.network import boundary_path
from cablefem.fem.system import build_system
from cablefem.statics.scene import start_states
from cablefem.model.builtin import flume_scene


def contact_error(points, kink=3.37):
    """The relative error of the total vertical contact force on a straight P1 x 10 flume chain
    that dips below the seabed over its first ``kink`` elements, 2 m deep at the anchor (the compiled
    kernel's rows at rest, the weight's rows taken out), against the exact integral of the spring's
    pressure along it (desire2023 Eq. 11: a triangle)."""
    scene = flume_scene("flat", "dynamic", elements=10, order=1)
    line = scene.lines[0].with_quadrature_points(points)
    scene = replace(scene, lines=[line])
    system = build_system(scene, line)
    (X0,), _ = start_states(scene, systems=[system])
    integ = GeneralizedAlpha(system, X0, boundary_path(scene, line), dt=0.01)
    s = line.node_arc_lengths()
    zb, deep, s_b = -scene.seabed.depth, 2.0, kink * s[-1] / 10
    zero = np.zeros((len(s), 3))

    def rows_z(z_start):
        X = np.zeros((len(s), 3))
        X[:, 0] = s
        X[:, 2] = z_start + deep * s / s_b
        rows, _ = integ.rows_and_tangent(X, zero, zero, 0.0, 0.0, 0.0, False)
        return rows[:, 2].sum()

    contact = -(rows_z(zb - deep) - rows_z(zb + 10.0))  # the rows are M A - f
    k = next(load for load in system.loads if load.name == "contact").stiffness[0, 0]
    return contact / (k * 0.5 * deep * s_b) - 1.0


def test_more_points_integrate_the_touchdown_kink_of_the_contact_better():
    """Over twelve places of the touchdown within an element, two points (P1's default) miss the
    triangle's integral by 0.2 % RMS (0.4 % at most); four points by a quarter of that, eight by a
    sixth of four's (measured 2.2e-3, 4.8e-4, 8.0e-5)."""
    kinks = 3 + (np.arange(12) + 0.5) / 12
    rms = {q: np.sqrt(np.mean([contact_error(q, kink) ** 2 for kink in kinks])) for q in (2, 4, 8)}
    assert rms[2] > 1e-3
    assert rms[4] <= 0.3 * rms[2]
    assert rms[8] <= 0.3 * rms[4]
    assert contact_error(0) == contact_error(2)


def test_a_line_refuses_fewer_points_than_its_mass_needs_and_too_many():
    line = flume_scene("flat", "dynamic", elements=10, order=2).lines[0]
    for bad in (1, 2, 17, 2.5, True):
        with pytest.raises(InputError) as error:
            line.with_quadrature_points(bad)
        assert error.value.key == "quadrature_points"
    assert line.with_quadrature_points(3).quadrature_points == 3


def test_the_scene_key_reaches_the_line_and_a_bad_value_names_file_and_key(tmp_path):
    from cablefem.io.scenes import load_scene

    text = """[line_types.chain]
diameter = 0.1
mass = 100.0
EA = 1e8
[[lines]]
anchor = [0, 0, -50]
fairlead = [200, 0, 0]
segments = [{ type = "chain", length = 230.0, elements = 20 }]
order = 2
quadrature_points = QP
[seabed]
kind = "horizontal"
depth = 50
"""
    path = tmp_path / "scene.toml"
    path.write_text(text.replace("QP", "5"))
    assert load_scene(str(path)).lines[0].quadrature_points == 5
    path.write_text(text.replace("QP", "2"))
    with pytest.raises(InputError) as error:
        load_scene(str(path))
    assert "lines[0].quadrature_points" in str(error.value) and "scene.toml" in str(error.value)
    assert "order + 1 = 3" in str(error.value)
