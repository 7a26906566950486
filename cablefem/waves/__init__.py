"""Linear waves, independent of the FEM: the sea (``Sea``: components over water of constant
depth), its kinematics at points and times (``cablefem.waves.airy``, compiled in
``cablefem.waves.compiled``), irregular seas from a spectrum (``cablefem.waves.spectra``), and seas
from a record of the elevation (``cablefem.waves.series``). The loads that act on lines and points
in waves are in ``cablefem.loads.morison`` and ``cablefem.loads.points``; the scene's ``[waves]``
table is read by ``cablefem.io.waves``.
"""

from cablefem.waves.dispersion import wave_number
from cablefem.waves.sea import STRETCHING, Sea

__all__ = ["STRETCHING", "Sea", "wave_number"]
