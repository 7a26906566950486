"""Defaults chosen by a scene's physics where the scene file does not set the key (docs/scene.md,
"Defaults by physics"); a key the file sets is obeyed as written.

- **A MoorDyn line's mesh.** NumSegs states an accuracy, MoorDyn's lumped-mass error at NumSegs
  segments, not a mesh to copy: a line whose element count and order no key sets gets P2 elements,
  ``ceil(NumSegs / NUMSEGS_PER_P2)`` per MoorDyn line up to NumSegs ``FITTED_NUMSEGS``, and above it
  ``FITTED_NUMSEGS / NUMSEGS_PER_P2 x (NumSegs / FITTED_NUMSEGS)^NUMSEGS_GROWTH`` rounded up, the fewest
  that are at least as accurate by the error's fits (verification/work_precision/numsegs.py derives both). A line on Hermite elements (EI > 0)
  keeps NumSegs of them (the ratio was measured on Lagrange elements), a line with a buoyant
  segment P1 x NumSegs (``keeps_numsegs``: a P2 element floating at zero tension folds).
- **The step.** Fixed steps of a fortieth of the shortest period of what drives the scene (a motion's
  period or ramp, the strong wave components). Error control (``adaptive = true``, both integrators,
  lines and networks, local tension error ``Solver.error_tolerance``) is not the default: on OC4's
  chains it is more accurate but never cheaper, on the flume chain's snap no more accurate at any
  tolerance and dearer, and its rows fall on the frames only (docs/scene.md; ``python -m
  benchmarks.systems --adaptive``). Asked for
  alone, its largest step is a twentieth of that period (``largest_step``).
- **VTK frames.** A MoorDyn file's dtOut where it gives one; else a tenth of the shortest forcing
  period (each frame ends a compiled march and costs ~2 ms of OC4's run; tensions.csv keeps every
  step), with error control at least its largest step (its steps land on every frame).

The dataclasses of ``cablefem.model.scene`` keep the plain defaults for scenes built in Python.
"""

import math
from dataclasses import replace

import numpy as np

#: P2 elements per MoorDyn segment are 1 / NUMSEGS_PER_P2, as many nodes as MoorDyn's: as accurate as
#: its lumped mass at NumSegs 10-20 in statics by the error's fits (verification/work_precision/numsegs.py:
#: 0.36-0.50 NumSegs needed)
NUMSEGS_PER_P2 = 2
#: above FITTED_NUMSEGS the P2 count grows as NumSegs^NUMSEGS_GROWTH, the fits' p1 / p2 (P1's error
#: falls as N^-p1, P2's as n^-p2: 1.42 on OC4's chain, 1.36 on the flume chain; the larger is kept),
#: from NumSegs / NUMSEGS_PER_P2 at FITTED_NUMSEGS: 27 at NumSegs 40 and 72 at 80, where the fits ask
#: for 25.6-25.9 and 65.7-69.5 (P2 x NumSegs / 2 falls short there)
FITTED_NUMSEGS = 20
NUMSEGS_GROWTH = 1.42
#: the element order a MoorDyn line gets where no key sets its order or element count
MOORDYN_ORDER = 2
#: fixed steps per shortest forcing period (OC4's chains at P2 x 10: 2.0 % RMS at 40, 3.3 % at 20,
#: MoorDyn-C's file 2.8 %; benchmarks/systems.py)
FIXED_STEPS_PER_PERIOD = 40
#: adaptive steps per shortest forcing period at most; and the largest step of a scene driven by none [s]
STEPS_PER_PERIOD = 20
LONGEST_STEP = 1.0
#: VTK frames per shortest forcing period (OC4 at defaults: frames every 0.25 s cost 2.2x the run of
#: frames every 1 s, benchmarks/systems.py)
FRAMES_PER_PERIOD = 10
#: wave components this fraction of the largest amplitude or more set the shortest wave period
WAVE_AMPLITUDE_SHARE = 0.1


def moordyn_elements(numsegs):
    """P2 elements that reach at least the accuracy of MoorDyn's ``numsegs`` segments (int): half of
    them up to FITTED_NUMSEGS, above it growing as numsegs^NUMSEGS_GROWTH."""
    if numsegs <= FITTED_NUMSEGS:
        return max(1, math.ceil(numsegs / NUMSEGS_PER_P2))
    return math.ceil(FITTED_NUMSEGS / NUMSEGS_PER_P2 * (numsegs / FITTED_NUMSEGS) ** NUMSEGS_GROWTH)


def keeps_numsegs(line, water_density):
    """Whether a MoorDyn line keeps its file's mesh (bool): on Hermite elements (EI > 0), NumSegs of
    them, as numsegs.py measured Lagrange elements only; with a buoyant segment (mass below
    ``water_density`` [kg/m^3] times its area), P1 x NumSegs, MoorDyn's own accuracy in statics. A
    buoyant segment can float at zero tension, where a P2 element folds within itself at no energy
    (a tension-only line's quadrature points compress freely: tripod.txt's float, EI zeroed, bends a
    P2 element to -16 % strain at a point and its statics stall at 3e-8 against the 1e-8 tolerance
    on every P2 mesh tried, where P1's straight elements converge)."""
    return line.element == "hermite" or any(s.type.mass < water_density * s.type.area for s in line.segments)


