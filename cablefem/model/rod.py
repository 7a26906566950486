"""Rigid rods (MoorDyn's RODS and ROD TYPES, issue 36): data, and how a rod enters a network.

A ``Rod`` is a rigid cylinder from end A to end B: ``diameter`` [m], ``mass_per_length`` [kg/m] in
air, the transverse drag and added-mass coefficients ``Cd``, ``Ca`` along it and ``CdEnd``,
``CaEnd`` at its ends (MoorDyn-C's ``RodProps``; ``Rod::setup`` and ``Rod::doRHS`` in Rod.cpp).
Its own loads are in ``cablefem.loads.rod``.

A rod is a rigid body, and it enters the network as one (``cablefem.model.network``):

- a *fixed* rod is two fixed points at its ends; a *coupled* rod a coupled body whose points are its
  ends; a rod *on a body* (MoorDyn's BodyN) two points of that body, its weight and buoyancy
  carried by the body (``Body.rods``);
- a *free* rod is a free ``Body`` whose frame has the rod's axis as its z axis, end A at its
  reference point and end B at (0, 0, L), with the rod's mass and inertia (``rod_body``): the same
  coupling unknown as any free body, with the rod's own loads in place of a body's (``Body.rod``);
  a *pinned* rod is that body with end A held where the file puts it (``Rod.pinned``). In a run a
  free or pinned rod's own loads, and those of the rods a free body carries, are
  ``cablefem.loads.rod_body``'s;
- a rod of zero length (MoorDyn's NumSegs 0) has no mass and no volume (Rod.cpp): a point.

Rotations are ``cablefem.model.network``'s: R = Rx(roll) Ry(pitch) Rz(yaw).
"""

import math
from dataclasses import dataclass

import numpy as np

from cablefem.errors import InputError


@dataclass(frozen=True)
class RodType:
    """MoorDyn's ROD TYPES row: ``diameter`` [m], ``mass_per_length`` [kg/m] in air, transverse
    drag ``Cd`` and added mass ``Ca`` along the rod, ``CdEnd`` and ``CaEnd`` at its ends."""

    name: str
    diameter: float
    mass_per_length: float
    Cd: float = 0.0
    Ca: float = 0.0
    CdEnd: float = 0.0
    CaEnd: float = 0.0


@dataclass(frozen=True)
class Rod:
    """A rod of ``type`` from ``end_a`` to ``end_b`` (3,) [m]: in the scene's frame, or on a body in
    the body's frame. ``pinned``: end A is held (to the ground or to its body), the rod turns about
    it. ``name`` is the scene's (``rod1``)."""

    name: str
    type: RodType
    end_a: np.ndarray
    end_b: np.ndarray
    pinned: bool = False

    def __post_init__(self):
        for key in ("end_a", "end_b"):
            value = np.asarray(getattr(self, key), dtype=float)
            if value.shape != (3,) or not np.all(np.isfinite(value)):
                raise InputError(f"expected 3 finite numbers, got {getattr(self, key)!r}", key=f"rods.{self.name}.{key}")
            object.__setattr__(self, key, value)

    @property
    def length(self):
        """|B - A| [m]."""
        return float(np.linalg.norm(self.end_b - self.end_a))

    @property
    def area(self):
        """The cross-section pi d^2 / 4 [m^2]."""
        return 0.25 * math.pi * self.type.diameter ** 2

    @property
    def mass(self):
        """The rod's mass in air [kg]."""
        return self.type.mass_per_length * self.length

    def inertia(self):
        """Principal moments of inertia (3,) [kg m^2] about the rod's centre of gravity in a frame
        with the axis as z: a uniform solid cylinder, m (3 r^2 + L^2) / 12 across, m r^2 / 2 along
        (MoorDyn-C lumps the across terms on its nodes, Rod::doRHS)."""
        m, r, L = self.mass, 0.5 * self.type.diameter, self.length
        across = m * (3.0 * r * r + L * L) / 12.0
        return np.array([across, across, 0.5 * m * r * r])


def axis_angles(direction):
    """(roll, pitch, 0) [rad] of the rotation R = Rx Ry Rz that turns the z axis onto the unit
    ``direction`` (3,): R e_z = (sin p, -sin r cos p, cos r cos p)."""
    u = np.asarray(direction, dtype=float) / np.linalg.norm(direction)
    roll = math.atan2(-u[1], u[2]) if math.hypot(u[1], u[2]) > 1e-12 else 0.0  # along x: any roll, take 0
    return np.array([roll, math.asin(max(-1.0, min(1.0, u[0]))), 0.0])


def rod_body(rod, Body):
    """The free ``Body`` that a free or pinned ``rod`` is (``Body``: ``cablefem.model.network.Body``,
    passed in to keep the import one way): reference point at end A, the axis its z axis, the rod's
    mass and inertia about its centre of gravity at (0, 0, L/2)."""
    L = rod.length
    return Body(rod.name, "free", rod.end_a, axis_angles(rod.end_b - rod.end_a), mass=rod.mass,
                inertia=rod.inertia(), cg=[0.0, 0.0, 0.5 * L], rod=rod)


def rod_end_local(rod, end):
    """Where end 'A' or 'B' of a free or pinned ``rod`` sits in its body's frame [m]."""
    return np.zeros(3) if end == "A" else np.array([0.0, 0.0, rod.length])
