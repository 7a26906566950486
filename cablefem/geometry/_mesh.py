"""Checks and topology of a triangulated seabed: orientation, adjacency, vertex normals.

A seabed is a height field z(x, y): faces are wound so that their normals
point up (either input winding gives the same surface), and a vertical face,
an edge of more than two faces or two neighbours that overlap in plan (the
surface folds over) is an ``InputError``. Vertex normals are the
angle-weighted mean of the adjacent face normals (Thürmer & Wüthrich 1998),
the "mean of the adjacent triangle normals" of desire2023 Sec. 2.2.2.2 made
independent of how a face is split into coplanar pieces.
"""

import numpy as np

from cablefem.errors import InputError

#: a face whose unit normal has |n_z| at most this is vertical, not a seabed
VERTICAL_TOLERANCE = 1e-9


def face_geometry(vertices, triangles):
    """Area vectors (k, 3) [m^2, twice the area] and the longest edge (k,) [m] of the triangles."""
    p = vertices[triangles]
    area = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    edges = np.linalg.norm(p - np.roll(p, 1, axis=1), axis=2)
    return area, edges.max(axis=1)


def checked_arrays(vertices, triangles):
    """Float vertices (m, 3) and int triangles (k, 3), or an InputError saying what is wrong."""
    vertices = np.asarray(vertices, dtype=float)
    triangles = np.asarray(triangles)
    if vertices.ndim != 2 or vertices.shape[1] != 3 or len(vertices) < 3:
        raise InputError(f"vertices must have shape (m >= 3, 3), got {vertices.shape}", key="vertices")
    bad = np.flatnonzero(~np.isfinite(vertices).all(axis=1))
    if len(bad):
        raise InputError(f"vertex {bad[0]} has a non-finite coordinate {vertices[bad[0]].tolist()} "
                         f"({len(bad)} such vertices)", key="vertices")
    if triangles.ndim != 2 or triangles.shape[1] != 3 or len(triangles) == 0:
        raise InputError(f"triangles must have shape (k >= 1, 3), got {triangles.shape}", key="triangles")
    if not np.issubdtype(triangles.dtype, np.integer):
        raise InputError("triangles must hold integer vertex indices", key="triangles")
    triangles = triangles.astype(np.int64)
    if triangles.min() < 0 or triangles.max() >= len(vertices):
        raise InputError(f"vertex indices must lie in [0, {len(vertices) - 1}], got "
                         f"[{triangles.min()}, {triangles.max()}]", key="triangles")
    return vertices, triangles


def orient_up(vertices, triangles):
    """Triangles (k, 3) wound so that their normals point up, and their unit normals (k, 3)."""
    area, longest = face_geometry(vertices, triangles)
    double_area = np.linalg.norm(area, axis=1)
    bad = np.flatnonzero(double_area <= 1e-12 * longest ** 2)
    if len(bad):
        raise InputError(f"triangle {bad[0]} (vertices {triangles[bad[0]].tolist()}) has zero area "
                         f"({len(bad)} degenerate triangles)", key="triangles")
    normal = area / double_area[:, None]
    bad = np.flatnonzero(np.abs(normal[:, 2]) <= VERTICAL_TOLERANCE)
    if len(bad):
        raise InputError(f"triangle {bad[0]} is vertical ({len(bad)} such): a seabed must be a "
                         "surface z(x, y), not a wall", key="triangles")
    down = normal[:, 2] < 0.0
    triangles = triangles.copy()
    triangles[down] = triangles[down][:, [0, 2, 1]]
    normal[down] *= -1.0
    return triangles, normal


def neighbours(triangles, n_vertices):
    """Neighbour (k, 3) across the edge opposite each corner, -1 on the boundary.

    Raises InputError for an edge of more than two faces (non-manifold) and for
    two up-oriented neighbours that run along their edge the same way (folded over).
    """
    k = len(triangles)
    tail = triangles[:, [1, 2, 0]].ravel()  # edge opposite corner i runs corner i+1 -> i+2
    head = triangles[:, [2, 0, 1]].ravel()
    key = np.minimum(tail, head) * n_vertices + np.maximum(tail, head)
    order = np.argsort(key, kind="stable")
    sorted_key = key[order]
    start = np.flatnonzero(np.r_[True, sorted_key[1:] != sorted_key[:-1]])
    count = np.diff(np.r_[start, len(key)])
    if np.any(count > 2):
        g = start[np.argmax(count > 2)]
        edge = order[g]
        raise InputError(f"edge {sorted([int(tail[edge]), int(head[edge])])} is shared by "
                         f"{count.max()} triangles: the surface is not a manifold", key="triangles")
    pairs = start[count == 2]
    first, second = order[pairs], order[pairs + 1]
    folded = tail[first] == tail[second]
    if np.any(folded):
        f = first[np.argmax(folded)]
        raise InputError(f"triangles {f // 3} and {second[np.argmax(folded)] // 3} overlap in plan "
                         f"across edge {[int(tail[f]), int(head[f])]}: the surface folds over", key="triangles")
    neighbour = np.full(3 * k, -1, dtype=np.int64)
    neighbour[first] = second // 3
    neighbour[second] = first // 3
    return neighbour.reshape(k, 3)


def vertex_normals(vertices, triangles, face_normal):
    """Angle-weighted mean (m, 3) of the unit face normals (k, 3) around each vertex, unit length."""
    p = vertices[triangles]
    normals = np.zeros((len(vertices), 3))
    for corner in range(3):
        u = p[:, (corner + 1) % 3] - p[:, corner]
        w = p[:, (corner + 2) % 3] - p[:, corner]
        angle = np.arctan2(np.linalg.norm(np.cross(u, w), axis=1), np.einsum("ka,ka->k", u, w))
        for axis in range(3):
            normals[:, axis] += np.bincount(triangles[:, corner], weights=angle * face_normal[:, axis],
                                            minlength=len(vertices))
    length = np.linalg.norm(normals, axis=1)
    unused = length == 0.0
    normals[unused] = (0.0, 0.0, 1.0)
    length[unused] = 1.0
    return normals / length[:, None]
