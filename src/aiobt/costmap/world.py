"""A global costmap fed by the map, the robot's pose and its scans.

The planner plans on it (:mod:`aiobt_services.planner.state` adds its search
graph); the Foxglove bridge and the web view mirror the same grid.
"""

from __future__ import annotations

import logging
import math
from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass, field

from aiobt.geometry import XYYaw
from aiobt.msgs import LaserScan, OccupancyGrid, PoseStamped

from .costmap import Costmap
from .grid import CostGrid, GridGeometry
from .inflation import InflationParams
from .obstacle_layer import ObstacleParams, Scan

log = logging.getLogger("aiobt.costmap.world")

MAP_FRAMES = ("", "map")
POSES_KEPT = 32  # the last poses, by stamp: a scan is marked from the one taken with it


def nearest(poses: Iterable[PoseStamped], stamp: float) -> PoseStamped | None:
    """Of ``poses`` (newest first), the one stamped nearest ``stamp``; stops at the first
    stamped at or before it (older ones are farther). Read lazily: a reader of kept
    payloads decodes only as far as this goes."""
    best: PoseStamped | None = None
    for pose in poses:
        if best is None or abs(pose.header.stamp - stamp) < abs(best.header.stamp - stamp):
            best = pose
        if pose.header.stamp <= stamp:
            break
    return best


@dataclass(frozen=True, slots=True)
class WorldOptions:
    inflation: InflationParams = field(default_factory=InflationParams)
    obstacles: ObstacleParams = field(default_factory=ObstacleParams)
    # robot s between folded scans (Nav2's global costmap: update_frequency 1 Hz, the newest
    # observation only); newer ones wait, replaced by the next, until one is due
    scan_period: float = 1.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.scan_period) and self.scan_period >= 0.0):
            raise ValueError(f"scan_period must be finite and >= 0, got {self.scan_period!r}")


