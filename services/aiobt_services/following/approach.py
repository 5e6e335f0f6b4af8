"""One control step toward the pose at the desired distance behind the object, and the
search turn (Nav2's ``approachObject`` and ``rotateToObject`` bodies, free of I/O)."""

from __future__ import annotations

import math

from aiobt.geometry import Pose2D, Velocity, turn_rate, wrap_angle
from aiobt.geometry.smooth import SmoothControlLaw

from .errors import FailedToControl
from .params import BACKWARD_PROJECTION, FollowingParams


def pose_at_distance(obj: Pose2D, robot: Pose2D, distance: float) -> Pose2D:
    """``obj`` moved ``distance`` toward the robot along the line between them
    (Nav2's ``getPoseAtDistance``; the object's heading kept)."""
    dx, dy = obj.x - robot.x, obj.y - robot.y
    dist = math.hypot(dx, dy)
    if dist == 0.0:
        return obj
    return Pose2D(obj.x - distance * dx / dist, obj.y - distance * dy / dist, obj.yaw)


def reached(goal: Pose2D, robot: Pose2D, params: FollowingParams) -> bool:
    """Nav2's ``isGoalReached``: within both tolerances of ``goal``."""
    return (
        robot.distance_to(goal) < params.linear_tolerance
        and abs(wrap_angle(goal.yaw - robot.yaw)) < params.angular_tolerance
    )


class Approach:
    """:meth:`step`: None when the robot is at the desired distance, else its command."""

    __slots__ = ("law", "params")

    def __init__(self, params: FollowingParams) -> None:
        self.params = params
        self.law = SmoothControlLaw(params.controller)

    def step(self, obj: Pose2D, robot: Pose2D) -> Velocity | None:
        distance = self.params.desired_distance
        if reached(pose_at_distance(obj, robot, distance), robot, self.params):
            return None
        aim = pose_at_distance(obj, robot, distance - BACKWARD_PROJECTION)
        cmd = self.law.velocity(robot.inverse().compose(aim))
        if not cmd.is_finite():
            raise FailedToControl(f"Failed to get control: command {cmd} toward {aim}")
        return cmd

    def turn(self, heading_error: float, current_rate: float) -> Velocity:
        """Nav2's ``computeRotateToHeadingCommand``: turn in place by ``heading_error``."""
        rotate = self.params.rotate
        w = turn_rate(heading_error, rotate.rotate_to_heading_angular_vel,
                      rotate.rotate_to_heading_max_angular_accel, current_rate,
                      self.params.period)  # fmt: skip
        return Velocity(0.0, w)
