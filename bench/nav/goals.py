"""Seeded random reachable goals in the office world and their grid optimum (pure, no bus).

The optimum of a leg is the length of the shortest 8-connected cell path from
the robot's cell to the goal's through cells the planner may put the robot's
centre on (cost below INSCRIBED on the planner's static costmap), found by the
planner's reference Dijkstra with unit weights: what any grid planner could at
best drive on this map.
"""

from __future__ import annotations

import math

import numpy as np

from aiobt.costmap import INSCRIBED, CostGrid
from aiobt_services.planner.reference import dijkstra
from bench.planner.plan_time import office, reachable

Cell = tuple[int, int]
GOAL_CLEARANCE_COST = 100  # goals well clear of walls (inflated cost below this)
MIN_LEG = 3.0  # m between consecutive goals (straight line)


def static_grid() -> CostGrid:
    """The planner's costmap of the office world before any scan."""
    return office()


def passable(grid: CostGrid) -> np.ndarray:
    return np.asarray(grid.costs < INSCRIBED)


def pick_goals(
    grid: CostGrid, start: tuple[float, float], count: int, seed: int
) -> list[tuple[float, float, float]]:
    """``count`` goals (x, y, yaw), each reachable from ``start`` and ``MIN_LEG`` from the last."""
    origin = grid.geometry.world_to_cell(*start)
    if origin is None:
        raise ValueError(f"start {start} is outside the map")
    clear = reachable(passable(grid), origin) & (grid.costs < GOAL_CLEARANCE_COST)
    rows, cols = np.nonzero(clear)
    rng = np.random.default_rng(seed)
    goals: list[tuple[float, float, float]] = []
    last = start
    while len(goals) < count:
        pick = int(rng.integers(len(rows)))
        x, y = grid.geometry.cell_to_world(int(cols[pick]), int(rows[pick]))
        if math.dist((x, y), last) >= MIN_LEG:
            yaw = float(rng.uniform(-math.pi, math.pi))
            goals.append((round(x, 3), round(y, 3), round(yaw, 3)))
            last = (x, y)
    return goals


class Optimum:
    """Shortest grid path lengths (m) on one costmap; the weights are built once."""

    def __init__(self, grid: CostGrid) -> None:
        self.geometry = grid.geometry
        free = passable(grid)
        self.weights: list[list[float]] = np.where(free, 1.0, math.inf).tolist()

    def length(self, a: tuple[float, float], b: tuple[float, float]) -> float:
        """Metres along the shortest 8-connected passable path (inf if none or off-map)."""
        cells = [self._nearest_passable(point) for point in (a, b)]
        if None in cells:
            return math.inf
        cost, _ = dijkstra(self.weights, cells[0], cells[1])  # type: ignore[arg-type]
        return cost * self.geometry.resolution

    def _nearest_passable(self, point: tuple[float, float]) -> Cell | None:
        """The cell of ``point``, or the nearest passable one within 3 cells (a robot
        stopped a little inside the inflated zone still starts from there)."""
        cell = self.geometry.world_to_cell(*point)
        if cell is None:
            return None
        col, row = cell
        ring = [(col + dc, row + dr) for dc in range(-3, 4) for dr in range(-3, 4)]
        ring.sort(key=lambda c: (c[0] - col) ** 2 + (c[1] - row) ** 2)
        height, width = len(self.weights), len(self.weights[0])
        for c, r in ring:
            if 0 <= c < width and 0 <= r < height and math.isfinite(self.weights[r][c]):
                return (c, r)
        return None
