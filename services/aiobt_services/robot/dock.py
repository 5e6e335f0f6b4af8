"""The charging dock as a robot meets it: a block against a wall with charging contacts
on its face and a fiducial (an AprilTag-like marker) above them.

The dock's pose (the world's ``aiobt.dock: [x, y, yaw]``) is where the robot's centre
stands when docked, facing the dock: the block's face is ``robot radius`` ahead of it.
The block is lower than the lidar's plane (as most docks are): the lidar does not see
it; the robot's camera sees the marker. :meth:`DockStation.detect` is that camera's
detection: the marker's pose in the robot's frame (``base_link``) with noise growing
with range, only when the marker is in the field of view, faces the camera and no wall
or obstacle stands between. :meth:`DockStation.charging_contact` is the only way the
battery charges: the robot's contacts pressed on the dock's, within a centimetre or so
and a few hundredths of a radian (the truth, as the hardware's contacts would know it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from aiobt.geometry import Pose2D, wrap_angle

from .mapfile import Dock, MapInfo
from .world import Physics, RobotShape


@dataclass(slots=True, frozen=True)
class DockShape:
    """The block, the contacts' reach and the camera's view of the marker."""

    depth: float = 0.12  # m, along the dock's axis
    width: float = 0.40  # m
    height: float = 0.12  # m: under the lidar's plane (0.2 m)
    contact_depth: float = 0.01  # m short of the face the spring contacts still touch
    contact_width: float = 0.012  # m off the axis the contacts still meet
    contact_angle: float = 0.04  # rad off the axis the contacts still meet
    camera_fov: float = 1.2  # rad, horizontal, centred on the robot's heading
    max_range: float = 3.0  # m
    min_range: float = 0.1  # m
    max_incidence: float = 1.1  # rad between the marker's normal and the line of sight
    noise_xy: tuple[float, float] = (0.002, 0.004)  # m: std = a + b * range
    noise_yaw: tuple[float, float] = (0.005, 0.01)  # rad: std = a + b * range


@dataclass(slots=True, frozen=True)
class DockStation:
    """One dock in the world (its pose from the map) with the robot's radius."""

    dock: Dock
    robot_radius: float
    shape: DockShape = DockShape()

    @property
    def pose(self) -> Pose2D:
        return Pose2D(self.dock.x, self.dock.y, self.dock.yaw)

    @property
    def marker(self) -> Pose2D:
        """The marker on the block's face, its yaw pointing into the dock (as the dock's)."""
        return self.pose.compose(Pose2D(self.robot_radius, 0.0, 0.0))

    def block(self) -> tuple[Pose2D, tuple[float, float, float]]:
        """The block's centre and half extents (x along the dock's axis)."""
        s = self.shape
        centre = self.pose.compose(Pose2D(self.robot_radius + 0.5 * s.depth, 0.0, 0.0))
        return centre, (0.5 * s.depth, 0.5 * s.width, 0.5 * s.height)

    def offset(self, robot: Pose2D) -> Pose2D:
        """The robot's pose in the dock's frame (0, 0, 0 when exactly docked)."""
        return self.pose.inverse().compose(robot)

    def charging_contact(self, robot: Pose2D) -> bool:
        off, s = self.offset(robot), self.shape
        return (
            off.x >= -s.contact_depth
            and abs(off.y) <= s.contact_width
            and abs(wrap_angle(off.yaw)) <= s.contact_angle
        )

    def bearing_from(self, robot: Pose2D) -> float:
        """The world heading from ``robot`` to the marker."""
        marker = self.marker
        return math.atan2(marker.y - robot.y, marker.x - robot.x)

    def visible(self, robot: Pose2D, occlusion: float) -> bool:
        """The marker in view from ``robot``; ``occlusion``: how far the first wall or
        obstacle lies along the line of sight (``inf``: none)."""
        s, marker = self.shape, self.marker
        seen = robot.inverse().compose(marker)
        distance = math.hypot(seen.x, seen.y)
        bearing = math.atan2(seen.y, seen.x)
        # the marker faces out of the dock: its normal is its yaw + pi
        incidence = wrap_angle(marker.yaw + math.pi - math.atan2(robot.y - marker.y,
                                                                  robot.x - marker.x))  # fmt: skip
        return (
            s.min_range <= distance <= s.max_range
            and abs(bearing) <= 0.5 * s.camera_fov
            and abs(incidence) <= s.max_incidence
            and occlusion >= distance - 0.05
        )

    def detect(self, robot: Pose2D, rng: np.random.Generator) -> Pose2D:
        """The marker's pose in the robot's frame, with the camera's noise."""
        s = self.shape
        seen = robot.inverse().compose(self.marker)
        distance = math.hypot(seen.x, seen.y)
        sigma_xy = s.noise_xy[0] + s.noise_xy[1] * distance
        sigma_yaw = s.noise_yaw[0] + s.noise_yaw[1] * distance
        dx, dy = rng.normal(0.0, sigma_xy, 2)
        return Pose2D(seen.x + float(dx), seen.y + float(dy),
                      wrap_angle(seen.yaw + float(rng.normal(0.0, sigma_yaw))))  # fmt: skip


def build_station(
    world: MapInfo, robot: RobotShape, physics: Physics
) -> tuple[DockStation | None, int]:
    """The world's dock and its block's body (``-1``: the world has no dock)."""
    if world.dock is None:
        return None, -1
    station = DockStation(world.dock, robot.radius)
    centre, half = station.block()
    return station, physics.static_box(centre.x, centre.y, centre.yaw, half)
