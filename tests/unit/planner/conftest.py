"""Small cost grids for planner tests."""

from __future__ import annotations

import numpy as np

from aiobt.costmap import LETHAL, CostGrid, Costmap, GridGeometry, InflationParams


def grid_from(costs: np.ndarray, resolution: float = 0.1) -> CostGrid:
    height, width = costs.shape
    return CostGrid(GridGeometry(width, height, resolution), costs.astype(np.uint8))


def room_with_wall(gap_row: int = 2) -> CostGrid:
    """20x20 free grid with a lethal wall at col 10, open only at ``gap_row``."""
    costs = np.zeros((20, 20), dtype=np.uint8)
    costs[:, 10] = LETHAL
    costs[gap_row, 10] = 0
    return grid_from(costs)


def corridor(width_m: float = 1.6, length_m: float = 4.0) -> CostGrid:
    """An inflated corridor along x (walls at y = 0 and y = width), 0.05 m cells."""
    res = 0.05
    rows, cols = round(width_m / res) + 1, round(length_m / res)
    occupancy = np.zeros((rows, cols), dtype=np.int8)
    occupancy[0, :] = 100
    occupancy[-1, :] = 100
    geometry = GridGeometry(cols, rows, res)
    costmap = Costmap.from_occupancy(occupancy, geometry, inflation=InflationParams(0.2, 1.0, 3.0))
    return costmap.snapshot()
