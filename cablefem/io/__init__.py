"""Input and output: scene readers (TOML, MoorDyn v2 input files) and result writers.

``cablefem.scene.load_scene`` is the entry point for scenes; the readers are
``read_toml_scene`` (``toml_scene``) and ``read_moordyn`` (``moordyn_input``).
Writers (``vtk``, ...) are imported from their own modules.
"""

from .moordyn_input import read_moordyn
from .toml_scene import read_toml_scene

__all__ = ["read_moordyn", "read_toml_scene"]
