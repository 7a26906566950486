"""What ``cablefem static`` writes besides each line's report: the network's points and bodies
(docs/outputs.md)."""

import numpy as np


def network_json(scene, reports, network=None):
    """The ``points`` and ``bodies`` fields of ``cablefem static --json`` (docs/outputs.md)."""
    from cablefem.statics.network import network_loads, point_positions

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
