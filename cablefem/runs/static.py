"""What ``cablefem static`` writes besides each line's report: the network's points and bodies
(docs/outputs.md)."""

import numpy as np


def network_json(scene, reports, network=None):
    """The ``points`` and ``bodies`` fields of ``cablefem static --json`` (docs/outputs.md)."""
    poses = {} if network is None else network.poses
    ends = [((rep.anchor_force, rep.nodes[0]), (rep.fairlead_force, rep.nodes[-1])) for rep in reports]
    forces, bodies = network_loads(scene, ends, poses)
    positions = point_positions(scene, [rep.nodes for rep in reports])
    points = {name: {"position": positions[name].tolist(), "force": forces.get(name, np.zeros(3)).tolist()}
              for name in scene.points}
    out = {}
    for name, body in scene.bodies.items():
        pose = poses.get(name, np.concatenate([body.position, body.rotation]))
        force, moment = bodies[name]
        out[name] = {"kind": body.kind, "position": pose[:3].tolist(), "rotation_deg": np.degrees(pose[3:]).tolist(),
                     "force": force.tolist(), "moment": moment.tolist()}
    return {"points": points, "bodies": out}


def network_loads(scene, ends, poses=None):
    """What the strings do to the network's named points and bodies. ``ends``: per string, its
    ((anchor force, anchor position), (fairlead force, fairlead position)), the forces the string
    exerts there. Returns {point: force (3,)} (the string ends there, summed) and {body: (force
    (3,), moment (3,) about its reference point)} at ``poses`` {name: (6,)} (default: where
    [bodies] puts them)."""
    points = {}
    for line, pair in zip(scene.lines, ends):
        for name, (force, at) in zip(line.ends, pair):
            if name is not None:
                total, _ = points.get(name, (np.zeros(3), None))
                points[name] = (total + force, np.asarray(at, dtype=float))
    bodies = {}
    for name, body in scene.bodies.items():
        pose = (poses or {}).get(name, np.concatenate([body.position, body.rotation]))
        force, moment = np.zeros(3), np.zeros(3)
        for point, (F, at) in points.items():
            if scene.points[point].body == name:
                force += F
                moment += np.cross(at - pose[:3], F)
        bodies[name] = (force, moment)
    return {name: F for name, (F, _) in points.items()}, bodies


def point_positions(scene, lines_nodes):
    """Where each named point of ``scene`` is: at a string end, or at the vertex of its joint inside
    a string; ``lines_nodes``: per string, its vertex positions (n, 3), anchor first."""
    out = {}
    for line, nodes in zip(scene.lines, lines_nodes):
        for name, row in zip(line.ends, (0, -1)):
            if name is not None:
                out[name] = np.asarray(nodes[row], dtype=float)
        for vertex, (_, joint) in zip(line.joint_vertices(), line.joints):
            out.setdefault(joint.name, np.asarray(nodes[vertex], dtype=float))
    return out
