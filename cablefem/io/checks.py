"""Scene-level checks, run on every scene before any work starts (docs/scene.md, "Limits").

The readers check each value where it is written: its type, its range and its
sane limit (``validate.LIMITS``). What needs the whole scene is checked here,
once for TOML and MoorDyn scenes alike (``cablefem.io.load_scene``), and by
``run_scene`` for scenes built in Python:

- names: the scene name starts every output file name, line names head
  tensions.csv columns;
- problem size: the nodes of all lines, the steps and frames of a run;
- the line ends against the water and the seabed: no seabed above the still water surface below a
  line end, no anchor or fairlead below the seabed (a padeye may lie there only with ``[soil]``);
  ends above the water are valid where the file puts them (a beam or a jumper in the air);
- a scene with ``[soil]`` (``check_soil``): a soil with some strength, lines between a fixed padeye
  and a fairlead (no free end, no points on them), every line type's ``nominal_diameter``, each
  padeye on or below the seabed surface (the laid line starts from it up or down to the lying
  chain), and a line long enough to be laid;
- the prescribed motion over its whole course, not only at rest: the peak
  chord strain of every line, the peak speed and acceleration of the fairlead.

Errors name the file and the key where the value was written (``Scene.where``:
``lines[0].anchor`` in a TOML, ``line 11: POINTS.1`` in a MoorDyn file).
"""

import math

import numpy as np

from cablefem.errors import InputError
from cablefem.io import validate as v

#: the ramp's smoothstep S(u) = 3u^2 - 2u^3 has |dS/dt| <= 1.5 / ramp, |d2S/dt2| <= 6 / ramp^2
_RAMP_SPEED, _RAMP_ACCELERATION = 1.5, 6.0
#: most time steps of a run: ~5 us per node and step, so 1e9 steps of the smallest line take days
MAX_STEPS = 1_000_000_000
#: most VTK frames of a run: a million files (~4 GB for a 40-element line) is beyond what
#: ParaView opens comfortably; write them less often ([output] every)
MAX_FRAMES = 1_000_000
_PLANE_AXES = {"xy": (0, 1), "xz": (0, 2), "yz": (1, 2), "yx": (1, 0), "zx": (2, 0), "zy": (2, 1)}


def _error(scene, key, reason):
    """An InputError at scene key ``key``, located where the scene's reader found it (an option
    of the command line, ``--dt``, is located by itself)."""
    if key.startswith("--"):
        return InputError(reason, key=key)
    file, where = scene.where(key)
    return InputError(reason, key=where, file=file)


def check_scene(scene):
    """Every scene-level check of this module; returns the scene (InputError at the first failure)."""
    check_names(scene)
    check_size(scene)
    check_run(scene)
    check_ends(scene)
    check_floating(scene)
    check_soil(scene)
    check_motion(scene)
    return scene


def check_names(scene):
    """The scene name is safe as the start of a file name; line names are printable."""
    file, key = scene.where("name")
    try:
        v.file_name_part(scene.name, key)
        for i, line in enumerate(scene.lines):
            file, key = scene.where(f"lines[{i}].name")
            v.printable_name(line.name, key)
    except InputError as error:
        raise InputError(error.reason, key=error.key, file=file) from None


def check_size(scene):
    """Refuse more nodes (order x elements + 1 per line) than ``LIMITS["nodes"]`` in all."""
    bound, _, why = v.LIMITS["nodes"]
    nodes = [line.order * sum(seg.elements for seg in line.segments) + 1 for line in scene.lines]
    if sum(nodes) > bound:
        i = int(np.argmax(nodes))
        line = scene.lines[i]
        j = int(np.argmax([seg.elements for seg in line.segments]))
        raise _error(scene, f"lines[{i}].segments[{j}].elements",
                     f"{sum(nodes):.4g} nodes in the scene ({line.segments[j].elements} elements of order "
                     f"{line.order} here) are beyond the sane limit of {bound:g} nodes ({why})")


