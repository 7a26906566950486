"""What a run writes of a network (issue 18; docs/outputs.md): the columns of tensions.csv and the
extremes of summary.json for its points and bodies (``NetworkRows``), and where its frames draw
them (``frame_marks``, ``body_reference``)."""

import numpy as np

from cablefem.model.network import rotation

#: a free body's pose columns in tensions.csv: its reference point [m] and angles [deg]
POSE = ("x", "y", "z", "roll_deg", "pitch_deg", "yaw_deg")

class NetworkRows:
    """The network's columns of tensions.csv and extremes of summary.json in a run: the force
    [N] of the strings that end at each named point (fx, fy, fz: the sum of those ends' forces)
    and each body's force and moment [N m] about its reference point where its motion puts it."""

    def __init__(self, scene):
        self.ends = {}  # point -> [(line index, 0 fairlead | 1 anchor)]
        for k, line in enumerate(scene.lines):
            for name, which in zip(line.ends, (1, 0)):
                if name is not None:
                    self.ends.setdefault(name, []).append((k, which))
        self.points = sorted(self.ends)
        self.bodies = {name: body for name, body in sorted(scene.bodies.items())
                       if any(scene.points[p].body == name for p in self.points)}
        self.locals = {name: [(p, scene.points[p].position) for p in self.points if scene.points[p].body == name]
                       for name in self.bodies}
        self.extremes = {**{f"point:{p}": {} for p in self.points}, **{f"body:{b}": {} for b in self.bodies}}
        self.free = [name for name, body in self.bodies.items() if body.kind == "free"]
        self.stepped = {}  # free body -> its ``RigidBody`` in the run (``follow``)

    def follow(self, groups):
        """Read the free bodies' poses from the ``RigidBody`` of the groups that step them."""
        for group in groups:
            for body in getattr(group, "bodies", ()):
                self.stepped[body.name] = body

    def columns(self):
        return ([f"point:{p}:{c}" for p in self.points for c in ("fx", "fy", "fz")] +
                [f"body:{b}:{c}" for b in self.bodies for c in ("fx", "fy", "fz", "mx", "my", "mz")] +
                [f"body:{b}:{c}" for b in self.free for c in POSE])

    def pose(self, name, times):
        """A body's displacement from its rest pose (len(times), 6): a coupled body's motion, a free
        body's pose as it was stepped, zero for a fixed one."""
        from cablefem.model.motion import body_motion

        body = self.bodies[name]
        if name in self.stepped:
            return np.array([self.stepped[name].pose_at(t) for t in times]) - np.concatenate(
                [body.position, body.rotation])
        if body.kind == "coupled" and body.motion is not None:
            return body_motion(body.motion, times)[0]
        return np.zeros((len(times), 6))

    def values(self, times, rows):
        """Per row (of ``rows``: per line (fairlead, anchor) forces) the network's values, with
        the extremes updated; (len(rows), len(columns)) floats."""
        times = np.asarray(times, dtype=float)
        force = {p: np.array([sum(row[k][which] for k, which in self.ends[p]) for row in rows]) for p in self.points}
        out = [force[p] for p in self.points]
        for name, body in self.bodies.items():
            R = rotation(body.rotation + self.pose(name, times)[:, 3:])
            total, moment = np.zeros((len(times), 3)), np.zeros((len(times), 3))
            for p, local in self.locals[name]:
                total += force[p]
                moment += np.cross(R @ local, force[p])
            out += [total, moment]
            self._update(f"body:{name}", times, {"force": total, "moment": moment})
        for name in self.free:
            pose = self.pose(name, times) + np.concatenate([self.bodies[name].position, self.bodies[name].rotation])
            out.append(np.hstack([pose[:, :3], np.degrees(pose[:, 3:])]))
        for p in self.points:
            self._update(f"point:{p}", times, {"force": force[p]})
        return np.hstack(out) if out else np.zeros((len(times), 0))

    def _update(self, key, times, series):
        entry = self.extremes[key]
        for name, values in series.items():
            size = np.linalg.norm(values, axis=1)
            k = int(np.argmax(size))
            if f"{name}_max" not in entry or size[k] > entry[f"{name}_max"]:
                entry[f"{name}_max"], entry[f"{name}_max_t"] = float(size[k]), float(times[k])


def frame_marks(scene):
    """Where a run's frames draw the network (``cablefem.io.vtk.polyline_mesh``): its named
    points as (line index, vertex index) and its bodies as (name, [(line index, vertex index)])
    of their points; a vertex k of a line is row k * order of its frame's points."""
    rows, points = {}, []
    for k, line in enumerate(scene.lines):
        last = sum(seg.elements for seg in line.segments)
        named = [(name, (0, last)[e]) for e, name in enumerate(line.ends) if name is not None]
        named += [(joint.name, vertex) for vertex, (_, joint) in zip(line.joint_vertices(), line.joints)
                  if joint.name in scene.points]
        for name, vertex in named:
            if name not in rows:
                rows[name] = (k, int(vertex) * line.order)
                points.append(rows[name])
    bodies = [(name, [rows[p] for p, point in scene.points.items() if point.body == name and p in rows])
              for name in sorted(scene.bodies)]
    return points, [(name, marks) for name, marks in bodies if marks]


def body_reference(body, t, stepped=None):
    """Where a body's reference point is at time t [m]: at rest, moved by its motion, or where the
    run stepped a free one (``stepped``: its ``RigidBody``)."""
    if stepped is not None:
        return stepped.pose_at(t)[:3].copy()
    if body.kind == "coupled" and body.motion is not None:
        from cablefem.model.motion import body_motion

        return body.position + body_motion(body.motion, t)[0][:3]
    return body.position.copy()