def moordyn_mesh(lines, water_density):
    """A MoorDyn file's lines (each segment's ``elements`` its NumSegs) on the default mesh: P2 with
    ``moordyn_elements`` per segment, except the lines that ``keeps_numsegs``. Returns (lines, note)."""
    meshed = [line if keeps_numsegs(line, water_density) else
              replace(line, order=MOORDYN_ORDER,
                      segments=tuple(replace(s, elements=moordyn_elements(s.elements)) for s in line.segments))
              for line in lines]
    counts = ", ".join(f"{line.name}: NumSegs {'+'.join(str(s.elements) for s in line.segments)} -> "
                       f"{'+'.join(str(s.elements) for s in new.segments)}"
                       + (" Hermite" if new.element == "hermite" else " P1, a buoyant segment" if new.order == 1 else "")
                       for line, new in zip(lines, meshed))
    note = (f"mesh: NumSegs read as an accuracy, MoorDyn's lumped-mass error at NumSegs segments; P2 elements, "
            f"NumSegs / {NUMSEGS_PER_P2} rounded up (above NumSegs {FITTED_NUMSEGS} more, as the statics error's fits ask), "
            f"reach it ({counts}); [moordyn] order or elements in a "
            "TOML that wraps the file set the mesh")
    return meshed, note


def _motion_periods(motion):
    """A motion's periods [s]: a harmonic or circular motion's period, twice a table's shortest row
    interval (the shortest period its rows resolve), its ramp."""
    periods = []
    if motion.kind in ("harmonic", "circular"):
        periods.append(motion.period)
    if motion.kind == "table" and motion.times is not None and len(motion.times) > 1:
        periods.append(2.0 * float(np.min(np.diff(motion.times))))
    if motion.ramp > 0.0:
        periods.append(motion.ramp)
    return periods


def forcing_periods(motion, sea=None, bodies=()):
    """The periods [s] of what drives a scene: the fairleads' [motion] and each coupled body's motion
    (``_motion_periods``), the waves' components of at least WAVE_AMPLITUDE_SHARE of the largest
    amplitude, and twice the interval of a current's record that varies in time (MoorDyn's Currents 2
    and 4)."""
    periods = _motion_periods(motion)
    for body in bodies:
        if body.kind == "coupled" and body.motion is not None:
            periods += _motion_periods(body.motion)
    if sea is not None:
        amplitude, omega = np.asarray(sea.amplitude, dtype=float), np.asarray(sea.omega, dtype=float)
        if amplitude.size:  # a sea of no components carries a current alone
            strong = (amplitude >= WAVE_AMPLITUDE_SHARE * amplitude.max()) & (omega > 0.0)
            periods += [2.0 * math.pi / w for w in omega[strong]]
        current = sea.current
        if current is not None and current.velocity.shape[3] > 1 and current.dt > 0.0:
            periods.append(2.0 * current.dt)  # the shortest period its record resolves
        if sea.ramp > 0.0:
            periods.append(sea.ramp)
    return [p for p in periods if p > 0.0]


def largest_step(motion, sea=None, bodies=()):
    """The largest adaptive step [s]: the shortest forcing period / STEPS_PER_PERIOD, at most LONGEST_STEP."""
    periods = forcing_periods(motion, sea, bodies)
    return min([LONGEST_STEP] + [p / STEPS_PER_PERIOD for p in periods])


def step(solver, given, motion, sea=None, bodies=()):
    """``solver`` with the step chosen where the [solver] keys in ``given`` (the names the scene sets)
    leave it open: neither ``dt`` nor ``adaptive`` given, fixed steps of the shortest forcing period /
    FIXED_STEPS_PER_PERIOD (the plain 0.01 s where nothing drives the scene); ``adaptive = true``
    alone, error control with its largest step by ``largest_step``. Returns (solver, note or None)."""
    if "dt" in given or ("adaptive" in given and not solver.adaptive):
        return solver, None
    if "adaptive" in given:
        solver = replace(solver, dt=largest_step(motion, sea, bodies))
        return solver, (f"steps: error control, local tension error {solver.error_tolerance:g} of each line's "
                        f"largest tension per step, at most {solver.dt:g} s (a twentieth of the shortest forcing "
                        f"period, at most {LONGEST_STEP:g} s)")
    periods = forcing_periods(motion, sea, bodies)
    if not periods:
        return solver, None
    solver = replace(solver, dt=min(periods) / FIXED_STEPS_PER_PERIOD)
    return solver, (f"steps: fixed, dt = {solver.dt:g} s, 1/{FIXED_STEPS_PER_PERIOD} of the shortest forcing "
                    f"period ({min(periods):g} s); [solver] dt or adaptive = true set them")


def frames(output, given, solver, motion, sea=None, bodies=()):
    """``output`` with its frame interval ``every`` [s] chosen where ``given`` (the [output] keys the
    scene sets, "every" for a MoorDyn file's dtOut) leaves it open: a tenth of the shortest forcing
    period, or the plain interval where nothing drives the scene; with error control at least its
    largest step (an adaptive run's steps land on every frame). Returns (output, note or None)."""
    if "every" in given:
        return output, None
    periods = forcing_periods(motion, sea, bodies)
    every = min(periods) / FRAMES_PER_PERIOD if periods else output.every
    if solver.adaptive:
        every = max(every, solver.dt)
    if every == output.every:
        return output, None
    return replace(output, every=every), (f"frames: a VTK frame every {every:g} s, 1/{FRAMES_PER_PERIOD} of the "
                                          f"shortest forcing period or the largest step; tensions.csv has "
                                          "every step; [output] every sets it")