def check_run(scene, duration=None, dt=None):
    """Refuse a run of more than MAX_STEPS steps or MAX_FRAMES frames; ``duration`` and ``dt``
    [s] override the scene's (the command line's --duration and --dt)."""
    solver = scene.solver
    duration_key = "--duration" if duration is not None else "solver.duration"
    dt_key = "--dt" if dt is not None else "solver.dt"
    duration = solver.duration if duration is None else duration
    dt = solver.dt if dt is None else dt
    steps = duration / dt
    if not steps <= MAX_STEPS:
        default = type(solver)()  # blame the value farther from its default
        longer, finer = duration / default.duration, default.dt / dt
        raise _error(scene, duration_key if longer > finer else dt_key, f"{duration:g} s in steps of {dt:g} s make {steps:.3g} steps, beyond the "
                      f"sane limit of {MAX_STEPS:g} (~5 us per node and step: days of wall time)")
    every = scene.output.every if solver.adaptive else max(scene.output.every, dt)
    frames = duration / every
    if not frames <= MAX_FRAMES:
        key = duration_key if duration_key.startswith("--") else "output.every"
        raise _error(scene, key, f"{duration:g} s with a frame every {every:g} s make {frames:.3g} VTK "
                      f"frames, beyond the sane limit of {MAX_FRAMES:g} files")


def check_ends(scene):
    """No seabed above the water below a line end, no anchor or fairlead more than its line's
    diameter below the seabed (an end above the water is valid: a beam or a jumper in the air)."""
    for i, line in enumerate(scene.lines):
        ends = np.array([line.anchor, line.fairlead])
        elevation = np.asarray(scene.seabed.elevation(ends[:, :2]), dtype=float)
        for end, (x, y, _), height in zip(("anchor", "fairlead"), ends, elevation):
            if height > 0.0:
                raise _error(scene, "seabed", f"the seabed is {height:.6g} m above the still water "
                             f"surface (z = 0) below the {end} of line '{line.name}' at x = {x:g}, "
                             f"y = {y:g}: a seabed lies below the water")
        gap = np.asarray(scene.seabed.gap_only(ends), dtype=float)
        in_soil = "soil" in scene.load_settings
        for end, depth, segment in (("anchor", -gap[0], line.segments[0]),
                                    ("fairlead", -gap[1], line.segments[-1])):
            allowed = segment.type.diameter + 1e-9 * max(1.0, float(np.max(np.abs(ends))))
            if depth > allowed and not (end == "anchor" and in_soil):
                soil = ": a padeye below the seabed needs a [soil] table" if end == "anchor" else ""
                raise _error(scene, f"lines[{i}].{end}", f"the {end} lies {depth:.6g} m below the "
                             f"seabed (more than the line's diameter, {segment.type.diameter:g} m){soil}")


def _lift(line, rho, g):
    """The most a string can lift what it hangs from [N]: the buoyancy in water of its parts lighter
    than water (a string's other end on the seabed or free pulls down or not at all)."""
    lift = sum(max(0.0, (rho * math.pi / 4.0 * s.type.diameter ** 2 - s.type.mass) * g * s.length)
               for s in line.segments)
    return lift + sum(max(0.0, rho * g * j.volume - j.mass * g + j.force[2]) for _, j in line.joints)


def check_floating(scene):
    """A free body or rod (with the rods it carries and the points on it) heavier than all the water
    it can displace, whose lines all end on the seabed or hang free (so that they can lift it by no
    more than their own buoyancy): no equilibrium in the water, which MoorDyn-C's relaxation would
    let sink; refused, with its weight and buoyancy."""
    env = scene.environment
    rho, g = env.water_density, env.gravity
    for name, body in sorted(scene.bodies.items()):
        if body.kind != "free" or body.waterplane_area > 0.0 or np.any(body.force):
            continue
        rods = (body.rod,) if body.rod is not None else tuple(body.rods)
        weight = g * (body.mass + (0.0 if body.rod is not None else sum(rod.mass for rod in rods)))
        buoyancy = rho * g * (body.volume + sum(rod.area * rod.length for rod in rods))
        on_body = {p.name for p in scene.points.values() if p.body == name}
        for point in (scene.points[p] for p in on_body):
            weight, buoyancy = weight + point.mass * g - min(point.force[2], 0.0), buoyancy + rho * g * point.volume
            buoyancy += max(point.force[2], 0.0)
        lift, bounded = 0.0, True
        for line in scene.lines:
            for e, end in enumerate(line.ends):
                if end not in on_body:
                    continue
                other, at = line.ends[1 - e], (line.fairlead, line.anchor)[e]
                point = scene.points.get(other)
                free_end = point is not None and point.kind == "free" and point.body is None and \
                    sum(o == other for l2 in scene.lines for o in l2.ends) == 1
                grounded = point is not None and point.kind == "fixed" and point.body is None and \
                    float(np.asarray(scene.seabed.gap_only(np.asarray(at, dtype=float)[None]))[0]) <= \
                    line.segments[e - 1].type.diameter
                bounded = bounded and (free_end or grounded)
                lift += _lift(line, rho, g)
        if bounded and on_body and weight > buoyancy + lift:
            what = "rod" if body.rod is not None else "body"
            raise _error(scene, f"bodies.{name}", f"the free {what} '{name}' cannot float: it weighs {weight:.6g} N "
                         f"(with its rods and points), all the water it can displace lifts {buoyancy:.6g} N and its "
                         f"lines, which end on the seabed or hang free, lift at most {lift:.6g} N; give it volume "
                         "or buoyant lines, or make it fixed or coupled")


