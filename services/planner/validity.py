"""IsPathValid: is a path still clear on the current costmap (Nav2 planner_server)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from aiobt_services.costmap import NO_INFORMATION, CostGrid

from .planning import Pose2D


def closest_index(poses: Sequence[Pose2D], x: float, y: float) -> int:
    xy = np.array([(p[0], p[1]) for p in poses], dtype=np.float64)
    return int(np.argmin(np.hypot(xy[:, 0] - x, xy[:, 1] - y)))


def invalid_poses(
    grid: CostGrid,
    poses: Sequence[Pose2D],
    max_cost: int = 253,
    consider_unknown_as_obstacle: bool = False,
    robot: tuple[float, float] | None = None,
) -> list[int]:
    """Indices of poses whose cell cost is >= ``max_cost`` (unknown cells count only
    with ``consider_unknown_as_obstacle``; off-map or non-finite poses always).

    Like Nav2, the check looks ahead from the pose closest to the robot, so
    the part already driven does not invalidate the path.
    """
    if not poses:
        return []
    first = 0
    if robot is not None and all(math.isfinite(v) for v in robot):
        first = closest_index(poses, *robot)
    xy = np.array([(p[0], p[1]) for p in poses[first:]], dtype=np.float64)
    cols, rows, inside = grid.geometry.world_to_cells(xy[:, 0], xy[:, 1])
    costs = np.where(inside, grid.costs[rows, cols], NO_INFORMATION).astype(np.int64)
    unknown = costs == NO_INFORMATION
    bad = ~inside | ((costs >= max_cost) & ~unknown)
    if consider_unknown_as_obstacle:
        bad |= unknown
    return (np.flatnonzero(bad) + first).tolist()


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
