"""The inflated global costmap for Foxglove, mirrored in the bridge.

The planner serves costs at poses (``get_cost_global_costmap``) but publishes no
grid, so the bridge folds the same topics (``map``, ``pose``, ``scan``) into the
planner's own world model (:class:`aiobt.costmap.world.FedCostmap`,
Nav2's default inflation: 0.22 m inscribed, 0.55 m inflation radius) and hands
out its master grid every ``period`` seconds of robot time (scan stamps). A
planner run with other inflation flags plans on a differently inflated grid.
"""

from __future__ import annotations

import math

from aiobt.costmap import CostGrid
from aiobt.costmap.world import FedCostmap
from aiobt.msgs import LaserScan, OccupancyGrid, PoseStamped


class CostmapMirror:
    """``on_scan`` returns the inflated grid when ``period`` s of robot time passed."""

    def __init__(self, period: float = 1.0) -> None:
        if not (math.isfinite(period) and period > 0.0):
            raise ValueError(f"costmap period must be > 0 s, not {period!r}")
        self.period = period
        self.world = FedCostmap()
        self._last: float | None = None

    def on_map(self, msg: OccupancyGrid) -> None:
        self.world.on_map(msg)
        self._last = None  # a new map is shown at the next scan

    def on_pose(self, msg: PoseStamped) -> None:
        self.world.on_pose(msg)

    def on_scan(self, msg: LaserScan) -> CostGrid | None:
        """Only the scans at the period's pace are folded in: obstacles stay marked in
        between, as in the planner's grid; what a skipped scan alone saw is missed."""
        stamp = msg.header.stamp
        if self._last is not None and 0.0 <= stamp - self._last < self.period:
            return None
        self.world.on_scan(msg)
        grid = self.world.snapshot()
        if grid is not None and self.world.pose is not None:
            self._last = stamp
        return grid
