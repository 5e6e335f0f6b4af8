"""Nav2's smooth control law (``nav2_graceful_controller::SmoothControlLaw``), the one
Nav2's docking and following servers drive with: a unicycle command that steers onto a
target pose along a smooth spiral (Park and Kuipers' graceful law), slowing with the
path's curvature and near the target.

Everything is in the robot's frame: the target is a :class:`Pose2D` relative to the
robot (Nav2 transforms it into ``base_frame`` first). Parameter names and defaults
are those of Nav2's docking ``controller.*`` parameters. :func:`rotate_to_heading` is
the two servers' turn in place (``Controller::rotateToTarget``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .pose import Pose2D, Velocity, wrap_angle

ORIGIN = Pose2D()


@dataclass(slots=True, frozen=True)
class SmoothControlParams:
    """Nav2's ``controller.*`` gains and limits (opennav_docking's defaults)."""

    k_phi: float = 3.0
    k_delta: float = 2.0
    beta: float = 0.4
    lambda_: float = 2.0  # Nav2's ``lambda``
    v_linear_min: float = 0.1
    v_linear_max: float = 0.25
    v_angular_max: float = 0.75
    slowdown_radius: float = 0.25
    deceleration_max: float = 2.5

    def __post_init__(self) -> None:
        for name in self.__slots__:
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"controller.{name.rstrip('_')} must be >= 0, got {value}")
        if self.slowdown_radius <= 0.0:
            raise ValueError("controller.slowdown_radius must be > 0")
        if self.v_linear_min > self.v_linear_max:
            raise ValueError(
                f"controller.v_linear_min ({self.v_linear_min}) is above "
                f"controller.v_linear_max ({self.v_linear_max})"
            )


@dataclass(slots=True, frozen=True)
class EgoPolar:
    """The target in egocentric polar coordinates: distance ``r``, the target's
    orientation ``phi`` and the robot's steering angle ``delta``, both to the line of
    sight (Nav2's ``EgocentricPolarCoordinates``)."""

    r: float
    phi: float
    delta: float

    @classmethod
    def of(cls, target: Pose2D, current: Pose2D = ORIGIN, backward: bool = False) -> EgoPolar:
        dx, dy = target.x - current.x, target.y - current.y
        sight = math.atan2(-dy, dx) + (math.pi if backward else 0.0)
        return cls(math.hypot(dx, dy), wrap_angle(target.yaw + sight),
                   wrap_angle(current.yaw + sight))  # fmt: skip


class SmoothControlLaw:
    """``calculateRegularVelocity`` and ``calculateNextPose`` of Nav2's law."""

    __slots__ = ("params",)

    def __init__(self, params: SmoothControlParams | None = None) -> None:
        self.params = params or SmoothControlParams()

    def curvature(self, r: float, phi: float, delta: float) -> float:
        p = self.params
        prop = p.k_delta * (delta - math.atan(-p.k_phi * phi))
        feedback = (1.0 + p.k_phi / (1.0 + (p.k_phi * phi) ** 2)) * math.sin(delta)
        return -1.0 / r * (prop + feedback) if r > 0.0 else 0.0

    def velocity(
        self, target: Pose2D, current: Pose2D = ORIGIN, backward: bool = False
    ) -> Velocity:
        """The command that steers from ``current`` (default: the robot's origin) to
        ``target``, both in one frame."""
        p = self.params
        ego = EgoPolar.of(target, current, backward)
        curvature = self.curvature(ego.r, ego.phi, ego.delta)
        curvature = -curvature if backward else curvature
        v = p.v_linear_max / (1.0 + p.beta * abs(curvature) ** p.lambda_)
        v = min(p.v_linear_max * ego.r / p.slowdown_radius, v)  # slow near the target
        v = min(math.sqrt(2.0 * ego.r * p.deceleration_max), v)
        v = min(max(v, p.v_linear_min), p.v_linear_max)
        v = -v if backward else v
        w = max(-p.v_angular_max, min(p.v_angular_max, curvature * v))
        v = w / curvature if curvature != 0.0 else v  # keep to the curvature
        return Velocity(v, w)

    def next_pose(
        self, dt: float, target: Pose2D, current: Pose2D, backward: bool = False
    ) -> Pose2D:
        """``current`` moved for ``dt`` by the command toward ``target``."""
        cmd = self.velocity(target, current, backward)
        return Pose2D(
            current.x + cmd.v * dt * math.cos(current.yaw),
            current.y + cmd.v * dt * math.sin(current.yaw),
            wrap_angle(current.yaw + cmd.w * dt),
        )


@dataclass(slots=True, frozen=True)
class RotateParams:
    """``controller.rotate_to_heading_*``: the turn in place (Nav2's defaults)."""

    rotate_to_heading_angular_vel: float = 1.0
    rotate_to_heading_max_angular_accel: float = 3.2

    def __post_init__(self) -> None:
        for name in self.__slots__:
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"controller.{name} must be > 0, got {value}")


def rotate_to_heading(
    params: RotateParams, angle_to_go: float, angular_now: float, dt: float
) -> float:
    """Nav2's ``rotateToTarget``: turn at ``rotate_to_heading_angular_vel`` towards a
    heading ``angle_to_go`` away, within the acceleration limit of ``angular_now``, then
    capped to what still stops on the heading."""
    accel = params.rotate_to_heading_max_angular_accel
    sign = 1.0 if angle_to_go > 0.0 else -1.0
    step = accel * dt
    w = min(
        max(sign * params.rotate_to_heading_angular_vel, angular_now - step), angular_now + step
    )
    stop = math.sqrt(2.0 * accel * abs(angle_to_go))
    return sign * stop if abs(w) > stop else w
