"""The scene's ``[waves]`` table (docs/scene.md, "Waves") read into a ``cablefem.waves.Sea``.

``kind`` chooses the keys: "regular" (amplitude, period, direction, phase), "irregular" (spectrum,
Hs, Tp, gamma, direction, components, seed, spreading, frequency_band), "components" (arrays
amplitude, period, direction, phase) or "elevation" (a file of t, eta at the origin; direction);
every kind takes ramp, depth (default: the water depth at the origin) and stretching. Angles are
in degrees. A key of another kind is refused naming the kind it belongs to.
"""

import math

import numpy as np

from cablefem.errors import InputError
from cablefem.io import validate as v
from cablefem.waves import STRETCHING, Sea
from cablefem.waves.series import from_record
from cablefem.waves.spectra import SPECTRA, irregular

KINDS = ("regular", "irregular", "components", "elevation")
COMMON = ("kind", "ramp", "depth", "stretching")
KIND_KEYS = {"regular": ("amplitude", "period", "direction", "phase"),
             "irregular": ("spectrum", "Hs", "Tp", "gamma", "direction", "components", "seed", "spreading",
                           "frequency_band"),
             "components": ("amplitude", "period", "direction", "phase"),
             "elevation": ("file", "direction", "time_step")}
REQUIRED = {"regular": ("amplitude", "period"), "irregular": ("Hs", "Tp"), "components": ("amplitude", "period"),
            "elevation": ("file",)}
_HEIGHT = v.limited(v.non_negative, "length")
_ANGLE = v.limited(v.number, "angle")
#: at most this many components (each costs every quadrature point of every line, every evaluation)
MAX_COMPONENTS = 10000


def _count(value, key):
    count = v.limited(v.whole, "nodes")(value, key)
    if count > MAX_COMPONENTS:
        raise InputError(f"{count} components, at most {MAX_COMPONENTS}", key=key)
    return count


def _seed(value, key):
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise InputError(f"expected a whole number >= 0, got {v.describe_type(value)} {value!r}", key=key)
    return value


def _band(value, key):
    if not isinstance(value, list) or len(value) != 2:
        raise InputError(f"expected [low, high] in rad/s, got {value!r}", key=key)
    return tuple(v.positive(x, f"{key}[{i}]") for i, x in enumerate(value))


def _numbers(converter):
    def convert(value, key):
        if not isinstance(value, list) or not value:
            raise InputError(f"expected an array of numbers, got {v.describe_type(value)}", key=key)
        return [converter(x, f"{key}[{i}]") for i, x in enumerate(value)]
    return convert


CONVERTERS = {"kind": v.choice(KINDS), "ramp": v.non_negative, "depth": v.limited(v.positive, "length"),
              "stretching": v.choice(STRETCHING), "amplitude": _HEIGHT, "period": v.positive, "direction": _ANGLE,
              "phase": _ANGLE, "spectrum": v.choice(SPECTRA), "Hs": v.limited(v.positive, "length"),
              "Tp": v.positive, "gamma": v.limited(v.positive, "coefficient"), "components": _count, "seed": _seed,
              "spreading": v.limited(v.positive, "coefficient"), "frequency_band": _band, "file": v.text,
              "time_step": v.positive}
ARRAYS = {"amplitude": _numbers(_HEIGHT), "period": _numbers(v.positive), "direction": _numbers(_ANGLE),
          "phase": _numbers(_ANGLE)}


def water_depth(seabed, key="waves.depth"):
    """The water depth [m] at the origin: minus the seabed's elevation below (0, 0)."""
    depth = -float(np.asarray(seabed.elevation(np.zeros((1, 2))))[0])
    if not depth > 0.0:
        raise InputError(f"the seabed below the origin is at z = {-depth:g} m, not below the water: give the "
                         "depth the waves see", key=key)
    return depth


def read_waves(raw, folder, seabed, gravity):
    """The Sea of a ``[waves]`` table; relative files resolve against ``folder``, the default depth is
    the water depth at the origin of ``seabed``, ``gravity`` [m/s^2] enters the dispersion."""
    raw = v.table(raw, "waves")
    v.check_keys(raw, raw, "waves", required=("kind",))
    kind = v.choice(KINDS)(raw["kind"], "waves.kind")
    owners = {}
    for other, keys in KIND_KEYS.items():
        for name in keys:
            owners.setdefault(name, []).append(other)
    elsewhere = {name: f"does not apply to waves kind '{kind}' (it belongs to {' and '.join(kinds)})"
                 for name, kinds in owners.items()}
    converters = dict(CONVERTERS, **(ARRAYS if kind == "components" else {}))
    converters = {name: converters[name] for name in COMMON + KIND_KEYS[kind]}
    values = v.pick(raw, "waves", converters, required=REQUIRED[kind], elsewhere=elsewhere)
    depth = values.get("depth") or water_depth(seabed)
    options = {"stretching": values.get("stretching", "wheeler"), "ramp": values.get("ramp", 0.0)}
    direction = math.radians(values.get("direction", 0.0)) if kind != "components" else 0.0
    if kind == "regular":
        return Sea.regular(values["amplitude"], values["period"], direction, math.radians(values.get("phase", 0.0)),
                           depth, gravity, state=(("amplitude", values["amplitude"]), ("period", values["period"]),
                                                  ("direction_deg", values.get("direction", 0.0))), **options)
    if kind == "irregular":
        if values.get("spectrum") == "pierson-moskowitz" and "gamma" in values:
            raise InputError("applies to the JONSWAP spectrum only (Pierson-Moskowitz has gamma = 1)",
                             key="waves.gamma")
        return irregular(values["Hs"], values["Tp"], depth, gravity, spectrum=values.get("spectrum", "jonswap"),
                         gamma=values.get("gamma", 3.3), direction=direction,
                         components=values.get("components", 200), seed=values.get("seed", 0),
                         spreading=values.get("spreading"), band=values.get("frequency_band"), **options)
    if kind == "components":
        return _components(values, depth, gravity, options)
    file = v.existing_file(values["file"], "waves.file", folder)
    times, eta = read_elevation(file, "waves.file")
    sea = from_record(times, eta, depth, gravity, direction, step=values.get("time_step"), key="waves",
                      source=file, **options)
    return sea


def _components(values, depth, gravity, options):
    """The Sea of ``kind = "components"``: arrays of one length (direction and phase default to 0)."""
    count = len(values["amplitude"])
    for name in ("period", "direction", "phase"):
        if name in values and len(values[name]) != count:
            raise InputError(f"expected {count} values, one per amplitude, got {len(values[name])}",
                             key=f"waves.{name}")
    radians = {name: np.radians(values.get(name, [0.0] * count)) for name in ("direction", "phase")}
    return Sea.from_components(values["amplitude"], 2.0 * np.pi / np.array(values["period"]), radians["direction"],
                               radians["phase"], depth, gravity, **options)


def read_elevation(path, key):
    """Times (k,) [s] strictly increasing and elevations (k,) [m] from a file of rows t, eta (commas,
    semicolons or blanks between; ``#`` starts a comment line; an optional header row ``t,eta``)."""
    data = v.read_time_table(path, key, ("t", "eta"), 4)
    return data[:, 0], data[:, 1]
