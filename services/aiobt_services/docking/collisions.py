"""What the docking controller checks its projected trajectory against (Nav2's
``controller.use_collision_detection``): a local costmap of its own, a rolling window
fed by the lidar at the window's update frequency (robot time), in ``map``.

Nav2's docking controller reads the local costmap the controller publishes; here the
server keeps the same kind of window (``aiobt.costmap.local``), fed from ``{ns}/scan``
with the robot's map pose. A dock lower than the lidar's plane is not in it.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable

import numpy as np

from aiobt.core.clock import Clock
from aiobt.costmap.checker import CollisionChecker
from aiobt.costmap.local import LocalCostmap
from aiobt.geometry import Pose2D
from aiobt.msgs import LaserScan

from .frames import RobotFrames

log = logging.getLogger("aiobt_services.docking.collisions")


class ScanCollisions:
    """``collides(pose)``: a pose in the robot's frame (``base_link``, now) on a lethal
    or inscribed cell of the window; unknown space is free (as Nav2's checker)."""

    def __init__(self, costmap: LocalCostmap, scan: Callable[[], LaserScan | None],
                 frames: RobotFrames, clock: Clock) -> None:  # fmt: skip
        self.costmap = costmap
        self.checker = CollisionChecker(costmap)
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
        """Any of ``poses`` (given in ``base_link``) on an obstacle."""
        robot = self._frames.robot("map")
        local = np.array([(p.x, p.y) for p in poses], dtype=np.float64)
        c, s = math.cos(robot.yaw), math.sin(robot.yaw)
        xy = np.column_stack((robot.x + c * local[:, 0] - s * local[:, 1],
                              robot.y + s * local[:, 0] + c * local[:, 1]))  # fmt: skip
        return bool(self.checker.lethal_mask(self.costmap.costs_at(xy)).any())