class FedCostmap:
    """Latest map, robot pose and scans folded into a :class:`Costmap`.

    Scans are coalesced, never queued: the newest one waits and is folded in
    when it is ``scan_period`` robot seconds (default 1: Nav2's global costmap
    rate) newer (header stamps) than the last one folded, or at once when it is
    the first since :meth:`forget` (the streams attached again) or its stamp went
    back (the robot restarted); the costmap skips a scan equal to the last, from
    the same pose. Each fold also brings the traversal up to date, so a reader
    (a plan, a cost query) takes the costmap and traversal as they are, as Nav2's
    planner reads its global costmap, and does no costmap work of its own.
    Snapshots and the traversal are updated from the costmap's changed window,
    not rebuilt. Bad messages (wrong frame, rotated map origin) are logged and dropped.
    """

    __slots__ = ("_early", "_folded", "_grid", "_pending", "_poses", "_taken",
                 "costmap", "options", "pose", "pose_stamp")  # fmt: skip

    def __init__(self, options: WorldOptions | None = None) -> None:
        self.options = options or WorldOptions()
        self.costmap: Costmap | None = None
        self.pose: XYYaw | None = None
        self.pose_stamp = 0.0
        self._poses: deque[PoseStamped] = deque(maxlen=POSES_KEPT)
        self._pending: tuple[LaserScan, XYYaw] | None = None
        self._early: LaserScan | None = None  # a scan that came before its pose
        self._taken: LaserScan | None = None  # the last scan taken (folded or waiting)
        self._folded = -math.inf  # stamp of the newest scan folded in
        self._grid: tuple[int, CostGrid] | None = None

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
        self._map_changed()

    def on_pose(self, msg: PoseStamped) -> None:
        if msg.header.frame_id not in MAP_FRAMES:
            log.warning("pose: frame '%s' is not 'map'; ignored", msg.header.frame_id)
            return
        self.pose = (msg.x, msg.y, msg.yaw)
        self.pose_stamp = msg.header.stamp
        self._poses.append(msg)
        early = self._early
        if early is not None and self.pose_stamp >= early.header.stamp:
            self._early = None
            self._take(early, nearest(reversed(self._poses), early.header.stamp))

    def forget(self) -> None:
        """Drop the robot's pose and the waiting scan (the streams start again: a pose
        from before the planner stopped listening is not where the robot is)."""
        self.pose = None
        self._poses.clear()
        self._pending = None
        self._early = None
        self._taken = None
        self._folded = -math.inf  # the first scan after is folded as it comes

    def on_scan(self, msg: LaserScan) -> None:
        """Take a scan, marked from the pose stamped nearest it (the robot publishes
        both at one step; a busy loop can see newer poses first, and a pose 20 ms off
        marks a wall a cell off, a change that comes and goes). A scan that came before
        its pose waits for it (not the first after :meth:`forget`: a request waits on
        that one). The scan taken last (the same message handed again, as a request
        does with the newest) is not taken twice: it is folded or waiting already."""
        if self.costmap is None or self.pose is None or msg is self._taken:
            return
        if self.waits_for_pose(msg.header.stamp, self.pose_stamp):
            self._early = msg
            return
        self._take(msg, nearest(reversed(self._poses), msg.header.stamp))

    def scan_due(self, stamp: float) -> bool:
        """Whether a scan stamped ``stamp`` is folded as it is taken: the first since
        :meth:`forget`, one ``scan_period`` newer than the last folded, or one whose
        stamp went back (the robot restarted)."""
        return stamp - self._folded >= self.options.scan_period or stamp < self._folded

    @property
    def folded_since_forget(self) -> bool:
        return math.isfinite(self._folded)

    def waits_for_pose(self, scan_stamp: float, newest_pose_stamp: float) -> bool:
        """Whether a scan newer than the newest pose waits for its pose (not the first
        after :meth:`forget`: a request waits on that one)."""
        return newest_pose_stamp < scan_stamp and self.folded_since_forget

    def take_scan(self, msg: LaserScan, poses: Iterable[PoseStamped]) -> None:
        """Take ``msg`` marked from the one of ``poses`` (the robot's, newest first: a
        reader of its kept poses) stamped nearest it; no-op before a map."""
        if self.costmap is None or msg is self._taken:
            return
        self._take(msg, nearest(poses, msg.header.stamp))

    def _take(self, msg: LaserScan, pose: PoseStamped | None) -> None:
        if pose is None:
            return
        self._taken = msg
        stamp = msg.header.stamp
        self._pending = (msg, (pose.x, pose.y, pose.yaw))
        if self.scan_due(stamp):
            self._fold_pending()
            self._folded_scan()

    def _fold_pending(self) -> None:
        """Fold the waiting scan (if any) into the obstacle layer."""
        if self._pending is None or self.costmap is None:
            return
        (msg, pose), self._pending = self._pending, None
        self._folded = msg.header.stamp
        scan = Scan.create(
            pose,
            msg.angle_min,
            msg.angle_increment,
            msg.ranges_array(),
            msg.range_min,
            msg.range_max,
        )
        self.costmap.update_from_scan(scan)

    def snapshot(self) -> CostGrid | None:
        """The current master grid (shared, read-only: a new one when the costmap changed)."""
        if self.costmap is None:
            return None
        master = self.costmap.master
        version = self.costmap.version
        if self._grid is None or self._grid[0] != version:
            self._grid = (version, CostGrid(self.costmap.geometry, master.copy()))
        return self._grid[1]

    def _map_changed(self) -> None:
        """Called after a new map is set: a subclass prepares what it derives from it."""

    def _folded_scan(self) -> None:
        """Called after a scan is folded in: a subclass brings what it derives up to date."""

    def layer(self, name: str) -> CostGrid:
        """The costs to check a path on: the master grid for "", or one layer's own
        by Nav2's default plugin names ("static_layer", "obstacle_layer"; the
        inflation layer has no costmap of its own, as in Nav2). LookupError
        without a map yet or for any other name."""
        grid = self.snapshot()
        if grid is None or self.costmap is None:
            raise LookupError("no map received yet on {ns}/map")
        if name == "":
            return grid
        own = {"static_layer": self.costmap.static, "obstacle_layer": self.costmap.obstacles}
        costs = own.get(name)
        if costs is None:
            raise LookupError(
                f"layer_name '{name}': no such layer with a costmap of its own "
                "(the global costmap's are static_layer and obstacle_layer)"
            )
        return CostGrid(self.costmap.geometry, costs.copy())

    def robot_xy(self) -> tuple[float, float] | None:
        return None if self.pose is None else (self.pose[0], self.pose[1])

    def require_pose(self) -> XYYaw:
        if self.pose is None or not all(math.isfinite(v) for v in self.pose):
            raise LookupError("no robot pose in 'map' received yet on {ns}/pose")
        return self.pose
