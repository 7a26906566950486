"""The one registry of time integrators: ``[solver] integrator`` names a key (docs/architecture.md,
"Adding an integrator"). Entries are imported when first asked for, so that a scene is read, and
``cablefem static`` runs, without loading the compiled steps."""

from importlib import import_module


class _Registry(dict):
    """Integrator names -> classes, each imported when first asked for (the compiled steps of BDF2
    load numba's kernels: a scene is read, and ``cablefem static`` runs, without them)."""

    def __getitem__(self, name):
        entry = super().__getitem__(name)
        if isinstance(entry, str):
            module, _, attribute = entry.rpartition(".")
            entry = getattr(import_module(module), attribute)
            super().__setitem__(name, entry)
        return entry

    def values(self):
        return [self[name] for name in self]

    def items(self):
        return [(name, self[name]) for name in self]


#: the one registry of integrators: [solver] integrator names their key (docs/architecture.md,
#: "Adding an integrator"): the integrator class, or where to import it from
INTEGRATORS = _Registry({"bdf2": "cablefem.dynamics.bdf2.BDF2",
                         "generalized-alpha": "cablefem.dynamics.generalized_alpha.GeneralizedAlpha"})


def integrator_options(solver, integrator=None):
    """Keyword arguments of ``integrator`` (a class, or its name in ``INTEGRATORS``; default:
    ``solver.integrator``) from a scene's ``Solver``: the common ones and those its class reads
    (``Integrator.options``)."""
    cls = integrator if isinstance(integrator, type) else INTEGRATORS[integrator or solver.integrator]
    return {"tolerance": solver.tolerance, "newton": solver.newton, "adaptive": solver.adaptive,
            "error_tolerance": solver.error_tolerance, **cls.options(solver)}
