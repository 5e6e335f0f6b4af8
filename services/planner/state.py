"""The planner's world model: the global costmap fed by map, pose and scans."""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field

from aiobt.msgs import LaserScan, OccupancyGrid, PoseStamped
from aiobt_services.costmap import (
    CostGrid,
    Costmap,
    GridGeometry,
    InflationParams,
    ObstacleParams,
    Scan,
)

from .planning import Pose2D
from .traversal import SearchParams, Traversal

log = logging.getLogger("aiobt_services.planner.state")
MAP_FRAMES = ("", "map")


@dataclass(frozen=True, slots=True)
class CostmapOptions:
    inflation: InflationParams = field(default_factory=InflationParams)
    obstacles: ObstacleParams = field(default_factory=ObstacleParams)
    search: SearchParams = field(default_factory=lambda: SearchParams(downsample=2))


class GlobalCostmap:
    """Latest map, robot pose and scans folded into a :class:`Costmap`.

    Bad messages (wrong frame, rotated map origin) are logged and dropped.
    """

    __slots__ = ("_cache", "costmap", "options", "pose", "pose_stamp")

    def __init__(self, options: CostmapOptions | None = None) -> None:
        self.options = options or CostmapOptions()
        self.costmap: Costmap | None = None
        self.pose: Pose2D | None = None
        self.pose_stamp = 0.0
        self._cache: tuple[object, CostGrid, Traversal | None] | None = None

    def on_map(self, msg: OccupancyGrid) -> None:
        if msg.header.frame_id not in MAP_FRAMES:
            log.error("map: frame '%s' is not 'map'; ignored", msg.header.frame_id)
            return
        info = msg.info
        if abs(info.origin.yaw) > 1e-6:
            log.error("map: rotated origin (yaw %.3f) is not supported; ignored", info.origin.yaw)
            return
        geometry = GridGeometry(
            info.width, info.height, info.resolution, info.origin.position.x, info.origin.position.y
        )
        if self.costmap is None:
            self.costmap = Costmap(geometry, self.options.inflation, self.options.obstacles)
        self.costmap.set_static(msg.array, geometry)
        log.info("map: %dx%d cells at %.3f m", info.width, info.height, info.resolution)

    def on_pose(self, msg: PoseStamped) -> None:
        if msg.header.frame_id not in MAP_FRAMES:
            log.warning("pose: frame '%s' is not 'map'; ignored", msg.header.frame_id)
            return
        self.pose = (msg.x, msg.y, msg.yaw)
        self.pose_stamp = msg.header.stamp

    def on_scan(self, msg: LaserScan) -> None:
        if self.costmap is None or self.pose is None:
            return
        self.costmap.update_from_scan(
            Scan.create(
                self.pose,
                msg.angle_min,
                msg.angle_increment,
                msg.ranges_array(),
                msg.range_min,
                msg.range_max,
            )
        )

    def snapshot(self) -> CostGrid | None:
        """The current master grid (shared, read-only: rebuilt when a layer changes)."""
        if self.costmap is None:
            return None
        master = self.costmap.master
        if self._cache is None or self._cache[0] is not master:
            self._cache = (master, CostGrid(self.costmap.geometry, master.copy()), None)
        return self._cache[1]

    def traversal(self) -> Traversal | None:
        """Search weights for the current snapshot (built once per snapshot)."""
        grid = self.snapshot()
        if grid is None or self._cache is None:
            return None
        if self._cache[2] is None:
            self._cache = (self._cache[0], grid, Traversal(grid, self.options.search))
        return self._cache[2]

    def robot_xy(self) -> tuple[float, float] | None:
        return None if self.pose is None else (self.pose[0], self.pose[1])

    def require_pose(self) -> Pose2D:
        if self.pose is None or not all(math.isfinite(v) for v in self.pose):
            raise LookupError("no robot pose in 'map' received yet on {ns}/pose")
        return self.pose
