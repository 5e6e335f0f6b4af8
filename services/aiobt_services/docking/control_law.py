"""Nav2's graceful controller's control law (``nav2_graceful_controller``'s
``SmoothControlLaw`` and ``EgocentricPolarCoordinates``), which the docking server's
controller drives the robot with: a smooth spiral onto a target pose, from Park and
Kuipers' "A smooth control law for graceful motion of differential wheeled mobile robots".

Poses are planar, in the robot's frame (the robot at the origin, heading +x) unless a
``current`` pose is given.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from aiobt.geometry import Pose2D, Velocity, wrap_angle


@dataclass(slots=True, frozen=True)
class EgoPolar:
    """The target relative to the robot: distance ``r``, the target's orientation
    against the line of sight ``phi``, the robot's steering against it ``delta``."""

    r: float
    phi: float
    delta: float

    @classmethod
    def of(cls, target: Pose2D, current: Pose2D, backward: bool = False) -> EgoPolar:
        dx, dy = target.x - current.x, target.y - current.y
        line_of_sight = math.atan2(-dy, dx) + (math.pi if backward else 0.0)
        return cls(
            math.hypot(dx, dy),
            wrap_angle(target.yaw + line_of_sight),
            wrap_angle(current.yaw + line_of_sight),
        )


@dataclass(slots=True, frozen=True)
class ControlLawParams:
    """``controller.*`` of Nav2's docking server (its defaults)."""

    k_phi: float = 3.0
    k_delta: float = 2.0
    beta: float = 0.4
    lambda_: float = 2.0
    v_linear_min: float = 0.1
    v_linear_max: float = 0.25
    v_angular_max: float = 0.75
    slowdown_radius: float = 0.25
    deceleration_max: float = 2.5
    rotate_to_heading_angular_vel: float = 1.0
    rotate_to_heading_max_angular_accel: float = 3.2

    def __post_init__(self) -> None:
        for name in self.__slots__:
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"controller.{name.rstrip('_')} must be >= 0, got {value}")
        if self.beta <= 0.0 or self.lambda_ < 1.0 or self.slowdown_radius <= 0.0:
            raise ValueError("controller.beta must be > 0, controller.lambda >= 1 and "
                             "controller.slowdown_radius > 0")  # fmt: skip


class SmoothControlLaw:
    """``calculateRegularVelocity``, ``calculateNextPose`` and the rotate-to-heading
    command of Nav2's docking controller."""

    def __init__(self, params: ControlLawParams) -> None:
        self.params = params

    def curvature(self, r: float, phi: float, delta: float) -> float:
        p = self.params
        prop_term = p.k_delta * (delta - math.atan(-p.k_phi * phi))
        feedback_term = (1.0 + p.k_phi / (1.0 + (p.k_phi * phi) ** 2)) * math.sin(delta)
        return -1.0 / r * (prop_term + feedback_term) if r > 0.0 else 0.0

    def velocity(self, target: Pose2D, current: Pose2D | None = None,
                 backward: bool = False) -> Velocity:  # fmt: skip
        """The command that steers ``current`` (default: the origin) onto ``target``."""
        p = self.params
        ego = EgoPolar.of(target, current or Pose2D(), backward)
        curvature = self.curvature(ego.r, ego.phi, ego.delta)
        curvature = -curvature if backward else curvature
        v = p.v_linear_max / (1.0 + p.beta * abs(curvature) ** p.lambda_)
        v = min(p.v_linear_max * (ego.r / p.slowdown_radius), v)
        v = min(math.sqrt(2.0 * ego.r * p.deceleration_max), v)
        v = min(max(v, p.v_linear_min), p.v_linear_max)
        v = -v if backward else v
        w = min(max(curvature * v, -p.v_angular_max), p.v_angular_max)
        v = w / curvature if curvature != 0.0 else v
        return Velocity(v, w)

    def next_pose(self, dt: float, target: Pose2D, current: Pose2D, backward: bool) -> Pose2D:
        cmd = self.velocity(target, current, backward)
        return Pose2D(
            current.x + cmd.v * dt * math.cos(current.yaw),
            current.y + cmd.v * dt * math.sin(current.yaw),
            wrap_angle(current.yaw + cmd.w * dt),
        )

    def rotate_to_heading(self, angle_to_go: float, angular_now: float, dt: float) -> float:
        """Turn rate toward a heading ``angle_to_go`` away, within the acceleration limit
        and slow enough to stop on it."""
        p = self.params
        sign = 1.0 if angle_to_go > 0.0 else -1.0
        accel = p.rotate_to_heading_max_angular_accel * dt
        w = min(
            max(sign * p.rotate_to_heading_angular_vel, angular_now - accel), angular_now + accel
        )
        stop = math.sqrt(2.0 * p.rotate_to_heading_max_angular_accel * abs(angle_to_go))
        return sign * stop if abs(w) > stop else w
