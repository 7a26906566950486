"""Points on a line (issue 18): clump weights and buoys at vertices (``cablefem.loads.points``) and
ends that are unknowns (``Line.prescribed``), in statics against closed forms and MoorPy, and in
dynamics the compiled steps equal to the Python path."""

import os
from dataclasses import replace

import numpy as np
import pytest

from cablefem.dynamics.bdf2 import BDF2
from cablefem.geometry import Horizontal
from cablefem.model.line import Joint, Line, LineType, Segment
from cablefem.model.scene import Contact, Environment
from cablefem.statics.solve import solve_static
from cablefem.fem.system import LineSystem

ENV = Environment(water_density=1025.0, gravity=9.81)
CHAIN = LineType("chain", diameter=0.1, mass=60.0, EA=5.0e8, damping=0.0, Cd_normal=1.2, Ca_normal=1.0)
W = CHAIN.submerged_weight(ENV.water_density, ENV.gravity)  # N/m
DEEP = Horizontal(2000.0)


def hanging(order, joint, length=300.0, elements=12, top=(0.0, 0.0, -20.0)):
    """A chain hanging from a prescribed top (its fairlead end) with ``joint`` at its free lower end."""
    top = np.asarray(top, dtype=float)
    return Line("hang", top - [0.0, 0.0, length], top, (Segment(CHAIN, length, elements),), order,
                joints=((0, joint),), prescribed=(False, True))


@pytest.mark.parametrize("order", [1, 2, 3])
def test_a_clump_weight_on_a_free_end_hangs_as_the_closed_form_says(order):
    """Hanging straight down: T(s) = F + w s from the clump up (F its weight in water), so the top
    carries F + w L and the clump sits (F L + w L^2 / 2) / EA below the unstretched length."""
    clump = Joint("clump", mass=5.0e3, volume=0.5)
    line = hanging(order, clump)
    system = LineSystem(line, DEEP, Contact(), ENV)
    result = solve_static(system)
    F = clump.mass * ENV.gravity - ENV.water_density * ENV.gravity * clump.volume
    L = line.unstretched_length
    top = -system.residual(result.X)[system.fem.fairlead_dof]
    np.testing.assert_allclose(top, [0.0, 0.0, -(F + W * L)], rtol=1e-10, atol=1e-6)
    bottom = result.X[system.fem.anchor_dof]
    expected = line.fairlead[2] - L - (F * L + W * L * L / 2) / CHAIN.EA
    np.testing.assert_allclose(bottom, [0.0, 0.0, expected], rtol=0, atol=1e-9 * L)


def test_a_buoy_on_a_taut_riser_floats_where_its_buoyancy_and_the_stretch_agree():
    """An anchored chain held up by a buoy at its free upper end, short enough that the buoy stays
    in the surface: with T_top = rho g V phi(z) - m g (phi the sphere's submerged fraction) the
    tension falls by w per metre down to the anchor, and z = z_a + L + (T_top L - w L^2 / 2) / EA:
    one equation for the buoy's height z, solved here by brentq."""
    from scipy.optimize import brentq

    from cablefem.loads.points import sphere_fraction

    buoy = Joint("buoy", mass=200.0, volume=30.0)
    L, za = 34.0, -35.0
    line = Line("riser", (0.0, 0.0, za), (0.0, 0.0, za + L), (Segment(CHAIN, L, 8),), 2,
                joints=((1, buoy),), prescribed=(True, False))
    system = LineSystem(line, DEEP, Contact(), ENV)
    result = solve_static(system)
    radius = np.cbrt(3 * buoy.volume / (4 * np.pi))

    def top_tension(z):
        phi = sphere_fraction(np.array([z]), np.array([radius]))[0][0]
        return ENV.water_density * ENV.gravity * buoy.volume * phi - buoy.mass * ENV.gravity

    z = brentq(lambda z: za + L + (top_tension(z) * L - W * L * L / 2) / CHAIN.EA - z, -radius, radius, xtol=1e-14)
    assert -radius < z < radius  # in the surface: the buoyancy is partial
    np.testing.assert_allclose(result.X[system.fem.fairlead_dof], [0.0, 0.0, z], rtol=0, atol=1e-9)
    anchor = -system.residual(result.X)[system.fem.anchor_dof]
    np.testing.assert_allclose(anchor, [0.0, 0.0, top_tension(z) - W * L], rtol=1e-9)


