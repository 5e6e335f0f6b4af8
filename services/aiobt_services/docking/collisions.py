"""What the docking controller checks its projected trajectory against (Nav2's
``controller.use_collision_detection``): the robot's footprint at each projected pose,
on a local costmap of the server's own, a rolling window fed by the lidar at the
window's update frequency (robot time), in ``map``.

As Nav2's ``CostmapTopicCollisionChecker``: a pose collides when the footprint
polygon's outline (``--footprint``; for a round robot Nav2's 16-point polygon of
``--robot-radius``) touches a lethal cell or leaves the window, or when there is no
costmap yet. Nav2's docking controller reads that costmap and footprint from the
controller's ``local_costmap/costmap_raw`` and ``local_costmap/published_footprint``;
aiobt's controller publishes neither, and its costmap is only updated during a
FollowPath goal, so the server keeps the same kind of window
(``aiobt.costmap.local``) from ``{ns}/scan``. A dock lower than the lidar's plane is
not in it.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence

import numpy as np

from aiobt.core.clock import Clock
from aiobt.costmap import LETHAL, CostGrid, footprints_cost
from aiobt.costmap.local import LocalCostmap
from aiobt.geometry import FloatArray, Pose2D
from aiobt.msgs import LaserScan

from .frames import RobotFrames

log = logging.getLogger("aiobt_services.docking.collisions")


def poses_in(frame: Pose2D, poses: Sequence[Pose2D]) -> FloatArray:
    """``poses`` given relative to ``frame`` as ``(n, 3)`` (x, y, yaw) in ``frame``'s parent."""
    local = np.array([(p.x, p.y, p.yaw) for p in poses], dtype=np.float64).reshape(-1, 3)
    c, s = np.cos(frame.yaw), np.sin(frame.yaw)
    out: FloatArray = np.column_stack((frame.x + c * local[:, 0] - s * local[:, 1],
                                       frame.y + s * local[:, 0] + c * local[:, 1],
                                       frame.yaw + local[:, 2]))  # fmt: skip
    return out


def footprint_collides(grid: CostGrid, robot: Pose2D, poses: Sequence[Pose2D],
                       footprint: FloatArray) -> bool:  # fmt: skip
    """Any of ``poses`` (in the robot's frame; the robot at ``robot`` in the grid's
    frame) with the ``footprint`` polygon's outline on a lethal cell or off the grid
    (Nav2's ``isCollisionFree`` false: ``footprintCost`` >= LETHAL_OBSTACLE)."""
    if not poses:
        return False
    return bool((footprints_cost(grid, poses_in(robot, poses), footprint) >= LETHAL).any())


class ScanCollisions:
    """``collides(poses)``: poses in the robot's frame (``base_link``, now) whose
    footprint touches an obstacle of the window."""

    def __init__(self, costmap: LocalCostmap, footprint: FloatArray,
                 scan: Callable[[], LaserScan | None], frames: RobotFrames,
                 clock: Clock) -> None:  # fmt: skip
        self.costmap = costmap
        self.footprint = footprint
        self._scan = scan
        self._frames = frames
        self._clock = clock
        self._updated = -float("inf")
        self._stamp = -float("inf")  # the newest scan taken in

    def refresh(self) -> None:
        """Take the newest scan in, once per update period of robot time."""
        now = self._clock.now()
        if now - self._updated < self.costmap.update_period:
            return
        scan = self._scan()
        if scan is None or scan.header.stamp <= self._stamp:
            return
        try:
            robot = self._frames.robot("map")
            self.costmap.add_scan(scan, robot)
        except (LookupError, ValueError) as exc:
            log.debug("scan not taken into the docking costmap: %s", exc)
            return
        self._updated, self._stamp = now, scan.header.stamp

    def collides(self, poses: list[Pose2D]) -> bool:
        """Any of ``poses`` (given in ``base_link``) on an obstacle; with no scan taken
        in yet, every pose (Nav2: "Costmap is not available")."""
        if self._stamp == -float("inf"):
            log.error("no costmap for the collision check yet: no scan taken in from {ns}/scan")
            return True
        robot = self._frames.robot("map")
        return footprint_collides(self.costmap.grid(), robot, poses, self.footprint)