def check_soil(scene):
    """With ``[soil]``: some strength (su_mudline and su_gradient not both 0), every line type's
    ``nominal_diameter`` given, each padeye on the seabed surface or below it (within its line's
    diameter), each line longer than the climb from its padeye to the surface."""
    keys = scene.load_settings.get("soil")
    if keys is None:
        return
    if keys.get("su_mudline", 0.0) == 0.0 and keys["su_gradient"] == 0.0:
        raise _error(scene, "soil.su_gradient", "su_mudline and su_gradient are both 0: a soil without "
                     "strength holds nothing (the line would sink without end)")
    for i, line in enumerate(scene.lines):
        if not all(line.prescribed) or line.joints:
            raise _error(scene, f"lines[{i}]", f"line '{line.name}' has a free end or points on it: the "
                         "pretension path of [soil] moves one line between a fixed padeye and its fairlead "
                         "(networks in soil are not supported yet)")
        for j, segment in enumerate(line.segments):
            if segment.type.nominal_diameter is None:
                raise _error(scene, f"line_types.{segment.type.name}.nominal_diameter", "missing: [soil] needs "
                             f"the chain's bar diameter d_b of line type '{segment.type.name}' (used by "
                             f"lines[{i}].segments[{j}]): the soil's resistance scales with it (rui2025 Eq. 3)")
        depth = -float(scene.seabed.gap_only(line.anchor[None])[0])
        diameter = line.segments[0].type.diameter
        if depth < -diameter:
            raise _error(scene, f"lines[{i}].anchor", f"the anchor (padeye) lies {-depth:.6g} m above the "
                         f"seabed (more than the line's diameter, {diameter:g} m): with [soil] a padeye lies "
                         "on or below the seabed surface, where the laid line starts from it")
        if depth >= line.unstretched_length:
            raise _error(scene, f"lines[{i}].segments", f"the line's {line.unstretched_length:g} m do not reach "
                         f"from the padeye {depth:.6g} m below the seabed to its surface: nothing to lay")
    if scene.friction.model != "none":
        scene.notes.append("friction: [friction] does not act on lines in [soil]: the soil's tangential "
                           "resistance is their friction (docs/scene.md, [soil])")


def check_motion(scene):
    """The fairlead motion's peak speed and acceleration, and every line's peak chord strain
    over the whole motion (every extreme of it, whatever the duration)."""
    motion = scene.motion
    if motion.kind == "fixed":
        return
    key = {"harmonic": "motion.amplitude", "circular": "motion.radius", "table": "motion.file"}[motion.kind]
    _check_pace(scene, motion)
    for i, line in enumerate(scene.lines):
        if not _chord_set_by_motion(scene, line):
            continue
        strain, displacement, when = peak_chord_strain(line, motion)
        if strain > v.MAX_CHORD_STRAIN:
            chord = float(np.linalg.norm(line.fairlead + displacement - line.anchor))
            at = f" at t = {when:g} s" if when is not None else ""
            raise _error(scene, key, f"moves the fairlead of line '{line.name}' by "
                         f"[{', '.join(f'{d:.6g}' for d in displacement)}] m{at}, where the line would need "
                         f"an absurd strain of {100 * strain:.1f} % (more than {100 * v.MAX_CHORD_STRAIN:g} %) "
                         f"to reach it (anchor-fairlead distance {chord:.6g} m, unstretched length "
                         f"{line.unstretched_length:.6g} m)")