def test_a_clump_weight_between_two_lines_matches_moorpy():
    """Two chains from two anchors at one depth meeting at a clump weight in mid-water, against MoorPy's
    System (elastic catenaries and a free point with mass): the point's position and both tensions."""
    os.environ.setdefault("PYTHONBREAKPOINT", "0")
    moorpy = pytest.importorskip("moorpy")
    depth, clump = 200.0, Joint("clump", mass=8.0e3, volume=1.0)
    a, b = np.array([-150.0, 0.0, -depth]), np.array([150.0, 0.0, -depth + 40.0])
    half = 130.0
    segments = (Segment(CHAIN, half, 20), Segment(CHAIN, half, 20))
    line = Line("v", a, b, segments, 2, joints=((1, clump),))
    system = LineSystem(line, Horizontal(depth + 500.0), Contact(), ENV)
    result = solve_static(system)
    point = result.X[20]
    fa = -system.residual(result.X)[system.fem.anchor_dof]
    fb = -system.residual(result.X)[system.fem.fairlead_dof]

    ms = moorpy.System(depth=depth + 500.0, rho=ENV.water_density, g=ENV.gravity)
    ms.setLineType(dnommm=100.0, name="c", d_vol=CHAIN.diameter, mass=CHAIN.mass, EA=CHAIN.EA, w=W)
    ms.addPoint(1, a)
    ms.addPoint(0, 0.5 * (a + b) - [0.0, 0.0, 60.0], m=clump.mass, v=clump.volume)
    ms.addPoint(1, b)
    ms.addLine(half, "c", pointA=1, pointB=2)
    ms.addLine(half, "c", pointA=2, pointB=3)
    ms.initialize()
    ms.solveEquilibrium(tol=1e-9)
    np.testing.assert_allclose(point, ms.pointList[1].r, rtol=0, atol=2e-4)
    np.testing.assert_allclose(np.linalg.norm(fa), ms.lineList[0].TA, rtol=2e-5)
    np.testing.assert_allclose(np.linalg.norm(fb), ms.lineList[1].TB, rtol=2e-5)


@pytest.mark.parametrize("order", [1, 2])
def test_compiled_steps_with_points_and_a_free_end_equal_the_python_path(order):
    """A hanging chain with a clump at a mid joint and a buoy-less free end, its top surging: the
    compiled BDF2 steps (free end in the band, node loads in the loop) give the Python path's numbers."""
    clump = Joint("clump", mass=3.0e3, volume=0.4, CdA=2.0, Ca=0.8)
    tip = Joint("tip", mass=500.0, CdA=0.5, Ca=1.0)
    line = replace(hanging(order, tip, length=200.0, elements=10),
                   segments=(Segment(CHAIN, 100.0, 5), Segment(CHAIN, 100.0, 5)),
                   joints=((0, tip), (1, clump)))
    static = LineSystem(line, DEEP, Contact(), ENV)
    X0 = solve_static(static).X
    system = LineSystem(line, DEEP, Contact(), ENV, dynamic=True, fem=static.fem)

    def top(t):
        w = 2 * np.pi / 8.0
        return (line.fairlead + [2.0 * np.sin(w * t), 0.0, 0.0], np.array([2.0 * w * np.cos(w * t), 0.0, 0.0]),
                np.array([-2.0 * w * w * np.sin(w * t), 0.0, 0.0]))

    times = np.arange(1, 401) * 0.02  # a period, for the motion to travel down to the free end
    runs = []
    for compiled in (True, False):
        integ = BDF2(system, X0, top, dt=0.02)
        assert (integ.stepper().packer is not None) == True  # noqa: E712  (the compiled steps exist for it)
        if not compiled:
            integ.stepper().packer = None
        runs.append((integ.march(times), integ.X.copy()))
    (f1, X1), (f2, X2) = runs
    np.testing.assert_allclose(f1, f2, rtol=0, atol=1e-9 * np.abs(f2).max())
    np.testing.assert_allclose(X1, X2, rtol=0, atol=1e-9)
    assert np.linalg.norm(X1[system.fem.anchor_dof] - X0[system.fem.anchor_dof]) > 1e-2  # the free end moves


def test_with_types_changes_the_types_and_keeps_joints_ends_and_mesh():
    """``Line.with_types`` (the switches of the studies: EA, beta, the slack law) replaces each
    segment's type and nothing else: a line built again from name, ends, segments and order would
    lose its joints and its free end."""
    line = hanging(2, Joint("clump", mass=5.0e3, volume=0.5))
    stiffer = line.with_types(lambda t: replace(t, EA=2.0 * t.EA))
    assert [seg.type.EA for seg in stiffer.segments] == [2.0 * CHAIN.EA]
    assert [(seg.length, seg.elements) for seg in stiffer.segments] == [(seg.length, seg.elements)
                                                                      for seg in line.segments]
    assert (stiffer.joints, stiffer.prescribed, stiffer.order) == (line.joints, (False, True), 2)
    np.testing.assert_array_equal(stiffer.anchor, line.anchor)
    np.testing.assert_array_equal(stiffer.fairlead, line.fairlead)
