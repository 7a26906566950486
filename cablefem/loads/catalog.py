"""The catalog of loads: every physical load of cablefem, in one list, and the record layouts built
from it (docs/architecture.md, "Adding a load").

Each load lives in one module with its two faces: the numpy reference (a class with
``evaluate(state, jacobian) -> Terms``, assembled through scikit-fem's forms) and the compiled
point kernel (numba), and describes itself in a ``LoadSpec``: its name, the quadrature rule it is
evaluated at, the parameters its kernel reads per element, the branch state it writes per point
and the branch holds it reads (Newton's corrections, ``cablefem.dynamics.policy``), its history per point
(committed on accepted steps), its scratch (named working values at a point, in the point context)
and the loads whose scratch it reads. The system (``cablefem.fem.system``), the compiled
evaluation (``cablefem.compiled.kernels``) and the compiled steps all build their load set, parameter
records, per-point records and scratch from this list by name: a kernel reads ``p.drag.normal``
from the element's record and ``ctx.contact.normal_force`` from the point context, never a column or
slot number.

``CATALOG`` order is the order the loads add their forces at a point (the compiled and the
reference faces sum in the same order).
"""

import numpy as np

#: the placeholder field of a record no load writes (numpy records need one field at least)
EMPTY = (("unused", "?"),)
#: where a load is evaluated: the full or the reduced quadrature points of each element, or
#: vertices of the line (a concentrated force: ``cablefem.loads.points``)
RULES = ("full", "reduced", "node")


def _default():
    from cablefem.loads import (added_mass, bending, contact, drag, friction, gravity, morison, points, rope, soil,
                                tension)

    return [tension.SPEC, rope.SPEC, bending.SPEC, gravity.SPEC, contact.SPEC, friction.SPEC, soil.SPEC,
            drag.SPEC, added_mass.SPEC, morison.SPEC, points.SPEC]


CATALOG = _default()
_frozen = []  # the Layout once the compiled kernels were built from it


def register(spec):
    """Add a load to the catalog. Only before the compiled kernels are built (the first import of
    ``cablefem.compiled.kernels``): they are compiled for one catalog, and numba caches them on disk."""
    if _frozen:
        raise RuntimeError(f"cannot register load '{spec.name}': the compiled kernels were built from "
                           "the catalog already; register loads before anything compiles "
                           "(see docs/architecture.md)")
    if any(existing.name == spec.name for existing in CATALOG):
        raise ValueError(f"a load named '{spec.name}' is in the catalog already")
    CATALOG.append(spec)


def spec(name):
    """The catalog's ``LoadSpec`` of ``name``; KeyError naming the known loads otherwise."""
    for entry in CATALOG:
        if entry.name == name:
            return entry
    raise KeyError(f"no load '{name}' in the catalog ({', '.join(s.name for s in CATALOG)})")


def spec_of(load):
    """The ``LoadSpec`` of a numpy load object; a clear error for a load with no compiled face. A
    variant of a catalog load (a wrapper that changes its numpy face for a study, e.g.
    validation/moordyn/switches.py; numpy path only) names the load it wraps as ``.wrapped`` and
    has that load's spec: its name, rule and history."""
    while not any(isinstance(load, entry.reference) for entry in CATALOG) and hasattr(load, "wrapped"):
        load = load.wrapped
    for entry in CATALOG:
        if isinstance(load, entry.reference):
            return entry
    raise TypeError(f"{type(load).__name__} is not in the load catalog (cablefem.loads.catalog): every "
                    "load needs a compiled face and one catalog line (docs/architecture.md)")


def build_loads(setting):
    """The loads a line of a scene gets, in catalog order: every spec's ``build(setting)`` that
    gives one (``setting.keys`` is the scene's table of the spec's section, or None), unless the
    line lacks a load whose scratch it reads (``LoadSpec.reads``: no contact, no friction)."""
    loads, built = [], set()
    for entry in CATALOG:
        if entry.build is None or not built.issuperset(entry.reads):
            continue
        keys = setting.sections.get(entry.section) if entry.section else None
        load = entry.build(setting.with_keys(keys))
        if load is not None:
            loads.append(load)
            built.add(entry.name)
    return loads


def sections():
    """The scene tables the catalog's loads read: {section: {key: converter}}."""
    return {entry.section: entry.keys for entry in CATALOG if entry.section}


def _record(parts):
    """A nested, aligned record dtype from (name, fields) pairs, the empty ones left out."""
    fields = [(name, np.dtype(list(entries), align=True)) for name, entries in parts if entries]
    return np.dtype(fields or list(EMPTY), align=True)


class Layout:
    """Record dtypes and kernel tuples of a catalog (``layout``)."""

    def __init__(self, catalog):
        self.specs = tuple(catalog)
        for k, s in enumerate(self.specs):
            if s.rule not in RULES:
                raise ValueError(f"load '{s.name}': rule must be one of {', '.join(RULES)}, got {s.rule!r}")
            if s.rule == "node" and (s.state or s.hold or s.history):
                raise ValueError(f"load '{s.name}': a node load has parameters only (no branch state, "
                                 "holds or history yet)")
            for name in s.reads:
                if not any(e.name == name and e.rule == s.rule and e.scratch for e in self.specs[:k]):
                    raise ValueError(f"load '{s.name}' reads the scratch of '{name}', which must be a load "
                                     f"of rule '{s.rule}' with scratch, earlier in the catalog")
        self.params = _record((s.name, (("active", "?"),) + tuple(s.params)) for s in self.specs if s.rule != "node")
        self.node = tuple(s for s in self.specs if s.rule == "node")
        self.node_params = _record((s.name, (("active", "?"),) + tuple(s.params)) for s in self.node)
        self.node_kernels = tuple(s.kernel for s in self.node)
        self.full = tuple(s for s in self.specs if s.rule == "full")
        self.reduced = tuple(s for s in self.specs if s.rule == "reduced")
        for rule, specs in (("full", self.full), ("reduced", self.reduced)):
            for kind in ("state", "hold", "history"):
                setattr(self, f"{rule}_{kind}", _record((s.name, getattr(s, kind)) for s in specs))
        self.full_kernels = tuple(s.kernel for s in self.full)
        self.reduced_kernels = tuple(s.kernel for s in self.reduced)
        self.full_rules = tuple(s.hold_rule for s in self.full if s.hold_rule is not None)
        self.reduced_rules = tuple(s.hold_rule for s in self.reduced if s.hold_rule is not None)
        #: the loads' scratch, one named record each (``ctx.<name>`` in ``cablefem.compiled.kernels``)
        self.scratch = tuple((s.name, np.dtype(list(s.scratch), align=True)) for s in self.specs if s.scratch)
        self.has_history = any(s.history for s in self.specs)


def layout():
    """The Layout of the catalog, which freezes it (``register`` refuses from then on)."""
    if not _frozen:
        _frozen.append(Layout(CATALOG))
    return _frozen[0]
