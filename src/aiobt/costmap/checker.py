"""Collision checking against a local costmap, behind a small typed Protocol.

Costs follow Nav2: free 0, inscribed 253, lethal 254, unknown 255. The robot
is treated as a circle whose radius the costmap's inflation already accounts
for, so a pose collides when the cost under its centre is inscribed or worse
(unknown counts as free unless ``allow_unknown`` is false).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from aiobt.geometry import FloatArray, Pose2D, Velocity, integrate_arc

from .grid import FREE, INSCRIBED, NO_INFORMATION


@runtime_checkable
class CostQuery(Protocol):
    """What the controller and behaviors need from a costmap."""

    @property
    def resolution(self) -> float:
        """Cell size in metres."""
        ...

    def costs_at(self, points: FloatArray) -> NDArray[np.uint8]:
        """Cost of the cell under each point (N, 2); outside the map: unknown."""
        ...


class GridCostmap:
    """A plain numpy cost grid (row = y, column = x) with an origin in metres."""

    __slots__ = ("_resolution", "costs", "origin")

    def __init__(
        self, costs: NDArray[np.uint8], resolution: float, origin: tuple[float, float]
    ) -> None:
        if not (math.isfinite(resolution) and resolution > 0.0):
            raise ValueError(f"GridCostmap resolution must be > 0, got {resolution!r}")
        self.costs = costs
        self._resolution = resolution
        self.origin = origin

    @classmethod
    def empty(
        cls, width_m: float, height_m: float, resolution: float, origin: tuple[float, float]
    ) -> GridCostmap:
        shape = (round(height_m / resolution), round(width_m / resolution))
        return cls(np.zeros(shape, dtype=np.uint8), resolution, origin)

    @property
    def resolution(self) -> float:
        return self._resolution

    def costs_at(self, points: FloatArray) -> NDArray[np.uint8]:
        cols = np.floor((points[:, 0] - self.origin[0]) / self._resolution).astype(np.int64)
        rows = np.floor((points[:, 1] - self.origin[1]) / self._resolution).astype(np.int64)
        height, width = self.costs.shape
        inside = (cols >= 0) & (cols < width) & (rows >= 0) & (rows < height)
        out = np.full(points.shape[0], NO_INFORMATION, dtype=np.uint8)
        out[inside] = self.costs[rows[inside], cols[inside]]
        return out

    def fill_box(self, x0: float, y0: float, x1: float, y1: float, cost: int) -> None:
        """Set every cell whose centre lies in the box to ``cost`` (test helper)."""
        res = self._resolution
        c0 = max(0, math.ceil((x0 - self.origin[0]) / res - 0.5))
        c1 = math.floor((x1 - self.origin[0]) / res - 0.5)
        r0 = max(0, math.ceil((y0 - self.origin[1]) / res - 0.5))
        r1 = math.floor((y1 - self.origin[1]) / res - 0.5)
        self.costs[r0 : r1 + 1, c0 : c1 + 1] = cost


@dataclass(slots=True, frozen=True)
class ArcCheck:
    """Outcome of projecting a command forward: where it first collides, if at all."""

    collides: bool
    time_to_collision: float
    max_cost: int


class CollisionChecker:
    """Projects commands forward on a costmap and reports the first collision."""

    __slots__ = ("allow_unknown", "costmap")

    def __init__(self, costmap: CostQuery, allow_unknown: bool = True) -> None:
        self.costmap = costmap
        self.allow_unknown = allow_unknown

    def lethal_mask(self, costs: NDArray[np.uint8]) -> NDArray[np.bool_]:
        unknown = costs == NO_INFORMATION
        blocked = (costs >= INSCRIBED) & ~unknown
        mask: NDArray[np.bool_] = blocked | (unknown & (not self.allow_unknown))
        return mask

    def pose_collides(self, pose: Pose2D) -> bool:
        return bool(self.lethal_mask(self.costmap.costs_at(np.array([[pose.x, pose.y]])))[0])

    def check_arc(
        self, pose: Pose2D, cmd: Velocity, horizon: float, max_distance: float = math.inf
    ) -> ArcCheck:
        """Project ``cmd`` for ``horizon`` s (and at most ``max_distance`` m)."""
        travel = min(abs(cmd.v) * horizon, max_distance)
        step_time = self._step_time(cmd, horizon)
        end_time = travel / abs(cmd.v) if abs(cmd.v) > 1e-9 else horizon
        times = np.arange(0.0, end_time + 1e-9, step_time)
        poses = integrate_arc(pose, cmd, times)
        costs = self.costmap.costs_at(poses[:, :2])
        blocked = self.lethal_mask(costs)
        known = costs[costs != NO_INFORMATION]
        max_cost = int(known.max()) if known.size else FREE
        if blocked.any():
            return ArcCheck(True, float(times[int(np.argmax(blocked))]), max_cost)
        return ArcCheck(False, math.inf, max_cost)

    def _step_time(self, cmd: Velocity, horizon: float) -> float:
        # one sample per half cell travelled, and at least ten samples per horizon
        speed = abs(cmd.v)
        per_cell = 0.5 * self.costmap.resolution / speed if speed > 1e-9 else horizon
        return max(1e-3, min(per_cell, horizon / 10.0))
