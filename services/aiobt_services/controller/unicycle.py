"""A kinematic unicycle robot for tests and benchmarks (no physics)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from aiobt.geometry import STOP, Pose2D, Velocity


@dataclass(slots=True)
class Unicycle:
    """Integrates commanded (v, w) exactly, with optional acceleration limits."""

    pose: Pose2D
    velocity: Velocity = STOP
    max_linear_accel: float = math.inf
    max_angular_accel: float = math.inf

    def step(self, cmd: Velocity, dt: float) -> Pose2D:
        v = _approach(self.velocity.v, cmd.v, self.max_linear_accel * dt)
        w = _approach(self.velocity.w, cmd.w, self.max_angular_accel * dt)
        p = self.pose
        half = 0.5 * w * dt
        chord = v * dt * (math.sin(half) / half if half else 1.0)  # exact arc, stable near w = 0
        x, y = p.x + chord * math.cos(p.yaw + half), p.y + chord * math.sin(p.yaw + half)
        self.pose = Pose2D(x, y, math.atan2(math.sin(p.yaw + w * dt), math.cos(p.yaw + w * dt)))
        self.velocity = Velocity(v, w)
        return self.pose


def _approach(current: float, target: float, max_step: float) -> float:
    return current + max(-max_step, min(max_step, target - current))
