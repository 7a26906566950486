"""Seabed output: any seabed as a triangle surface in a VTK .vtu file (DIR/seabed.vtu
of ``cablefem run``), through meshio, for ParaView and pyvista."""

import os
from pathlib import Path

import numpy as np

from cablefem.errors import InputError


def write_seabed_vtu(seabed, path, bounds=None):
    """Write seabed.surface(bounds) to path (.vtu) with point data normal (m, 3) and elevation (m,) [m].

    bounds ((xmin, xmax), (ymin, ymax)) [m] is the horizontal extent to draw:
    a plane needs it (else +-1000 m), a grid or mesh defaults to its own. The
    normal at a vertex is the seabed's projection direction d_P there. The
    file is written beside its final name and moved into place, so a failed
    write leaves no half file.
    """
    import meshio

    path = Path(path)
    if path.suffix.lower() != ".vtu":
        raise InputError(f"expected a .vtu file name, got {path.name!r}", key="path")
    points, triangles = seabed.surface(bounds)
    points = np.asarray(points, dtype=float)
    normal = np.asarray(seabed.project(points).direction, dtype=float)
    mesh = meshio.Mesh(points, [("triangle", np.asarray(triangles, dtype=np.int64))],
                       point_data={"normal": normal, "elevation": points[:, 2].copy()})
    partial = path.with_name(f".{path.name}.partial")
    try:
        meshio.write(partial, mesh, file_format="vtu")
        os.replace(partial, path)
    finally:
        if partial.exists():
            partial.unlink()
    return path
