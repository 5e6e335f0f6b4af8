"""Nav2's ``GoalIntentSearch``: which of the nearest graph nodes a pose can reach.

``sight_blocked``: the straight line from the pose to a node crosses a cell at or
over the inscribed cost (unknown cells do not block). ``reachable_first``: a
breadth-first search over the 8-connected cells not in collision, from the pose's
cell, up to ``max_iterations`` cells; the first candidate node's cell it reaches.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Sequence

from aiobt.costmap import INSCRIBED, NO_INFORMATION, CostGrid, line_cells

from .vectors import XY

NEIGHBOURS = ((-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (1, -1), (-1, 1), (1, 1))


def _blocks(cost: int) -> bool:
    return INSCRIBED <= cost != NO_INFORMATION


def sight_blocked(grid: CostGrid, start: XY, end: XY) -> bool | None:
    """Whether the line between the points is blocked; None if either is off the grid."""
    a, b = grid.geometry.world_to_cell(*start), grid.geometry.world_to_cell(*end)
    if a is None or b is None:
        return None
    cols, rows = line_cells(*a, *b)
    costs = grid.costs[rows, cols]
    return bool(((costs >= INSCRIBED) & (costs != NO_INFORMATION)).any())


def reachable_first(
    grid: CostGrid, start: XY, candidates: Sequence[XY], max_iterations: int
) -> int | None:
    """Index in ``candidates`` of the first one the search reaches, or None."""
    geometry = grid.geometry
    origin = geometry.world_to_cell(*start)
    targets: dict[tuple[int, int], int] = {}
    for index, xy in enumerate(candidates):
        cell = geometry.world_to_cell(*xy)
        if cell is not None:
            targets.setdefault(cell, index)
    if origin is None or not targets:
        return None
    queue, seen, iterations = deque([origin]), {origin}, 0
    while queue and iterations < max_iterations:
        iterations += 1
        col, row = queue.popleft()
        if (col, row) in targets:
            return targets[(col, row)]
        for dc, dr in NEIGHBOURS:
            cell = (col + dc, row + dr)
            if cell in seen or not geometry.contains_cell(*cell):
                continue
            seen.add(cell)
            if not _blocks(int(grid.costs[cell[1], cell[0]])):
                queue.append(cell)
    return None
