"""The oblique plane of verification/seabed_equivalence and its descriptions: an STL mesh,
MoorDyn-C and -F grids, x y z soundings, a MoorDyn file with a SeafloorFile, and one scene per
description and ``[seabed] simplify`` setting."""

import math
from pathlib import Path

import numpy as np

from cablefem.geometry import DepthGrid, Plane
from cablefem.geometry.planes import _grid_triangles

#: the plane: rises at SLOPE_DEG towards AZIMUTH_DEG (from +x), through the anchor
SLOPE_DEG, AZIMUTH_DEG = 10.0, 60.0
ANCHOR = (-595.0, 0.0, -150.0)
#: plan extent of the files [m]: the line and its downhill sag lie well inside
EXTENT = ((-800.0, 200.0), (-400.0, 400.0))
ELEMENTS = 40
#: Newton's relative residual for every solve of (a) (the scenes' default is 1e-8)
TOLERANCE = 1e-10

SCENE = """\
name = "{name}"

[line_types.chain]    # desire2023 Table 5 (cablefem.model.builtin.table5_chain)
diameter = 0.3539
mass = 835.4
EA = 3.15e9
damping = 0.001
Cd_normal = 2.5
Cd_tangential = 0.5
Ca_normal = 3.8
Ca_tangential = 0.0

[[lines]]
name = "line1"
anchor = [{ax!r}, {ay!r}, {az!r}]
fairlead = [0.0, 0.0, 0.0]
segments = [{{ type = "chain", length = 635.0, elements = {elements} }}]

[seabed]
{seabed}
stiffness = 3.0e5

[solver]
tolerance = {tolerance!r}
"""

MOORDYN = """\
--------------------- MoorDyn Input File ------------------------------------
The Table 5 chain on a 10 deg oblique slope given as a MoorDyn-C bathymetry grid
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam     Mass/m   EA       BA/-zeta   EI    Cd    Ca    CdAx                 CaAx
(name)     (m)      (kg/m)   (N)      (N-s/-)    (-)   (-)   (-)   (-)                  (-)
chain      0.3539   835.4    3.15e9   3.15e6     0.0   2.5   3.8   0.15915494309189535  0.0
---------------------- POINTS --------------------------------
ID     Attachment  X        Y     Z        M      V        CdA   CA
(-)    (-)         (m)      (m)   (m)      (kg)   (m^3)    (m^2) (-)
1      Fixed       {ax!r}   {ay!r}   {az!r}   0      0        0     0
2      Coupled     0.0      0.0   0.0      0      0        0     0
---------------------- LINES --------------------------------------
ID    LineType   AttachA  AttachB  UnstrLen  NumSegs  Outputs
(-)   (-)        (-)      (-)      (m)       (-)      (-)
1     chain      1        2        635.0     {elements}       -
---------------------- OPTIONS -----------------------------------------
{grid}   SeafloorFile
1025.0               WtrDnsty
9.81                 g
3.0e5                kBot
---------------------------------------------------------------------------
"""


def oblique_plane():
    """The reference seabed: a Plane through ANCHOR rising SLOPE_DEG towards AZIMUTH_DEG."""
    return Plane.from_slope(ANCHOR, math.radians(SLOPE_DEG), math.radians(AZIMUTH_DEG))


def _on_plane(plane, xy):
    """Points (n, 3) [m] of plane above xy (n, 2)."""
    return np.column_stack([xy, plane.elevation(xy)])


def write_seabed_files(folder, seed=3):
    """Write the plane as an STL mesh, MoorDyn-C and -F grids, x y z soundings and a MoorDyn
    input file with SeafloorFile into folder; {label: file name}."""
    import meshio

    from cablefem.geometry.readers import moordyn_c, moordyn_f

    folder = Path(folder)
    plane = oblique_plane()
    (x0, x1), (y0, y1) = EXTENT
    rng = np.random.default_rng(seed)
    # grid: 100 m cells
    x, y = np.linspace(x0, x1, 11), np.linspace(y0, y1, 9)
    gx, gy = np.meshgrid(x, y)
    grid = DepthGrid(x, y, plane.elevation(np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape))
    moordyn_c.write(folder / "grid_c.txt", grid)
    moordyn_f.write(folder / "grid_f.txt", grid)
    # mesh: the same nodes, interior ones jittered by up to 30 m, ASCII STL (full precision)
    xy = np.column_stack([gx.ravel(), gy.ravel()])
    inner = (xy[:, 0] > x0) & (xy[:, 0] < x1) & (xy[:, 1] > y0) & (xy[:, 1] < y1)
    xy[inner] += rng.uniform(-30.0, 30.0, (int(inner.sum()), 2))
    mesh = meshio.Mesh(_on_plane(plane, xy), [("triangle", _grid_triangles(len(x), len(y)))])
    mesh.write(folder / "slope.stl", binary=False)
    # soundings: 400 scattered points and the corners, Delaunay-triangulated by the reader
    xy = np.vstack([[[x0, y0], [x1, y0], [x0, y1], [x1, y1]],
                    np.column_stack([rng.uniform(x0, x1, 400), rng.uniform(y0, y1, 400)])])
    np.savetxt(folder / "soundings.xyz", _on_plane(plane, xy), fmt="%.17g",
               header="x y z [m]: a 10 deg plane, scattered")
    ax, ay, az = ANCHOR
    (folder / "mooring.dat").write_text(MOORDYN.format(ax=ax, ay=ay, az=az, elements=ELEMENTS,
                                                       grid="grid_c.txt"))
    return {"mesh (stl)": "slope.stl", "grid (MoorDyn-C)": "grid_c.txt",
            "grid (MoorDyn-F)": "grid_f.txt", "points (xyz)": "soundings.xyz",
            "MoorDyn SeafloorFile": "mooring.dat"}


def write_scenes(folder):
    """Write the seabed files and one scene per description and simplify setting into folder;
    [(label, simplify, scene file name)], the plane first."""
    folder = Path(folder)
    files = write_seabed_files(folder)
    ax, ay, az = ANCHOR

    def scene(name, seabed):
        text = SCENE.format(name=name, ax=ax, ay=ay, az=az, elements=ELEMENTS, seabed=seabed,
                            tolerance=TOLERANCE)
        (folder / f"{name}.toml").write_text(text)
        return f"{name}.toml"

    plane = f'kind = "plane"\npoint = [{ax!r}, {ay!r}, {az!r}]\nslope_deg = {SLOPE_DEG!r}\n' \
            f'azimuth_deg = {AZIMUTH_DEG!r}'
    scenes = [("plane", True, scene("plane", plane))]
    kinds = {"slope.stl": "mesh", "grid_c.txt": "grid", "grid_f.txt": "grid", "soundings.xyz": "points"}
    for label, file in files.items():
        stem = Path(file).stem
        if file == "mooring.dat":
            scenes.append((label, True, file))
            wrapper = f'[moordyn]\nfile = "{file}"\n[seabed]\nsimplify = false\n[solver]\n' \
                      f'tolerance = {TOLERANCE!r}\n'
            (folder / "mooring_general.toml").write_text(wrapper)
            scenes.append((label, False, "mooring_general.toml"))
            continue
        for on in (True, False):
            seabed = f'kind = "{kinds[file]}"\nfile = "{file}"\nsimplify = {str(on).lower()}'
            scenes.append((label, on, scene(f"{stem}_{'simplified' if on else 'general'}", seabed)))
    return scenes
