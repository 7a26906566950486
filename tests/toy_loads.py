"""Two loads that are not cablefem's, added as docs/architecture.md tells a newcomer to: each in one
module (here, one file for both) with its numpy face, its compiled face and its LoadSpec, and one
``catalog.register`` line. ``tests/test_catalog_extension.py`` runs ``measure()`` in a fresh
process (the compiled kernels are built for one catalog) and asserts what it prints.

- ``UniformForce``: a force per unit length, the same everywhere, from a scene table
  ``[uniform_force] force = [x, y, z]`` (the recipe's toy); conservative, with its potential energy
  -f . r per unit length, which statics' line search sums with the other loads'.
- ``PlasticSpring``: each point tied to a rest position by an elastic-perfectly-plastic spring
  (stiffness k [N/m^2], yield force F_y [N/m], radial return), the rest position its history: the
  test of per-point history (a hysteresis loop with a closed form).
"""

import json
import sys

import numpy as np
from numba import njit

from cablefem.io import validate as v
from cablefem.loads import LoadSpec, Terms, identity_like, outer


class UniformForce:
    """A force per unit length f [N/m] (3,), the same at every point of ``nel`` elements."""

    name = "uniform"

    def __init__(self, force, nel):
        self.force = np.asarray(force, dtype=float)
        self.nel = nel

    def evaluate(self, state, jacobian=True):
        return Terms(force=np.broadcast_to(self.force.reshape(3, 1, 1), state.r.shape).copy())

    def energy(self, state):
        """Potential energy density -f . r [J/m] (nel, nq)."""
        return -np.einsum("c,ceq->eq", self.force, state.r)

    def params(self):
        return {"force": np.tile(self.force, (self.nel, 1))}


@njit(cache=True, _nrt=False)
def uniform_point(ctx, p, old, new, state, hold, out):
    q = p.uniform
    if q.active:
        for i in range(3):
            out.f[i] += q.force[i]


def build_uniform(setting):
    if setting.keys is None:
        return None
    return UniformForce(setting.keys["force"], len(setting.props["mass"]))


UNIFORM = LoadSpec("uniform", "full", (("force", "f8", (3,)),), uniform_point, UniformForce,
                   build=build_uniform, section="uniform_force", keys={"force": v.vector3})


class PlasticSpring:
    """f = -k (r - q) while |k (r - q)| <= F_y, the rest position q moving (radial return) beyond:
    stiffness k [N/m^2] and yield force F_y [N/m] per unit length, for ``nel`` elements."""

    name = "plastic"

    def __init__(self, stiffness, yield_force, nel):
        self.k, self.yield_force, self.nel = float(stiffness), float(yield_force), nel

    def initial_history(self, state):
        return {"rest": np.moveaxis(state.r, 0, -1)}  # unloaded where the points start

    def evaluate(self, state, jacobian=True):
        rest = np.moveaxis(state.old["plastic"]["rest"], -1, 0)
        trial = self.k * (state.r - rest)
        size = np.sqrt(np.einsum("ceq,ceq->eq", trial, trial))
        yielded = size > self.yield_force
        unit = trial / np.where(yielded, size, 1.0)
        force = np.where(yielded, -self.yield_force * unit, -trial)
        moved = np.where(yielded, state.r - self.yield_force / self.k * unit, rest)
        state.new["plastic"]["rest"] = np.moveaxis(moved, 0, -1)
        terms = Terms(force=force)
        if jacobian:  # the consistent tangent of the radial return
            eye = identity_like(trial)
            plastic = -(self.yield_force / np.where(yielded, size, 1.0)) * self.k * (eye - outer(unit, unit))
            terms.force_r = np.where(yielded, plastic, -self.k * eye)
        return terms

    def params(self):
        return {"k": np.full(self.nel, self.k), "yield_force": np.full(self.nel, self.yield_force)}


@njit(cache=True, _nrt=False)
def plastic_point(ctx, p, old, new, state, hold, out):
    q = p.plastic
    if not q.active:
        return
    trial = ctx.plastic.trial
    for i in range(3):
        trial[i] = q.k * (ctx.r[i] - old.plastic.rest[i])
    size = np.sqrt(trial[0] ** 2 + trial[1] ** 2 + trial[2] ** 2)
    yielded = size > q.yield_force
    for i in range(3):
        unit = trial[i] / size if yielded else trial[i]
        out.f[i] += -q.yield_force * unit if yielded else -trial[i]
        new.plastic.rest[i] = ctx.r[i] - q.yield_force / q.k * unit if yielded else old.plastic.rest[i]
    if ctx.jac:  # A = -f_r
        for i in range(3):
            for j in range(3):
                delta = 1.0 if i == j else 0.0
                if yielded:
                    out.A[i, j] += q.yield_force / size * q.k * (delta - trial[i] * trial[j] / (size * size))
                else:
                    out.A[i, j] += q.k * delta


def build_plastic(setting):
    if setting.keys is None:
        return None
    return PlasticSpring(setting.keys["stiffness"], setting.keys["yield_force"], len(setting.props["mass"]))


PLASTIC = LoadSpec("plastic", "full", (("k", "f8"), ("yield_force", "f8")), plastic_point, PlasticSpring,
                   history=(("rest", "f8", (3,)),), scratch=(("trial", "f8", (3,)),), frames=("rest",), build=build_plastic,
                   section="plastic_spring", keys={"stiffness": v.positive, "yield_force": v.positive})


def register():
    """The newcomer's one line per load."""
    from cablefem.loads import catalog

    catalog.register(UNIFORM)
    catalog.register(PLASTIC)


if __name__ == "__main__":
    register()
    from toy_measure import measure

    json.dump(measure(sys.argv[1]), sys.stdout)
