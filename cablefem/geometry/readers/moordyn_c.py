"""MoorDyn-C ``SeafloorFile`` bathymetry grid (housner2022 Sec. 2.1).

Layout, as MoorDyn-C's ``Seafloor::setup`` reads it::

    nx ny
    x_1 x_2 ... x_nx
    y_1 y_2 ... y_ny
    x y z          (one row per grid node, any order)

with z the seabed *elevation* [m], negative below the still water surface
(MoorDyn's ``getWaterDepth`` returns "a negative number"). MoorDyn-C snaps a
row whose x or y is not a tick to the tick below, lets a later row overwrite an
earlier one and leaves missing nodes at z = 0; here each of those is an error
naming the file line, and every node must be given exactly once. Blank lines
are skipped.
"""

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry.grid import DepthGrid
from cablefem.geometry.readers import (MAX_COORDINATE, count, is_integer, match_axis, numbers, read_lines,
    strictly_increasing)


def matches(head):
    """Whether the first lines head (list of str) look like this layout: 'nx ny' integers first."""
    rows = [line.split() for line in head if line.strip()]
    return bool(rows) and len(rows[0]) == 2 and all(is_integer(t) for t in rows[0])


def read(path):
    """The DepthGrid of a MoorDyn-C seafloor file; InputError naming the line when malformed."""
    rows = [(n, line.split()) for n, line in enumerate(read_lines(path), 1) if line.strip()]
    if len(rows) < 4:
        raise InputError("expected 'nx ny', a line of x values, a line of y values and rows "
                         f"'x y z', found {len(rows)} non-blank lines", file=path)
    (line_n, sizes), (line_x, x_tokens), (line_y, y_tokens) = rows[:3]
    if len(sizes) != 2:
        raise InputError(f"expected 'nx ny', got {' '.join(sizes)!r}", key=f"line {line_n}")
    nx, ny = count(sizes[0], line_n, "nx"), count(sizes[1], line_n, "ny")
    axes = []
    for name, line, tokens, size in (("x", line_x, x_tokens, nx), ("y", line_y, y_tokens, ny)):
        if len(tokens) != size:
            raise InputError(f"expected n{name} = {size} {name} values, got {len(tokens)}",
                             key=f"line {line}")
        values = numbers(tokens, line, f"{name} values")
        strictly_increasing(values, line, name)
        axes.append(values)
    x, y = axes

    lines = np.array([n for n, _ in rows[3:]])
    for n, tokens in rows[3:]:
        if len(tokens) != 3:
            raise InputError(f"expected 3 values 'x y z', got {len(tokens)}", key=f"line {n}")
    try:  # fast path; the slow one finds the offending line
        tokens = [t for _, tokens in rows[3:] for t in tokens]
        table = np.array(tokens, dtype=float).reshape(-1, 3)
        joined = "".join(tokens)  # numpy, as float(), reads other scripts' digits and 1_000
        clean = (joined.isascii() and "_" not in joined and bool(np.all(np.isfinite(table)))
                 and bool(np.all(np.abs(table) <= MAX_COORDINATE)))
    except ValueError:
        clean = False
    if not clean:
        table = np.vstack([numbers(tokens, n, "row 'x y z'") for n, tokens in rows[3:]])

    ix, iy = match_axis(x, table[:, 0]), match_axis(y, table[:, 1])
    off = np.flatnonzero((ix < 0) | (iy < 0))
    if len(off):
        k = off[0]
        name, value, axis = ("x", table[k, 0], x) if ix[k] < 0 else ("y", table[k, 1], y)
        raise InputError(f"{name} = {value:g} is not on the grid (the {len(axis)} {name} values "
                         f"of line {line_x if name == 'x' else line_y} run from {axis[0]:g} to "
                         f"{axis[-1]:g})", key=f"line {lines[k]}")

    node = iy * nx + ix
    _, first = np.unique(node, return_index=True)
    repeated = np.setdiff1d(np.arange(len(node)), first)
    if len(repeated):
        k = repeated[0]
        earlier = np.flatnonzero(node == node[k])[0]
        raise InputError(f"node x = {table[k, 0]:g}, y = {table[k, 1]:g} is given twice, "
                         f"on lines {lines[earlier]} and {lines[k]}", key=f"line {lines[k]}")
    if len(node) < nx * ny:
        missing = np.setdiff1d(np.arange(nx * ny), node)[0]
        raise InputError(f"hole: no row for node x = {x[missing % nx]:g}, y = {y[missing // nx]:g} "
                         f"({nx * ny - len(node)} of {nx * ny} nodes missing)",
                         key="rows")

    z = np.empty(nx * ny)
    z[node] = table[:, 2]
    return DepthGrid(x, y, z.reshape(ny, nx))


def write(path, grid):
    """Write DepthGrid grid to path in this layout, every value to full precision."""
    nx, ny = len(grid.x), len(grid.y)
    vertices = grid.vertices
    with open(path, "w", encoding="utf-8") as f:
        f.write(f"{nx} {ny}\n")
        f.write(" ".join(f"{v:.17g}" for v in grid.x) + "\n")
        f.write(" ".join(f"{v:.17g}" for v in grid.y) + "\n")
        f.writelines(f"{a:.17g} {b:.17g} {c:.17g}\n" for a, b, c in vertices)
