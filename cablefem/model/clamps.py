"""Clamped tangents at line ends on bodies (docs/scene.md, Bending): a clamp holds its direction in
the scene's frame, so it is refused where the body would turn it. A clamp that turns with its body
(R(t) d) and one whose moment enters a free body's balance are not built."""

import math

import numpy as np

from cablefem.errors import InputError
from cablefem.model.motion import body_motion


def check_no_free_body_clamps(lines, points, bodies, where=lambda key: key):
    """InputError, at the line's tangent key, if a clamped tangent ends one of ``lines`` (as written)
    at a point of a free body: the clamp's moment would not enter the body's balance."""
    for index, line in enumerate(lines):
        for end, name in enumerate(line.ends):
            body = None if name is None else bodies.get(points[name].body)
            if line.tangents[end] is not None and body is not None and body.kind == "free":
                raise InputError(f"a clamped tangent at point '{name}' of free body '{body.name}' is not built (the "
                                 "clamp's moment would not enter the body's balance): pin the end (leave the "
                                 "tangent out) or make the body coupled or fixed",
                                 key=where(f"lines[{index}].{('anchor', 'fairlead')[end]}_tangent"))


def check_clamps_do_not_turn(scene):
    """InputError if a clamped tangent ends a line at a point of a coupled body whose motion turns
    it during the run: the clamp would keep its direction in the scene's frame while the body turns
    (a clamp that turns with its body, R(t) d, is not built; in statics the body is at rest)."""
    times = np.linspace(0.0, scene.solver.duration, 2001)
    for line in scene.lines:
        for end, name in enumerate(line.ends):
            body = None if name is None else scene.bodies.get(scene.points[name].body)
            if line.tangents[end] is None or body is None or body.kind != "coupled" or body.motion is None:
                continue
            turn = float(np.max(np.abs(body_motion(body.motion, times)[0][:, 3:])))
            if turn > 0.0:
                raise InputError(f"line '{line.name}' is clamped (a tangent) at point '{name}' of body '{body.name}', "
                                 f"whose motion turns it (up to {math.degrees(turn):.3g} deg): a clamp that turns "
                                 "with its body is not built; pin the end (leave the tangent out) or give the body "
                                 "a motion without rotation", key=f"bodies.{body.name}.motion")
