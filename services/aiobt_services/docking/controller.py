"""The docking server's controller (Nav2's ``opennav_docking::Controller``): the
graceful control law toward a pose in the robot's frame, the turn in place, and the
check of the trajectory the law would drive (``controller.use_collision_detection``):
projected ``projection_time`` ahead in ``simulation_time_step`` steps, every pose
farther than ``dock_collision_threshold`` from the dock (docking) or from the start
(undocking) must be free.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from aiobt.geometry import Pose2D, Velocity
from aiobt.geometry.smooth import (
    RotateParams,
    SmoothControlLaw,
    SmoothControlParams,
    rotate_to_heading,
)

from .errors import FailedToControl

Collides = Callable[[list[Pose2D]], bool]  # any of these poses (robot's frame) on an obstacle


@dataclass(slots=True, frozen=True)
class ControllerParams:
    """``controller.*`` beyond the law's, Nav2's defaults."""

    law: SmoothControlParams = field(default_factory=SmoothControlParams)
    rotate: RotateParams = field(default_factory=RotateParams)
    use_collision_detection: bool = True
    projection_time: float = 5.0
    simulation_time_step: float = 0.1
    dock_collision_threshold: float = 0.3

    def __post_init__(self) -> None:
        if not (self.projection_time > 0.0 and self.simulation_time_step > 0.0):
            raise ValueError("controller.projection_time and controller.simulation_time_step "
                             "must be > 0")  # fmt: skip


class DockController:
    def __init__(self, params: ControllerParams, collides: Collides | None = None) -> None:
        self.params = params
        self.law = SmoothControlLaw(params.law)
        self.collides = collides if params.use_collision_detection else None

    def command(self, target: Pose2D, backward: bool, docking: bool) -> Velocity:
        """Toward ``target``, given in the robot's frame; FailedToControl when the way
        there collides."""
        cmd = self.law.velocity(target, backward=backward)
        if not self.trajectory_free(target, backward, docking):
            raise FailedToControl("Failed to get control")
        return cmd

    def trajectory_free(self, target: Pose2D, backward: bool, docking: bool) -> bool:
        if self.collides is None:
            return True
        p = self.params
        step, steps = p.simulation_time_step, math.ceil(p.projection_time / p.simulation_time_step)
        pose, checked = Pose2D(), []
        for _ in range(max(1, steps - 1)):
            pose = self.law.next_pose(step, target, pose, backward)
            to_target = math.hypot(target.x - pose.x, target.y - pose.y)
            away = to_target if docking else math.hypot(pose.x, pose.y)
            if away > p.dock_collision_threshold:
                checked.append(pose)
            if to_target <= 1e-2:
                break
        return not (checked and self.collides(checked))

    def rotate(self, angle_to_go: float, angular_now: float, dt: float) -> Velocity:
        return Velocity(0.0, rotate_to_heading(self.params.rotate, angle_to_go, angular_now, dt))
