"""Regulated Pure Pursuit (Nav2's ``FollowPath`` default, Macenski et al. 2023).

Per cycle: find the robot's foot point on the path (searching forward from the
last one, so a U-turn does not snap to the return leg), pick a carrot at a
speed-scaled lookahead, steer on the circle through it, regulate the speed on
curvature, obstacle proximity and approach to the goal, rotate in place towards
the path at the start and towards the goal heading at the end, and refuse a
command whose arc collides within a time horizon.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from aiobt.costmap import INSCRIBED, NO_INFORMATION
from aiobt.costmap.checker import CollisionChecker
from aiobt.geometry import (
    FloatArray,
    PlanarPath,
    Pose2D,
    Velocity,
    to_robot_frame,
    turn_rate,
    wrap_angle,
)
from aiobt.robot.latency import LEAD_CAP, holding_time

from .base import ControlContext, PlanFollower
from .errors import no_valid_control
from .speed_limit import SpeedLimit
from .tracking import project_onto_path, remaining_length, search_stop


@dataclass(slots=True)
class RPPParams:
    desired_linear_vel: float = 0.5
    lookahead_dist: float = 0.6
    min_lookahead_dist: float = 0.3
    max_lookahead_dist: float = 0.9
    lookahead_time: float = 1.5
    use_velocity_scaled_lookahead_dist: bool = True
    max_angular_vel: float = 1.8
    use_rotate_to_heading: bool = True
    rotate_to_heading_angular_vel: float = 1.8
    rotate_to_heading_min_angle: float = 0.785
    max_angular_accel: float = 3.2
    use_regulated_linear_velocity_scaling: bool = True
    regulated_linear_scaling_min_radius: float = 0.9
    regulated_linear_scaling_min_speed: float = 0.25
    use_cost_regulated_linear_velocity_scaling: bool = True
    cost_scaling_dist: float = 0.6
    cost_scaling_gain: float = 1.0
    inflation_cost_scaling_factor: float = 3.0
    inscribed_radius: float = 0.3
    approach_velocity_scaling_dist: float = 0.6
    min_approach_linear_velocity: float = 0.05
    use_collision_detection: bool = True
    max_allowed_time_to_collision_up_to_carrot: float = 1.0
    max_robot_pose_search_dist: float = 2.0


class RegulatedPurePursuit(PlanFollower):
    """The ``FollowPath`` controller id."""

    __slots__ = ("_base_linear_vel", "_last_w", "params")
    name = "RegulatedPurePursuit"

    def __init__(self, params: RPPParams | None = None) -> None:
        super().__init__()
        self.params = params or RPPParams()
        self._base_linear_vel = self.params.desired_linear_vel
        self._last_w = 0.0

    def set_speed_limit(self, limit: SpeedLimit) -> None:
        """Nav2's ``setSpeedLimit``: the top speed under ``limit`` (none: as configured)."""
        self.params.desired_linear_vel = limit.replaced(self._base_linear_vel)

    def reset(self) -> None:
        super().reset()
        self._last_w = 0.0

    def compute_velocity(self, pose: Pose2D, speed: Velocity, ctx: ControlContext) -> Velocity:
        path = self._require_path()
        stop = search_stop(path, self._segment, self.params.max_robot_pose_search_dist)
        projection = project_onto_path(path, pose, self._segment, stop)
        self._segment = projection.segment
        goal = path.goal
        if self.params.use_rotate_to_heading and pose.distance_to(goal) < ctx.goal_xy_tolerance:
            self.trajectory = _poses(path, self._segment, len(path))
            return self._rotate(pose, wrap_angle(goal.yaw - pose.yaw), ctx)
        carrot, inside = self._carrot(path, pose, self._lookahead(speed))
        self.trajectory = _up_to_carrot(path, self._segment, inside, carrot, pose)
        angle_to_carrot = math.atan2(carrot[1], carrot[0])
        if (
            self.params.use_rotate_to_heading
            and abs(angle_to_carrot) > self.params.rotate_to_heading_min_angle
        ):
            return self._rotate(pose, angle_to_carrot, ctx)
        curvature = 2.0 * carrot[1] / max(carrot[0] ** 2 + carrot[1] ** 2, 1e-9)
        v = self._regulated_speed(pose, curvature, remaining_length(path, projection), ctx)
        w = v * curvature
        if abs(w) > self.params.max_angular_vel:
            w = math.copysign(self.params.max_angular_vel, w)
            v = abs(w / curvature)
        cmd = Velocity(v, w)
        self._check_arc(pose, cmd, math.hypot(*carrot), ctx)
        self._last_w = w
        return cmd

    def _lookahead(self, speed: Velocity) -> float:
        p = self.params
        if not p.use_velocity_scaled_lookahead_dist:
            return p.lookahead_dist
        return min(max(abs(speed.v) * p.lookahead_time, p.min_lookahead_dist), p.max_lookahead_dist)

    def _carrot(
        self, path: PlanarPath, pose: Pose2D, lookahead: float
    ) -> tuple[tuple[float, float], int]:
        """The point where the path (after the foot point) leaves the lookahead circle (robot
        frame), and how many path poses from the foot point come before it."""
        local = to_robot_frame(pose, path.xy[self._segment :])
        dist = np.hypot(local[:, 0], local[:, 1])
        beyond = np.nonzero(dist >= lookahead)[0]
        beyond = beyond[beyond > 0]
        if beyond.size == 0:
            return (float(local[-1, 0]), float(local[-1, 1])), len(local)
        i = int(beyond[0])
        return _circle_segment_intersection(local[i - 1], local[i], lookahead), i

    def _regulated_speed(
        self, pose: Pose2D, curvature: float, remaining: float, ctx: ControlContext
    ) -> float:
        p = self.params
        v = p.desired_linear_vel
        if p.use_regulated_linear_velocity_scaling and abs(curvature) > 1e-9:
            radius = 1.0 / abs(curvature)
            if radius < p.regulated_linear_scaling_min_radius:
                v *= radius / p.regulated_linear_scaling_min_radius
        if p.use_cost_regulated_linear_velocity_scaling and ctx.collision is not None:
            v = min(v, self._cost_regulated(pose, ctx.collision))
        v = max(v, p.regulated_linear_scaling_min_speed)
        if remaining < p.approach_velocity_scaling_dist:
            v = max(
                v * remaining / p.approach_velocity_scaling_dist, p.min_approach_linear_velocity
            )
        return min(v, p.desired_linear_vel)

    def _cost_regulated(self, pose: Pose2D, collision: CollisionChecker) -> float:
        p = self.params
        cost = int(collision.costmap.costs_at(np.array([[pose.x, pose.y]]))[0])
        if cost == NO_INFORMATION or cost == 0 or cost >= INSCRIBED:
            return p.desired_linear_vel
        # invert Nav2's inflation decay: cost = 252 * exp(-k (d - r_inscribed))
        distance = (
            -math.log(cost / (INSCRIBED - 1)) / p.inflation_cost_scaling_factor + p.inscribed_radius
        )
        if distance >= p.cost_scaling_dist:
            return p.desired_linear_vel
        return p.desired_linear_vel * p.cost_scaling_gain * distance / p.cost_scaling_dist

    def _rotate(self, pose: Pose2D, angle_error: float, ctx: ControlContext) -> Velocity:
        p = self.params
        w = turn_rate(
            angle_error,
            p.rotate_to_heading_angular_vel,
            p.max_angular_accel,
            self._last_w,
            ctx.dt,
            min(ctx.lead, LEAD_CAP),  # the turn in flight is reckoned, as Spin does
        )
        if (
            p.use_collision_detection
            and ctx.collision is not None
            and ctx.collision.pose_collides(pose)
        ):
            raise no_valid_control(
                "RegulatedPurePursuit detected collision while rotating to heading"
            )
        self._last_w = w
        return Velocity(0.0, w)

    def _check_arc(
        self, pose: Pose2D, cmd: Velocity, carrot_dist: float, ctx: ControlContext
    ) -> None:
        """Up to the carrot, plus the way the robot may still go on this command before a
        stop acts (:func:`holding_time` of the lead), so the stop keeps its margin under a
        sim speed-up."""
        p, collision = self.params, ctx.collision
        if not p.use_collision_detection or collision is None:
            return
        holding = holding_time(ctx.lead)
        horizon = p.max_allowed_time_to_collision_up_to_carrot + holding
        reach = max(carrot_dist, collision.costmap.resolution) + abs(cmd.v) * holding
        check = collision.check_arc(pose, cmd, horizon, reach)
        if check.collides:
            raise no_valid_control(
                f"RegulatedPurePursuit detected collision ahead "
                f"(in {check.time_to_collision:.2f} s at v={cmd.v:.2f} m/s, w={cmd.w:.2f} rad/s)"
            )


