"""The followed object: a box walking a loop in the simulation, and the tracker on the
robot that detects it in the lidar.

:class:`FollowTarget` moves the box (a real obstacle: it blocks, bumps and shows in
the scan) ``speed`` m/s along its path each physics step; it waits while the robot
stands in its way. :meth:`FollowTarget.detect` is the tracker: from one scan, the
returns the simulation labels as the box's (as a labelled-point sensor does; only
beams that really hit it, with the lidar's noise and dropouts, none through a wall),
the box's centre estimated from those points in the robot's frame; nothing when
fewer than ``min_points`` beams hit it, while it hides, or as the tracker's own
dropout. It reads the scan as published (``{ns}/scan``). Its truth is only for
``{ns}/sim/target``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from aiobt.geometry import Pose2D
from aiobt.msgs import LaserScan

from .lidar import Rectangles, rectangle_distances
from .obstacles import ObstacleError, ObstacleSpec
from .sim import Simulation
from .target_path import LoopPath

LABEL_SLACK = 0.05  # m beyond 3 sigma of range noise a return still counts as the box's


@dataclass(slots=True, frozen=True)
class TrackerConfig:
    """The tracker: fewest returns for a detection, and how often it misses one."""

    min_points: int = 3
    dropout: float = 0.05

    def __post_init__(self) -> None:
        if self.min_points < 1 or not 0.0 <= self.dropout < 1.0:
            raise ValueError("tracker: min_points >= 1 and dropout within [0, 1) needed")


class FollowTarget:
    """The box ``oid`` on ``path``; :meth:`update` each step, :meth:`detect` per scan."""

    def __init__(
        self, sim: Simulation, oid: str, path: LoopPath, speed: float, size: float,
        height: float = 1.0, hold: float = 0.0, tracker: TrackerConfig | None = None,
    ) -> None:  # fmt: skip
        self.sim, self.id, self.path, self.speed, self.size = sim, oid, path, speed, size
        self.tracker = tracker or TrackerConfig()
        self.travelled = 0.0
        self.start_at = sim.time + hold
        self.hidden_until = -math.inf
        self._rng = np.random.default_rng(sim.config.noise.seed + 1)
        spec = ObstacleSpec(oid, "box", path.pose_at(0.0), size, size, height=height)
        sim.spawn(spec)

    @property
    def pose(self) -> Pose2D:
        return self.sim.obstacle_pose(self.id)

    def update(self) -> None:
        """Walk on by one step (from ``hold`` on), unless the robot is in the way."""
        if self.sim.time < self.start_at or self.id not in self.sim.obstacles:
            return
        ahead = self.travelled + self.speed * self.sim.config.dt
        try:
            self.sim.move(self.id, self.path.pose_at(ahead))
        except ObstacleError:
            return  # blocked (by the robot): it waits
        self.travelled = ahead

    def hide(self, seconds: float) -> None:
        self.hidden_until = self.sim.time + seconds

    @property
    def hidden(self) -> bool:
        return self.sim.time < self.hidden_until

    def detect(self, scan: LaserScan) -> Pose2D | None:
        """The box's centre in the robot's frame from ``scan`` (taken this step)."""
        if self.hidden or self._rng.uniform() < self.tracker.dropout:
            return None
        robot, box = self.sim.true_pose, self.pose
        ranges = np.asarray(scan.ranges, dtype=np.float64)
        bearings = scan.angle_min + scan.angle_increment * np.arange(ranges.size)
        ranges[(ranges < scan.range_min) | (ranges > scan.range_max)] = np.inf  # no return
        half = [0.5 * self.size]
        rect = Rectangles.from_centres([box.x], [box.y], half, half, box.yaw)
        headings = robot.yaw + bearings
        to_box = rectangle_distances(rect, robot.x, robot.y, np.cos(headings), np.sin(headings))
        with np.errstate(invalid="ignore"):
            slack = 3.0 * self.sim.config.lidar.noise + LABEL_SLACK
            labelled = np.isfinite(ranges) & (np.abs(ranges - to_box) < slack)
        if int(labelled.sum()) < self.tracker.min_points:
            return None
        r, a = ranges[labelled], bearings[labelled]
        cx, cy = float(np.mean(r * np.cos(a))), float(np.mean(r * np.sin(a)))
        bearing = math.atan2(cy, cx)
        depth = 0.5 * self.size  # the visible faces' points lie about this short of the centre
        return Pose2D(cx + depth * math.cos(bearing), cy + depth * math.sin(bearing), bearing)
