"""A scene: lines + seabed + water + motion + solver settings (docs/scene.md: every key).

Data only: scenes are read by ``cablefem.io.load_scene`` (TOML, ``cablefem.io.toml_scene``, or a
MoorDyn v2 input file, ``cablefem.io.moordyn_input``); the built-in ones are in
``cablefem.model.builtin``. Defaults of every optional key live here, in one place.
"""

from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Environment:
    """Water and gravity: density [kg/m^3], gravity [m/s^2], uniform current [m/s] (3,), or a
    current varying with depth (``cablefem.loads.current.CurrentProfile``, then ``current`` is zero),
    and waves (a ``cablefem.waves.Sea``, None in still water), which add to the current."""

    water_density: float = 1025.0
    gravity: float = 9.81
    current: tuple = (0.0, 0.0, 0.0)
    current_profile: object = None
    waves: object = None


@dataclass(frozen=True)
class Contact:
    """Seabed normal contact (desire2023 Eq. 11): ground stiffness per unit area [N/m^3]
    and damping, either as a fraction of critical (``damping_ratio``) or, as MoorDyn's
    cBot, as an absolute coefficient per unit area [N s/m^3] (``damping``, overrides)."""

    stiffness: float = 3.0e5
    damping_ratio: float = 1.0
    damping: float | None = None
    #: the damper acts on points moving out of the seabed too (MoorDyn-C), not only closing ones
    damping_when_opening: bool = False


@dataclass(frozen=True)
class Friction:
    """Seabed friction: model "none" | "isotropic" (desire2023 Eq. 12) |
    "anisotropic" (housner2022 Eq. 5-13); kinetic coefficients, static/kinetic
    scale, and the saturation velocity [m/s]."""

    model: str = "none"
    mu: float = 0.3
    mu_axial: float = 0.69
    mu_transverse: float = 1.0
    static_scale: float = 1.0
    v_threshold: float = 0.01
    saturation_damping: float | None = None  # MoorDyn-C FricDamp [N s/m per node], if read from MoorDyn


@dataclass(frozen=True)
class Motion:
    """Prescribed fairlead motion relative to the scene's fairlead position.

    kind: "fixed" | "harmonic" | "circular" | "table". Harmonic: amplitude (3,) [m],
    period [s], offset (3,) [m]. Circular: radius [m], period [s], plane ("xy", "xz",
    "yz"). Table: times (k,) [s] and positions (k, 3) [m], joined by a smooth spline or, with
    ``interpolation = "linear"``, by straight lines (``cablefem.model.motion``). ``ramp`` [s] scales
    the whole displacement by the smoothstep 3u^2 - 2u^3, u = t / ramp.
    """

    kind: str = "fixed"
    amplitude: tuple = (0.0, 0.0, 0.0)
    period: float = 1.0
    offset: tuple = (0.0, 0.0, 0.0)
    ramp: float = 0.0
    radius: float = 0.0
    plane: str = "xz"
    times: np.ndarray | None = None
    positions: np.ndarray | None = None
    phase: tuple = ()  # a body's harmonic motion: per component [rad]; empty: none
    interpolation: str = "spline"  # table: "spline" | "linear"


@dataclass(frozen=True)
class Solver:
    """Solver settings: integrator ("bdf2" | "generalized-alpha"), time step [s], duration [s],
    relative residual tolerance, Newton iteration cap, the assembly path ("kernel" or
    "forms"; "numpy", the statics of ``cablefem static`` on a small scene), the spectral radius at infinite frequency of generalised-alpha, whether
    the statics of ``cablefem static`` and of a run's start fit a mesh vertex to the touchdown point
    (``cablefem.statics.touchdown.solve_line``; a run then runs on that mesh),
    Newton in dynamics ("full", "modified": the tangent's LU factors kept across iterations
    and steps, or "auto": full with the compiled kernel, modified without), and the
    adaptive step control of BDF2 (dt is then the largest step; error_tolerance is the
    local tension error per step as a fraction of the largest tension)."""

    integrator: str = "bdf2"
    dt: float = 0.01
    duration: float = 120.0
    tolerance: float = 1e-8
    max_iterations: int = 50
    assembly: str = "kernel"
    rho_inf: float = 0.5
    fit_touchdown: bool = False
    newton: str = "auto"
    adaptive: bool = False
    error_tolerance: float = 3e-4


@dataclass(frozen=True)
class Output:
    """Where and how often a run writes: directory and seconds between VTK frames."""

    dir: str = "out"
    every: float = 0.1


@dataclass
class Scene:
    """Everything a solve needs. ``notes`` records what was chosen (seabed model, ...);
    ``keys`` where a scene key (``lines[0].anchor``, ``seabed``) was written when that is not
    the key itself in ``source``: scene key -> (file, key in that file), for error messages."""

    name: str
    lines: list
    seabed: object
    contact: Contact = field(default_factory=Contact)
    environment: Environment = field(default_factory=Environment)
    friction: Friction = field(default_factory=Friction)
    motion: Motion = field(default_factory=Motion)
    solver: Solver = field(default_factory=Solver)
    output: Output = field(default_factory=Output)
    source: str | None = None
    notes: list = field(default_factory=list)
    moordyn_options: dict = field(default_factory=dict)  # raw OPTIONS of a MoorDyn file (name -> text)
    keys: dict = field(default_factory=dict)
    load_settings: dict = field(default_factory=dict)  # tables of the catalog's loads: section -> {key: value}
    points: dict = field(default_factory=dict)  # name -> cablefem.model.network.Point
    bodies: dict = field(default_factory=dict)  # name -> cablefem.model.network.Body
    failures: tuple = ()  # cablefem.model.failure.Failure: line ends that let go during a run

    def where(self, key):
        """(file, key) naming where scene key ``key`` was written (``Scene.keys``)."""
        return self.keys.get(key, (self.source, key))
