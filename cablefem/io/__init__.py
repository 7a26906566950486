"""Input and output: scene readers (TOML, MoorDyn v2 input files) and result writers.

``load_scene`` is the entry point for scenes (``cablefem.io.scenes`` picks the reader); the
readers are ``read_toml_scene`` (``toml_scene``) and ``read_moordyn`` (``moordyn_input``).
Writers (``vtk``, ``output``, ...) are imported from their own modules. The readers are
imported on first use: a writer does not load them.
"""

from importlib import import_module

_LAZY = {"load_scene": "scenes", "MOORDYN_EXTENSIONS": "scenes", "read_moordyn": "moordyn_input",
         "read_toml_scene": "toml_scene"}

__all__ = list(_LAZY)


def __getattr__(name):
    """The readers by name, imported on first use."""
    if name in _LAZY:
        return getattr(import_module(f"{__name__}.{_LAZY[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