def _chord_set_by_motion(scene, line):
    """Whether [motion] alone sets ``line``'s chord: its fairlead end follows [motion] (the line's own
    fairlead, or a coupled point off any body) and its anchor end stays where the line has it (the
    line's own anchor, a fixed point, or a point of a fixed body). A line with an end on a free point
    or a free body, or moved by a coupled body's motion, has a chord that the run solves for or that
    [motion] does not give."""
    points, bodies = scene.points, scene.bodies
    anchor, fairlead = line.ends
    if fairlead is not None and (points[fairlead].body is not None or points[fairlead].kind != "coupled"):
        return False
    if anchor is None:
        return True
    point = points[anchor]
    return bodies[point.body].kind == "fixed" if point.body is not None else point.kind == "fixed"


def peak_chord_strain(line, motion):
    """The largest chord strain (float) ``line`` needs over the whole ``motion``, the fairlead
    displacement (3,) [m] where it does, and the table time [s] of it (None for other motions).

    The displacement is S(t) d(t) with the ramp S in [0, 1]: every displacement the motion
    reaches lies in the convex hull of 0 and its unramped extremes, and the distance from the
    anchor, a convex function, is largest at one of those: o +- A (harmonic), the point of the
    circle around o farthest from the anchor (circular), a sample of the table's motion (its rows
    and seven points between each two: ``table_samples``)."""
    chord = line.fairlead - line.anchor
    candidates, times = [np.zeros(3)], [None]
    offset = np.asarray(motion.offset, dtype=float)
    if motion.kind == "harmonic":
        amplitude = np.asarray(motion.amplitude, dtype=float)
        candidates += [offset + amplitude, offset - amplitude]
        times += [None, None]
    elif motion.kind == "circular":
        i, j = _PLANE_AXES[motion.plane]
        centre = chord + offset
        inside = np.array([centre[i], centre[j]])
        norm = float(np.linalg.norm(inside))
        direction = inside / norm if norm > 0 else np.array([1.0, 0.0])
        farthest = offset.copy()
        farthest[i] += motion.radius * direction[0]
        farthest[j] += motion.radius * direction[1]
        candidates.append(farthest)
        times.append(None)
    elif motion.kind == "table":
        at, positions = table_samples(motion)[:2]
        candidates += list(positions)
        times += [float(t) for t in at]
    strains = [float(np.linalg.norm(chord + d)) / line.unstretched_length - 1.0 for d in candidates]
    k = int(np.argmax(strains))
    return strains[k], candidates[k], times[k]


def table_samples(motion, pieces=8):
    """Times (m,) [s] and a table motion's positions, velocities and accelerations (m, 3) (its
    spline's or its straight lines', ``cablefem.model.motion.table_kinematics``) at its rows and
    ``pieces`` - 1 points between each two."""
    from cablefem.model.motion import table_kinematics

    times = np.asarray(motion.times, dtype=float)
    with np.errstate(over="ignore", invalid="ignore"):
        at = np.append((times[:-1, None] + np.diff(times)[:, None] * np.arange(pieces) / pieces).ravel(), times[-1])
        return (at, *table_kinematics(motion, at))


def _check_pace(scene, motion):
    """Refuse a fairlead motion faster than sound in water or accelerating beyond the sane limit
    (upper bounds of the ramped motion, within a factor of a few of its peaks)."""
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        if motion.kind == "table":
            _, positions, velocities, accelerations = table_samples(motion)
            speed, acceleration, reach = (float(np.max(np.linalg.norm(x, axis=1)))
                                          for x in (velocities, accelerations, positions))
            key = "motion.file"
        else:
            size = float(np.linalg.norm(motion.amplitude)) if motion.kind == "harmonic" else motion.radius
            omega = 2.0 * math.pi / motion.period if motion.period > 0 else math.inf
            speed, acceleration = size * omega, size * omega * omega
            reach, key = float(np.linalg.norm(motion.offset)) + size, "motion.period"
        ramp_speed = ramp_acceleration = 0.0
        if motion.ramp > 0.0:
            ramp_speed = _RAMP_SPEED / motion.ramp * reach
            ramp_acceleration = 2 * _RAMP_SPEED / motion.ramp * speed + _RAMP_ACCELERATION / motion.ramp ** 2 * reach
    for value, ramped, quantity in ((speed, ramp_speed, "speed"), (acceleration, ramp_acceleration, "acceleration")):
        bound, unit, why = v.LIMITS[quantity]
        total = value + ramped
        if not total <= bound:
            raise _error(scene, "motion.ramp" if ramped > value else key,
                         f"the fairlead's peak {quantity} would reach {total:.3g} {unit}, beyond the sane "
                         f"limit of {bound:g} {unit} ({why})")
