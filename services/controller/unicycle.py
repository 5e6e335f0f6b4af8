"""A kinematic unicycle robot for tests and benchmarks (no physics)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .geometry import STOP, Pose2D, Velocity


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
        if abs(w) < 1e-9:
            x, y = p.x + v * dt * math.cos(p.yaw), p.y + v * dt * math.sin(p.yaw)
        else:
            yaw_end = p.yaw + w * dt
            x = p.x + v / w * (math.sin(yaw_end) - math.sin(p.yaw))
            y = p.y - v / w * (math.cos(yaw_end) - math.cos(p.yaw))
        self.pose = Pose2D(x, y, math.atan2(math.sin(p.yaw + w * dt), math.cos(p.yaw + w * dt)))
        self.velocity = Velocity(v, w)
        return self.pose


def _approach(current: float, target: float, max_step: float) -> float:
    return current + max(-max_step, min(max_step, target - current))
