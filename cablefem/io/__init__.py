"""Input and output: scene readers (TOML, MoorDyn v2 input files) and result writers.

``load_scene`` is the entry point for scenes (``cablefem.io.scenes`` picks the reader); the
readers are ``read_toml_scene`` (``toml_scene``) and ``read_moordyn`` (``moordyn_input``).
Writers (``vtk``, ``output``, ...) are imported from their own modules.
"""

from .moordyn_input import read_moordyn
from .scenes import MOORDYN_EXTENSIONS, load_scene
from .toml_scene import read_toml_scene

__all__ = ["MOORDYN_EXTENSIONS", "load_scene", "read_moordyn", "read_toml_scene"]
