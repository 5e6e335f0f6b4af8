"""What the docking and undocking procedures share: the robot's frames, robot time,
the base command, the controller, and the control loops toward a pose and a heading
(Nav2's ``getCommandToPose`` and ``rotateToDock``)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from aiobt.core.clock import Clock
from aiobt.geometry import Pose2D, Velocity, wrap_angle

from .controller import DockController
from .errors import FailedToControl
from .frames import RobotFrames
from .params import DockingParams

STOP = Velocity(0.0, 0.0)


def l2_norm(a: Pose2D, b: Pose2D) -> float:
    """Nav2's ``utils::l2Norm``: distance in x, y and heading together."""
    return math.sqrt((a.x - b.x) ** 2 + (a.y - b.y) ** 2 + wrap_angle(b.yaw - a.yaw) ** 2)


@dataclass(slots=True)
class Motion:
    params: DockingParams
    controller: DockController
    frames: RobotFrames
    clock: Clock
    drive: Callable[[Velocity], None]  # publishes cmd_vel
    turn_rate: Callable[[], float]  # the odometry's angular velocity
    refresh: Callable[[], None] = lambda: None  # takes the newest scan into the costmap

    def stop(self) -> None:
        self.drive(STOP)

    async def tick(self) -> None:
        await self.clock.sleep(self.params.period)

    def command_to_pose(self, pose: Pose2D, frame: str, linear_tolerance: float,
                        angular_tolerance: float, backward: bool) -> Velocity | None:  # fmt: skip
        """The command toward ``pose`` (in ``frame``), None once within the tolerances."""
        robot = self.frames.robot(frame)
        near = math.hypot(robot.x - pose.x, robot.y - pose.y) < linear_tolerance
        if near and abs(wrap_angle(pose.yaw - robot.yaw)) < angular_tolerance:
            return None
        target = self.frames.transform(pose, frame, "base_link")
        self.refresh()
        return self.controller.command(target, backward, docking=False)

    async def rotate_to(self, heading: float, frame: str) -> None:
        """Turn in place to ``heading`` in ``frame`` (Nav2's rotateToDock)."""
        began, p = self.clock.now(), self.params
        while True:
            to_go = wrap_angle(heading - self.frames.robot(frame).yaw)
            if abs(to_go) < p.rotation_angular_tolerance:
                return
            self.drive(self.controller.rotate(to_go, self.turn_rate(), p.period))
            if self.clock.now() - began > p.rotate_to_dock_timeout:
                raise FailedToControl("Timed out rotating to dock")
            await self.tick()
