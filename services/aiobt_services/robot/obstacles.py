"""Obstacle descriptions and their motion; pure logic, checked before spawning."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from aiobt.geometry import Pose2D

from .lidar import Disc, Solid
from .mapfile import MapInfo

SHAPES = ("box", "cylinder")


class ObstacleError(ValueError):
    """A spawn, move or remove request that cannot be carried out, with the reason."""


@dataclass(slots=True, frozen=True)
class Motion:
    """Back and forth along the segment from the spawn point to ``(to_x, to_y)``."""

    to_x: float
    to_y: float
    speed: float  # m/s


@dataclass(slots=True, frozen=True)
class ObstacleSpec:
    """One obstacle: a box (size_x by size_y) or a cylinder (radius), and its height."""

    id: str
    shape: str
    pose: Pose2D
    size_x: float = 0.5
    size_y: float = 0.5
    radius: float = 0.25
    height: float = 1.0
    motion: Motion | None = None

    @property
    def bounding_radius(self) -> float:
        if self.shape == "cylinder":
            return self.radius
        return 0.5 * math.hypot(self.size_x, self.size_y)

    def distance_to(self, x: float, y: float, at: Pose2D | None = None) -> float:
        """How far the point (x, y) is from this obstacle's footprint placed at ``at``
        (default: its spawn pose); 0 inside it. Exact for both shapes: a box's
        corners are not rounded off into its bounding circle."""
        pose = at or self.pose
        dx, dy = x - pose.x, y - pose.y
        if self.shape == "cylinder":
            return max(0.0, math.hypot(dx, dy) - self.radius)
        c, s = math.cos(pose.yaw), math.sin(pose.yaw)
        along, across = c * dx + s * dy, -s * dx + c * dy  # in the box's frame
        out_x = max(0.0, abs(along) - 0.5 * self.size_x)
        out_y = max(0.0, abs(across) - 0.5 * self.size_y)
        return math.hypot(out_x, out_y)

    def moved_to(self, pose: Pose2D, motion: Motion | None) -> ObstacleSpec:
        return replace(self, pose=pose, motion=motion)

    def pose_at(self, elapsed: float) -> Pose2D:
        """Pose ``elapsed`` seconds after (re)spawn: ping-pong along the segment."""
        if self.motion is None or self.motion.speed <= 0.0:
            return self.pose
        length = math.hypot(self.motion.to_x - self.pose.x, self.motion.to_y - self.pose.y)
        if length == 0.0:
            return self.pose
        travelled = (elapsed * self.motion.speed) % (2.0 * length)
        frac = (travelled if travelled <= length else 2.0 * length - travelled) / length
        return Pose2D(
            self.pose.x + frac * (self.motion.to_x - self.pose.x),
            self.pose.y + frac * (self.motion.to_y - self.pose.y),
            self.pose.yaw,
        )


def _check_positive(what: str, value: float) -> None:
    if not (math.isfinite(value) and value > 0.0):
        raise ObstacleError(f"{what} must be a finite number > 0, got {value}")


def _check_inside(spec: ObstacleSpec, x: float, y: float, world: MapInfo, where: str) -> None:
    if not (math.isfinite(x) and math.isfinite(y)):
        raise ObstacleError(f"obstacle '{spec.id}': {where} ({x}, {y}) is not finite")
    if not world.contains(x, y, margin=spec.bounding_radius):
        raise ObstacleError(
            f"obstacle '{spec.id}': {where} ({x:.2f}, {y:.2f}) with radius "
            f"{spec.bounding_radius:.2f} m is outside the world ({_bounds(world)})"
        )


def _bounds(world: MapInfo) -> str:
    xs, ys = world.cell_to_world(
        [0, 0, world.height, world.height], [0, world.width, 0, world.width]
    )
    return f"x {xs.min():.2f}..{xs.max():.2f}, y {ys.min():.2f}..{ys.max():.2f}"


def validate(spec: ObstacleSpec, world: MapInfo) -> None:
    """Raise :class:`ObstacleError` naming what is wrong with ``spec`` in ``world``."""
    if not spec.id:
        raise ObstacleError("obstacle id must not be empty")
    if spec.shape not in SHAPES:
        raise ObstacleError(f"obstacle '{spec.id}': shape {spec.shape!r} is not one of {SHAPES}")
    if spec.shape == "box":
        _check_positive(f"obstacle '{spec.id}': size_x", spec.size_x)
        _check_positive(f"obstacle '{spec.id}': size_y", spec.size_y)
    else:
        _check_positive(f"obstacle '{spec.id}': radius", spec.radius)
    _check_positive(f"obstacle '{spec.id}': height", spec.height)
    if not math.isfinite(spec.pose.yaw):
        raise ObstacleError(f"obstacle '{spec.id}': yaw is not finite")
    _check_inside(spec, spec.pose.x, spec.pose.y, world, "position")
    if spec.motion is not None:
        _check_positive(f"obstacle '{spec.id}': motion speed", spec.motion.speed)
        _check_inside(spec, spec.motion.to_x, spec.motion.to_y, world, "motion end")


def solid(spec: ObstacleSpec, here: Pose2D) -> Solid:
    """``spec`` at ``here`` as the lidar's plane cuts it."""
    if spec.shape == "box":
        return (here.x, here.y, here.yaw, 0.5 * spec.size_x, 0.5 * spec.size_y)
    return Disc(here.x, here.y, spec.radius)
