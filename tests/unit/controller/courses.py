"""Test courses and a closed-loop driver: session + kinematic unicycle on a fixed dt."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from aiobt.costmap.checker import CollisionChecker
from aiobt.geometry import PlanarPath, Pose2D
from aiobt.robot.state import RobotState
from aiobt_services.controller.session import (
    ControllerConfig,
    FollowPathSession,
    FollowRequest,
    StepResult,
)
from aiobt_services.controller.unicycle import Unicycle

SPACING = 0.05


def polyline(points: list[tuple[float, float]], frame: str = "map") -> PlanarPath:
    """A densely sampled path through ``points`` with yaw along the path."""
    return PlanarPath.through(points, SPACING, frame)


def straight(length: float = 4.0) -> PlanarPath:
    return polyline([(0.0, 0.0), (length, 0.0)])


def curve(radius: float = 2.0, angle: float = math.pi / 2) -> PlanarPath:
    """A straight metre then a left arc of ``radius``."""
    arc = [
        (1.0 + radius * math.sin(a), radius - radius * math.cos(a))
        for a in np.linspace(0, angle, 60)
    ]
    return polyline([(0.0, 0.0), *arc])


def u_turn(leg: float = 3.0, radius: float = 1.0) -> PlanarPath:
    """East ``leg`` m, a left half circle, then back west ``leg`` m."""
    arc = [
        (leg + radius * math.sin(a), radius - radius * math.cos(a))
        for a in np.linspace(0, math.pi, 60)
    ]
    return polyline([(0.0, 0.0), *arc, (0.0, 2 * radius)])


@dataclass
class Run:
    result: StepResult | None = None
    time: float = 0.0
    cross_track: list[float] = field(default_factory=list)
    commands: list[tuple[float, float]] = field(default_factory=list)


def drive(
    path: PlanarPath,
    start: Pose2D | None = None,
    controller_id: str = "FollowPath",
    goal_checker_id: str = "general_goal_checker",
    collision: CollisionChecker | None = None,
    config: ControllerConfig | None = None,
    max_time: float = 60.0,
    robot: Unicycle | None = None,
) -> tuple[Run, Unicycle]:
    cfg = config or ControllerConfig()
    dt = cfg.control_period
    robot = robot or Unicycle(start or Pose2D(0.0, 0.0, 0.0))
    request = FollowRequest(path, controller_id, goal_checker_id, "progress_checker")
    session = FollowPathSession(request, cfg, 0.0, collision)
    run = Run()
    now = 0.0
    while now < max_time:
        state = RobotState(robot.pose, robot.velocity, now)
        step = session.step(now, {path.frame_id: state})
        if step.feedback is not None:
            run.cross_track.append(step.feedback.cross_track_error)
        run.commands.append((step.cmd.v, step.cmd.w))
        if step.finished:
            run.result = step
            break
        robot.step(step.cmd, dt)
        now += dt
    run.time = now
    return run, robot