def _poses(path: PlanarPath, start: int, stop: int) -> FloatArray:
    return np.column_stack((path.xy[start:stop], path.yaw[start:stop]))


def _up_to_carrot(
    path: PlanarPath, start: int, count: int, carrot: tuple[float, float], pose: Pose2D
) -> FloatArray:
    """RPP's local plan (Nav2 publishes the carrot-lookahead segment): the path poses from
    the foot point up to the carrot, then the carrot itself (robot frame -> path frame)."""
    segment = _poses(path, start, start + count)
    c, s = math.cos(pose.yaw), math.sin(pose.yaw)
    x = pose.x + c * carrot[0] - s * carrot[1]
    y = pose.y + s * carrot[0] + c * carrot[1]
    heading = float(path.yaw[min(start + count, len(path) - 1)])
    return np.vstack((segment, [[x, y, heading]]))


def _circle_segment_intersection(a: np.ndarray, b: np.ndarray, r: float) -> tuple[float, float]:
    """Point on segment a->b at distance r from the origin (a inside, b outside)."""
    d = b - a
    qa = float(d @ d)
    if qa < 1e-12:
        return float(b[0]), float(b[1])
    qb = 2.0 * float(a @ d)
    qc = float(a @ a) - r * r
    t = (-qb + math.sqrt(max(qb * qb - 4.0 * qa * qc, 0.0))) / (2.0 * qa)
    t = min(max(t, 0.0), 1.0)
    return float(a[0] + t * d[0]), float(a[1] + t * d[1])
