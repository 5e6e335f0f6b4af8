"""From a search's cells to a path's points: exact ends, checked end legs, dense legs.

A search returns the cells of a path at its own resolution (a downsampled
block is a cell). The path starts and ends at the exact requested points, not
at their cells' centres, so the first and last legs are checked again from
those points (any-angle planners join them to far vertices); a leg that is not
clear goes through its cell's centre instead. A start or goal cell that the
search could use only because it was opened (a downsampled block with a refused
fine cell) gets no point but the exact end: the search leaves and enters such a
cell by a grid step only, like GridBased. Long legs are filled with evenly
spaced points so consecutive poses are never farther apart than GridBased's
(its longest step: from a corner of the start cell to a diagonal neighbour).
"""

from __future__ import annotations

import itertools
import math

from .traversal import Traversal

Point = tuple[float, float]
LONGEST_STEP = 1.5 * math.sqrt(2.0)  # in cells: GridBased's longest step, never filled


def path_points(leg: Traversal, cells: list[int], start: Point, goal: Point) -> list[Point]:
    """Points from ``start`` to ``goal`` along ``cells`` (found on ``leg``'s weights)."""
    centres = leg.to_world(cells)
    points = [start, *centres[1:-1], goal]
    opened = {c for c in (cells[0], cells[-1]) if leg.is_opened(c)}
    if cells[0] not in opened and not segment_clear(leg, start, points[1]):
        points.insert(1, centres[0])
    if cells[-1] not in opened and not segment_clear(leg, points[-2], goal):
        points.insert(len(points) - 1, centres[-1])
    return densify(points, leg, opened)


def densify(points: list[Point], leg: Traversal, skip: set[int]) -> list[Point]:
    """Fill legs longer than GridBased's longest step with points at most one cell
    apart (none inside the cells in ``skip``)."""
    res = leg.geometry.resolution
    out: list[Point] = [points[0]]
    for (px, py), (x, y) in itertools.pairwise(points):
        length = math.hypot(x - px, y - py)
        if length > LONGEST_STEP * res:
            pieces = math.ceil(length / res)
            for k in range(1, pieces):
                point = (px + (x - px) * k / pieces, py + (y - py) * k / pieces)
                cell = leg.geometry.world_to_cell(*point)
                if cell is None or leg.index(*cell) not in skip:
                    out.append(point)
        out.append((x, y))
    return out


def segment_clear(leg: Traversal, a: Point, b: Point) -> bool:
    """True if every cell of ``leg`` the segment a-b touches is passable (both cells
    beside a corner it passes exactly through, too): a float grid walk."""
    g = leg.geometry
    x0, y0 = (a[0] - g.origin_x) / g.resolution, (a[1] - g.origin_y) / g.resolution
    x1, y1 = (b[0] - g.origin_x) / g.resolution, (b[1] - g.origin_y) / g.resolution
    col, row = math.floor(x0), math.floor(y0)
    steps = abs(math.floor(x1) - col) + abs(math.floor(y1) - row)
    dx, dy = x1 - x0, y1 - y0
    col_step, row_step = (1 if dx > 0 else -1), (1 if dy > 0 else -1)
    t_col_step = abs(1.0 / dx) if dx else math.inf
    t_row_step = abs(1.0 / dy) if dy else math.inf
    t_col = ((col + 1 - x0) if dx > 0 else (x0 - col)) * t_col_step if dx else math.inf
    t_row = ((row + 1 - y0) if dy > 0 else (y0 - row)) * t_row_step if dy else math.inf
    if not _free(leg, col, row):
        return False
    while steps > 0:
        if math.isclose(t_col, t_row, rel_tol=1e-12, abs_tol=1e-12):
            if not (_free(leg, col + col_step, row) and _free(leg, col, row + row_step)):
                return False
            col, row, steps = col + col_step, row + row_step, steps - 2
            t_col, t_row = t_col + t_col_step, t_row + t_row_step
        elif t_col < t_row:
            col, steps, t_col = col + col_step, steps - 1, t_col + t_col_step
        else:
            row, steps, t_row = row + row_step, steps - 1, t_row + t_row_step
        if not _free(leg, col, row):
            return False
    return True


def _free(leg: Traversal, col: int, row: int) -> bool:
    if not (0 <= col < leg.geometry.width and 0 <= row < leg.geometry.height):
        return False
    return leg.weights[leg.index(col, row)] != math.inf
