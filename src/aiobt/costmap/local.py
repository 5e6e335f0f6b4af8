"""The local costmap: the costmap library's rolling window, fed by lidar, as a CostQuery.

The window lives in the frame of the poses it is fed with
(:class:`aiobt.robot.tracker.RobotTracker`'s ``costmap_frame``). The controller's is
in ``map`` (the robot pose from ``{ns}/pose``), so paths from the planner are
checked without a transform; :class:`FrameShift` serves a path given in ``odom``
by moving query points through odom -> map. The behaviors' is in ``odom`` (Nav2's
``local_frame``), so a relocalization does not move it.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from aiobt.geometry import FloatArray, Pose2D
from aiobt.msgs import LaserScan

from .checker import CostQuery
from .grid import NO_INFORMATION, CostGrid
from .inflation import InflationParams
from .obstacle_layer import ObstacleParams, Scan
from .rolling import RollingCostmap

log = logging.getLogger("aiobt.costmap.local")


@dataclass(slots=True, frozen=True)
class LocalCostmapParams:
    size: float = 5.0
    resolution: float = 0.05
    robot_radius: float = 0.22
    inflation_radius: float = 0.55
    cost_scaling_factor: float = 3.0
    obstacle_max_range: float = 2.5
    raytrace_max_range: float = 3.0
    update_frequency: float = 5.0  # Hz of robot time (Nav2's local costmap default)

    def __post_init__(self) -> None:
        if not (math.isfinite(self.update_frequency) and self.update_frequency > 0.0):
            raise ValueError(
                f"local costmap update_frequency must be finite and > 0 Hz, "
                f"got {self.update_frequency!r}"
            )


class LocalCostmap:
    """A rolling window around the robot; outside the window reads as unknown.

    Readers (:meth:`costs_at`, :meth:`grid`) see the published view: a copy of the
    window's costs, replaced whole by each update, never a half-done one. The sync
    methods (:meth:`add_scan`, :meth:`follow`, the clearings) update and publish at
    once; :meth:`updated` updates without publishing, for a worker thread whose result
    the control loop publishes between its cycles (:meth:`publish`)."""

    __slots__ = ("_costmap", "_view", "update_period")

    def __init__(self, params: LocalCostmapParams | None = None) -> None:
        p = params or LocalCostmapParams()
        self.update_period = 1.0 / p.update_frequency  # robot s between updates from the robot
        self._costmap = RollingCostmap(
            p.size,
            p.size,
            p.resolution,
            InflationParams(p.robot_radius, p.inflation_radius, p.cost_scaling_factor),
            ObstacleParams(
                obstacle_max_range=p.obstacle_max_range, raytrace_max_range=p.raytrace_max_range
            ),
            track_unknown_space=False,
        )
        self._view = self._built()

    @property
    def resolution(self) -> float:
        return self._costmap.geometry.resolution

    @property
    def costmap(self) -> RollingCostmap:
        """The window being updated (not the published view: see the class docstring)."""
        return self._costmap

    def grid(self) -> CostGrid:
        """The published costs (a copy, kept until the next :meth:`publish`: do not modify)."""
        return self._view

    def costs_at(self, points: FloatArray) -> NDArray[np.uint8]:
        view = self._view
        cols, rows, ok = view.geometry.world_to_cells(points[:, 0], points[:, 1])
        return np.where(ok, view.costs[rows, cols], NO_INFORMATION).astype(np.uint8)

    def publish(self, view: CostGrid) -> None:
        """Make ``view`` (from :meth:`updated`) what readers see."""
        self._view = view

    def updated(
        self, scan: LaserScan | None, sensor: Pose2D | None, centre: Pose2D | None
    ) -> CostGrid:
        """The window centred on ``centre`` (if given), then the scan taken at ``sensor``
        (if given) cleared and marked, inflated: a new view, not yet published. Raises
        ValueError for a scan it cannot take (the window is centred already)."""
        if centre is not None:
            self._costmap.update_origin(centre.x, centre.y)
        if scan is not None and sensor is not None:
            self._costmap.update_from_scan(
                Scan.create(
                    (sensor.x, sensor.y, sensor.yaw),
                    scan.angle_min,
                    scan.angle_increment,
                    scan.ranges_array(),
                    scan.range_min,
                    scan.range_max,
                )
            )
        return self._built()

    def _built(self) -> CostGrid:
        return CostGrid(self._costmap.geometry, self._costmap.master.copy())

    def follow(self, pose: Pose2D) -> None:
        """Keep the window centred on the robot."""
        self._view = self.updated(None, None, pose)

    def add_scan(self, scan: LaserScan, sensor: Pose2D, centre: Pose2D | None = None) -> None:
        """Clear and mark from a scan taken at ``sensor`` (the robot pose in map), the
        window centred on ``centre`` first (default: the sensor; a newer robot pose, so
        that the window moves before the scan, not after with its cells pending)."""
        try:
            view = self.updated(scan, sensor, centre or sensor)
        except ValueError:
            self._view = self._built()  # the window moved before the scan was refused
            raise
        self._view = view

    def staged(self, change: Callable[[RollingCostmap], object]) -> CostGrid:
        """``change`` made to the window (e.g. a clearing): the new view, not published."""
        change(self._costmap)
        return self._built()

    def clear_entirely(self) -> None:
        self._view = self.staged(RollingCostmap.clear_entirely)

    def clear_around(self, pose: Pose2D, reset_distance: float) -> None:
        self._view = self.staged(clearing(pose, reset_distance, keep_inside=False))

    def clear_except(self, pose: Pose2D, reset_distance: float) -> None:
        self._view = self.staged(clearing(pose, reset_distance, keep_inside=True))


def clearing(
    pose: Pose2D, reset_distance: float, keep_inside: bool
) -> Callable[[RollingCostmap], None]:
    """Nav2's clear-except (``keep_inside``) or clear-around of a square of side
    ``reset_distance`` at ``pose``, as a change for :meth:`LocalCostmap.staged`."""

    def change(costmap: RollingCostmap) -> None:
        clear = costmap.clear_except if keep_inside else costmap.clear_around
        clear(pose.x, pose.y, reset_distance)

    return change


@dataclass(slots=True, frozen=True)
class CostmapUpdate:
    """One update from the robot: the window centred on ``centre``, then ``scan`` (taken
    at ``sensor``) cleared and marked; either may be missing."""

    scan: LaserScan | None
    sensor: Pose2D | None
    centre: Pose2D | None

    def apply(self, costmap: LocalCostmap) -> CostGrid:
        """The new view (not published); a scan it cannot take is dropped with a warning."""
        try:
            return costmap.updated(self.scan, self.sensor, self.centre)
        except ValueError as exc:
            log.warning("scan dropped: %s", exc)
            return costmap.updated(None, None, None)


class FrameShift:
    """A CostQuery in another frame: points are moved by ``transform`` before the look-up."""

    __slots__ = ("inner", "transform")

    def __init__(self, inner: CostQuery, transform: Pose2D | None = None) -> None:
        self.inner = inner
        self.transform = transform or Pose2D(0.0, 0.0, 0.0)

    @property
    def resolution(self) -> float:
        return self.inner.resolution

    def costs_at(self, points: FloatArray) -> NDArray[np.uint8]:
        t = self.transform
        c, s = math.cos(t.yaw), math.sin(t.yaw)
        moved = np.column_stack(
            (t.x + c * points[:, 0] - s * points[:, 1], t.y + s * points[:, 0] + c * points[:, 1])
        )
        return self.inner.costs_at(moved)


def frame_transform(in_target: Pose2D, in_source: Pose2D) -> Pose2D:
    """The source -> target transform, given the same robot pose in both frames."""
    yaw = in_target.yaw - in_source.yaw
    c, s = math.cos(yaw), math.sin(yaw)
    return Pose2D(
        in_target.x - (c * in_source.x - s * in_source.y),
        in_target.y - (s * in_source.x + c * in_source.y),
        yaw,
    )
