"""IsPathValid: is a path still clear on the current costmap (Nav2 planner_server)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from aiobt.costmap import INSCRIBED, LETHAL, NO_INFORMATION, CostGrid, footprint_cost
from aiobt.costmap.grid import FloatArray
from aiobt.geometry import XYYaw


def closest_index(poses: Sequence[XYYaw], x: float, y: float) -> int:
    xy = np.array([(p[0], p[1]) for p in poses], dtype=np.float64)
    return int(np.argmin(np.hypot(xy[:, 0] - x, xy[:, 1] - y)))


def invalid_poses(
    grid: CostGrid,
    poses: Sequence[XYYaw],
    max_cost: int = 253,
    consider_unknown_as_obstacle: bool = False,
    robot: tuple[float, float] | None = None,
    *,
    stop_at_first_collision: bool = False,
    max_lookahead_distance: float = -1.0,
    footprint: FloatArray | None = None,
) -> list[int]:
    """Indices of poses in collision, as Nav2's IsPathValid service finds them.

    - checked from the pose closest to the robot (the part already driven does
      not invalidate the path), for ``max_lookahead_distance`` m along the path
      from there (all of it if < 0), up to the first collision if asked;
    - the robot as a point on the inflated costs (a round robot), or the
      ``footprint`` polygon's outline at each pose's heading;
    - a pose collides at a lethal cost or at ``max_cost`` and above (a point
      also at the inscribed cost, and off the map); unknown counts only with
      ``consider_unknown_as_obstacle``.
    """
    if not poses:
        return []
    first = 0
    if robot is not None and all(math.isfinite(v) for v in robot):
        first = closest_index(poses, *robot)
    xy = np.array([(p[0], p[1]) for p in poses[first:]], dtype=np.float64)
    if max_lookahead_distance >= 0:
        along = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(xy, axis=0).T))))
        xy = xy[: max(1, int(np.searchsorted(along, max_lookahead_distance, side="right")))]
    if footprint is None:
        cols, rows, inside = grid.geometry.world_to_cells(xy[:, 0], xy[:, 1])
        costs = np.where(inside, grid.costs[rows, cols], LETHAL).astype(np.int64)
    else:
        yaws = [p[2] for p in poses[first : first + len(xy)]]
        costs = np.array(
            [
                footprint_cost(grid, x, y, yaw, footprint)
                for (x, y), yaw in zip(xy, yaws, strict=True)
            ],
            dtype=np.int64,
        )
    unknown = costs == NO_INFORMATION
    bad = (costs >= max_cost) | (costs == LETHAL)
    if footprint is None:
        bad |= costs == INSCRIBED
    bad = (bad & ~unknown) | (unknown & consider_unknown_as_obstacle)
    found = np.flatnonzero(bad) + first
    return found[:1].tolist() if stop_at_first_collision else found.tolist()


def pose_costs(grid: CostGrid, xy: Sequence[tuple[float, float]]) -> tuple[list[float], bool]:
    """Nav2's GetCosts: the cost of the cell under each position (the robot is round,
    so the inflation layer's cost there is its footprint's); a position off the map
    costs NO_INFORMATION and makes the answer unsuccessful."""
    if not xy:
        return [], True
    points = np.array(xy, dtype=np.float64)
    cols, rows, inside = grid.geometry.world_to_cells(points[:, 0], points[:, 1])
    costs = np.where(inside, grid.costs[rows, cols], NO_INFORMATION).astype(np.float64)
    return costs.tolist(), bool(inside.all())
