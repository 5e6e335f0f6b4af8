"""Cost look-ups for points, segments and footprints on a :class:`CostGrid`.

Anything outside the grid counts as LETHAL (Nav2's FootprintCollisionChecker).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from .grid import LETHAL, CostGrid, FloatArray, IntArray


def point_cost(grid: CostGrid, x: float, y: float) -> int:
    cell = grid.geometry.world_to_cell(x, y)
    if cell is None:
        return LETHAL
    return int(grid.costs[cell[1], cell[0]])


def points_cost(grid: CostGrid, xs: npt.ArrayLike, ys: npt.ArrayLike) -> IntArray:
    """Vectorised :func:`point_cost`."""
    cols, rows, ok = grid.geometry.world_to_cells(np.asarray(xs), np.asarray(ys))
    costs: IntArray = np.where(ok, grid.costs[rows, cols], LETHAL).astype(np.intp)
    return costs


def line_cells(col0: int, row0: int, col1: int, row1: int) -> tuple[IntArray, IntArray]:
    """Cells of the digital line between two cells (both ends included), DDA/Bresenham."""
    steps = max(abs(col1 - col0), abs(row1 - row0)) + 1
    cols = np.rint(np.linspace(col0, col1, steps)).astype(np.intp)
    rows = np.rint(np.linspace(row0, row1, steps)).astype(np.intp)
    return cols, rows


def segment_points(x0: float, y0: float, x1: float, y1: float, spacing: float) -> FloatArray:
    """``(n, 2)`` points from (x0, y0) to (x1, y1) at most ``spacing`` apart, ends included."""
    length = math.hypot(x1 - x0, y1 - y0)
    count = max(2, math.ceil(length / spacing) + 1)
    t = np.linspace(0.0, 1.0, count)
    return np.column_stack((x0 + (x1 - x0) * t, y0 + (y1 - y0) * t))


def segment_max_cost(grid: CostGrid, x0: float, y0: float, x1: float, y1: float) -> int:
    """Highest cost of any cell the segment passes through (LETHAL if it leaves the grid)."""
    points = segment_points(x0, y0, x1, y1, grid.geometry.resolution * 0.5)
    return int(points_cost(grid, points[:, 0], points[:, 1]).max())


def segment_is_free(
    grid: CostGrid, x0: float, y0: float, x1: float, y1: float, max_cost: int = LETHAL - 1
) -> bool:
    """True if no cell along the segment costs more than ``max_cost``."""
    return segment_max_cost(grid, x0, y0, x1, y1) <= max_cost


def oriented_footprint(x: float, y: float, yaw: float, footprint: npt.ArrayLike) -> FloatArray:
    """Footprint vertices ``(k, 2)`` in the robot frame, moved to pose (x, y, yaw)."""
    vertices = np.asarray(footprint, dtype=np.float64).reshape(-1, 2)
    c, s = math.cos(yaw), math.sin(yaw)
    rotated = vertices @ np.array([[c, s], [-s, c]])
    result: FloatArray = rotated + np.array([x, y])
    return result


def footprint_cost(grid: CostGrid, x: float, y: float, yaw: float, footprint: npt.ArrayLike) -> int:
    """Nav2 ``footprintCost``: the highest cost on the footprint's outline, LETHAL
    if any cell of it is (even where others are unknown, which is higher).

    With fewer than 3 vertices the robot is a point (circular robots rely on
    the inflation layer's inscribed cost).
    """
    vertices = np.asarray(footprint, dtype=np.float64).reshape(-1, 2)
    if len(vertices) < 3:
        return point_cost(grid, x, y)
    return int(footprints_cost(grid, np.array([[x, y, yaw]]), vertices)[0])


def outline_points(footprint: npt.ArrayLike, spacing: float) -> FloatArray:
    """``(m, 2)`` points along the closed outline of a polygon, each edge sampled as
    :func:`segment_points` samples it (ends included), all edges at once."""
    a = np.asarray(footprint, dtype=np.float64).reshape(-1, 2)
    b = np.roll(a, -1, axis=0)
    lengths = np.hypot(*(b - a).T)
    counts = np.maximum(2, np.ceil(lengths / spacing).astype(np.intp) + 1)
    edge = np.repeat(np.arange(len(a)), counts)
    along = np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts, counts)
    t = along / (counts[edge] - 1)
    points: FloatArray = a[edge] + (b - a)[edge] * t[:, None]
    return points


def footprints_cost(grid: CostGrid, poses: npt.ArrayLike, footprint: npt.ArrayLike) -> IntArray:
    """:func:`footprint_cost` of a polygon (at least 3 vertices) at each of ``poses``
    ``(n, 3)`` (x, y, yaw), vectorised: the outline is sampled once in the robot's frame
    and moved to every pose (turning it keeps the spacing)."""
    vertices = np.asarray(footprint, dtype=np.float64).reshape(-1, 2)
    if len(vertices) < 3:
        raise ValueError(f"a footprint polygon needs at least 3 vertices, got {len(vertices)}")
    at = np.asarray(poses, dtype=np.float64).reshape(-1, 3)
    outline = outline_points(vertices, grid.geometry.resolution * 0.5)
    c, s = np.cos(at[:, 2])[:, None], np.sin(at[:, 2])[:, None]
    xs = at[:, 0:1] + c * outline[:, 0] - s * outline[:, 1]
    ys = at[:, 1:2] + s * outline[:, 0] + c * outline[:, 1]
    costs = points_cost(grid, xs, ys)  # (n, m)
    lethal = (costs == LETHAL).any(axis=1)
    result: IntArray = np.where(lethal, LETHAL, costs.max(axis=1)).astype(np.intp)
    return result  # lethal beats unknown
