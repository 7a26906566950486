"""Scattered soundings: 'x y z' rows [m] Delaunay-triangulated in plan (desire2023 Sec. 2.2.2.2).

One point per row, separated by whitespace or commas; '#' starts a comment;
blank lines are skipped. The points are triangulated in (x, y) by
scipy.spatial.Delaunay (Qhull) into a ``TriangulatedSurface``. Errors name the
file and the row: a row that is not three numbers, a NaN, fewer than three
points, two points at the same (x, y), and points all on one line.
"""

from pathlib import Path

import numpy as np

from cablefem.errors import InputError
from cablefem.geometry.triangulated import TriangulatedSurface
from cablefem.geometry.readers import check_coordinates, parse_number


def parse(lines):
    """Points (n, 3) [m] and their 1-based line numbers (n,) from the text lines (list of str)."""
    points, numbers = [], []
    for number, line in enumerate(lines, start=1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        fields = text.replace(",", " ").split()
        if len(fields) != 3:
            raise InputError(f"expected three numbers 'x y z', got {len(fields)} fields: {text!r}",
                             key=f"line {number}")
        values = [parse_number(field) for field in fields]
        if None in values:
            raise InputError(f"expected three numbers 'x y z', got {text!r}", key=f"line {number}")
        if not np.all(np.isfinite(values)):
            raise InputError(f"not a finite number in {text!r}", key=f"line {number}")
        check_coordinates(values, f"line {number}", "x y z")
        points.append(values)
        numbers.append(number)
    return np.array(points, dtype=float).reshape(-1, 3), np.array(numbers, dtype=int)


def triangulate(points, numbers):
    """Delaunay triangles (k, 3) in plan of points (n, 3) [m] read from lines numbers (n,)."""
    from scipy.spatial import Delaunay, QhullError

    if len(points) < 3:
        raise InputError(f"need at least 3 points to make a seabed, got {len(points)}")
    xy = points[:, :2] - points[:, :2].mean(axis=0)  # centred: survey coordinates can be 1e6 m
    order = np.lexsort(xy.T[::-1])
    same = np.flatnonzero(np.all(xy[order[1:]] == xy[order[:-1]], axis=1))
    if len(same):
        a, b = sorted(order[same[0]:same[0] + 2])
        raise InputError(f"lines {numbers[a]} and {numbers[b]} give the same (x, y) = "
                         f"{points[a, :2].tolist()}: a seabed has one depth per position")
    singular = np.linalg.svd(xy, compute_uv=False)
    if singular[1] <= 1e-10 * singular[0]:
        raise InputError(f"all {len(points)} points lie on one line in plan: they span no surface")
    try:
        delaunay = Delaunay(xy)
    except QhullError as error:
        raise InputError(f"cannot triangulate the points: {str(error).strip().splitlines()[0]}") from None
    if len(delaunay.coplanar):
        left = delaunay.coplanar[0, 0]
        raise InputError(f"line {numbers[left]}: the point {points[left, :2].tolist()} is too close "
                         "to another to be triangulated")
    simplices = delaunay.simplices
    corner = xy[simplices]
    u, w = corner[:, 1] - corner[:, 0], corner[:, 2] - corner[:, 0]
    area = np.abs(u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0])
    # Qhull may leave zero-area slivers along a straight stretch of the hull
    return simplices[area > 1e-12 * np.ptp(xy, axis=0).max() ** 2]


def read(path):
    """The TriangulatedSurface through the soundings in file path (str or Path) [m]."""
    file = str(path)
    try:
        lines = Path(path).read_text(encoding="utf-8").splitlines()
    except FileNotFoundError:
        raise InputError("no such file", file=file) from None
    except UnicodeDecodeError:
        raise InputError("not a text file of 'x y z' rows (not UTF-8)", file=file) from None
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror or error}", file=file) from None
    try:
        points, numbers = parse(lines)
        return TriangulatedSurface(points, triangulate(points, numbers))
    except InputError as error:
        raise error.within(file=file) from None
