"""Planar poses and velocities: the one ``Pose2D``, the one angle wrap.

Angles are radians; :func:`wrap_angle` maps any angle into ``[-pi, pi)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

XYYaw = tuple[float, float, float]
"""A pose as a plain tuple, where a hot loop or a numpy row wants no object."""


def wrap_angle(angle: float) -> float:
    """Angle wrapped to ``[-pi, pi)``."""
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def turn_rate(
    angle_error: float,
    max_rate: float,
    accel: float,
    previous: float,
    dt: float,
    lead: float = 0.0,
) -> float:
    """Angular speed to turn in place by ``angle_error``, stopping on the heading.

    At most ``max_rate`` and ``sqrt(2 accel |coming|)`` (decelerates instead of
    overshooting), and within ``accel * dt`` of the ``previous`` rate. ``coming`` is
    the error less the turn still in flight: the base goes on at the ``previous`` rate
    for the ``lead`` (clock seconds until a command sent now acts) before this one
    takes over, as the Spin behavior reckons. With no lead it is the error itself.
    """
    in_flight = previous * lead if previous * angle_error > 0.0 else 0.0
    coming = max(0.0, abs(angle_error) - abs(in_flight))
    magnitude = min(max_rate, math.sqrt(2.0 * accel * coming))
    w = math.copysign(magnitude, angle_error)
    step = accel * dt
    return min(max(w, previous - step), previous + step)


@dataclass(slots=True, frozen=True)
class Pose2D:
    """A planar pose: position in metres, heading in radians."""

    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0

    def compose(self, other: Pose2D) -> Pose2D:
        """``self * other``: ``other`` expressed in the frame of ``self``."""
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return Pose2D(
            self.x + c * other.x - s * other.y,
            self.y + s * other.x + c * other.y,
            wrap_angle(self.yaw + other.yaw),
        )

    def inverse(self) -> Pose2D:
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return Pose2D(-c * self.x - s * self.y, s * self.x - c * self.y, wrap_angle(-self.yaw))

    def distance_to(self, other: Pose2D) -> float:
        return math.hypot(other.x - self.x, other.y - self.y)

    def is_finite(self) -> bool:
        return math.isfinite(self.x) and math.isfinite(self.y) and math.isfinite(self.yaw)


@dataclass(slots=True, frozen=True)
class Velocity:
    """A unicycle command or measurement: forward speed ``v``, yaw rate ``w``."""

    v: float = 0.0
    w: float = 0.0

    def is_finite(self) -> bool:
        return math.isfinite(self.v) and math.isfinite(self.w)


STOP = Velocity(0.0, 0.0)
