"""MoorDyn-F / MoorPy bathymetry grid (housner2022 Sec. 2.1; MoorPy ``readBathymetryFile``).

Layout::

    --- MoorDyn Bathymetry Input File ---     (a title line, any text)
    nGridX 4
    nGridY 3
              x_1   x_2   x_3   x_4
    y_1   d_11  d_12  d_13  d_14
    y_2   d_21  ...
    y_3   ...

one row per y value, with the water *depths* d [m] positive down (MoorPy's
``getDepthFromBathymetry`` returns "local seabed depth (positive down)"); the
seabed elevation is z = -d. MoorPy reads the first nGridX tokens of the x line
and trusts every row; here a row with a missing depth is a hole, a repeated y
a duplicate, and every count must be as declared. Blank lines after the title
are skipped.
"""

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry.grid import DepthGrid
from cablefem.geometry.readers import count, numbers, read_lines, strictly_increasing


def matches(head):
    """Whether the first lines head (list of str) look like this layout: 'nGridX n' second."""
    rows = [line.split() for line in head[1:] if line.strip()]
    return bool(rows) and len(rows[0]) >= 2 and rows[0][0].lower() == "ngridx"


def _size(row, name):
    """Grid size from a 'nGridX n' row (line number, tokens)."""
    line, tokens = row
    if len(tokens) < 2 or tokens[0].lower() != name.lower():
        raise InputError(f"expected '{name} <count>', got {' '.join(tokens)!r}", key=f"line {line}")
    return count(tokens[1], line, name)


def read(path):
    """The DepthGrid of a MoorDyn-F/MoorPy bathymetry file; InputError naming the line when malformed."""
    lines = read_lines(path)
    rows = [(n, line.split()) for n, line in enumerate(lines[1:], 2) if line.strip()]
    if len(rows) < 4:
        raise InputError("expected a title, 'nGridX n', 'nGridY n', a line of x values and rows "
                         f"'y depth ...', found {len(rows) + 1} lines", file=path)
    nx, ny = _size(rows[0], "nGridX"), _size(rows[1], "nGridY")
    line_x, x_tokens = rows[2]
    if len(x_tokens) != nx:
        raise InputError(f"expected nGridX = {nx} x values, got {len(x_tokens)}", key=f"line {line_x}")
    x = numbers(x_tokens, line_x, "x values")
    strictly_increasing(x, line_x, "x")

    data = rows[3:]
    if len(data) > ny:
        raise InputError(f"row {ny + 1} of depths, but nGridY = {ny}", key=f"line {data[ny][0]}")
    y = np.empty(len(data))
    depth = np.empty((len(data), nx))
    for k, (line, tokens) in enumerate(data):
        values = numbers(tokens, line, "row 'y depth ...'")
        y[k] = values[0]
        earlier = np.flatnonzero(y[:k] == y[k])
        if len(earlier):
            raise InputError(f"y = {y[k]:g} is given twice, on lines {data[earlier[0]][0]} and {line}",
                             key=f"line {line}")
        if k and y[k] < y[k - 1]:
            raise InputError(f"y values must increase strictly: y = {y[k]:g} follows "
                             f"y = {y[k - 1]:g} of line {data[k - 1][0]}", key=f"line {line}")
        if len(values) - 1 < nx:
            raise InputError(f"hole: no depth for x = {x[len(values) - 1]:g}, y = {y[k]:g} "
                             f"(the row has {len(values) - 1} of nGridX = {nx} depths)",
                             key=f"line {line}")
        if len(values) - 1 > nx:
            raise InputError(f"{len(values) - 1} depths, but nGridX = {nx}", key=f"line {line}")
        depth[k] = values[1:]
    if len(data) < ny:
        raise InputError(f"hole: {len(data)} rows of depths, but nGridY = {ny}",
                         key=f"line {rows[1][0]}")
    return DepthGrid(x, y, -depth)


def write(path, grid, title="--- MoorDyn Bathymetry Input File ---"):
    """Write DepthGrid grid to path in this layout (depths positive down), full precision."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(f"{title}\nnGridX {len(grid.x)}\nnGridY {len(grid.y)}\n")
        f.write("        " + " ".join(f"{v:.17g}" for v in grid.x) + "\n")
        for y, row in zip(grid.y, -grid.z):
            f.write(f"{y:.17g} " + " ".join(f"{d:.17g}" for d in row) + "\n")
