"""Shared by the controller/behaviors service tests: start robot + service, paths, poses."""

from __future__ import annotations

import math
import os
import signal
from collections.abc import Callable, Sequence
from typing import Any, TypeVar

import pytest

from aiobt.geometry import PlanarPath
from aiobt.msgs import ActionResult, Path, PoseStamped
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings, ClientGoal
from tests.integration.services import TRUTH

R = TypeVar("R", bound=ActionResult)

Spawn = Callable[[Sequence[str]], ServiceProcess]
SPEED = "4"


# the controller's and behaviours' own accuracy, measured against the truth (``{ns}/pose``):
# the robot's odometry without its default error (slip, turn scale, noise), which a spin or a
# drive measured by odometry would add (the robot's and localization's tests cover it)
EXACT_ODOMETRY = ("--odom-noise", "0", "--slip", "0", "--odom-turn-scale", "0")


async def start(
    spawn: Spawn,
    bus: Bus,
    settings: BusSettings,
    service: str,
    *extra: str,
    world: str = "small",
    speed: str = SPEED,
    robot_args: Sequence[str] = EXACT_ODOMETRY,
    sim_time: bool = True,
) -> ServiceProcess:
    """The robot (``world``, ``speed``) and one of our services on sim time (or on the wall
    clock: ``sim_time=False``); returns the robot."""
    common = ["--connect", settings.connect[0], "--namespace", settings.namespace]
    robot = spawn(
        [
            "-m",
            "aiobt_services.robot",
            "--world",
            world,
            "--speed",
            speed,
            *TRUTH,
            *robot_args,
            *common,
        ]
    )
    clock = ["--sim-time"] if sim_time else []
    ours = spawn(["-m", f"aiobt_services.{service}", *clock, *common, *extra])
    for name, proc in (("robot", robot), (service, ours)):
        if not await bus.presence(bus.keys.topic(f"nodes/{name}")).wait(30.0):
            pytest.fail(f"{name} did not come up:\n{proc.output()}")
    return robot


def path_through(points: Sequence[tuple[float, float]], spacing: float = 0.05) -> Path:
    """A dense map-frame path through ``points``, yaw along the path."""
    planar = PlanarPath.through(points, spacing)
    poses = [
        PoseStamped.from_xy_yaw(float(x), float(y), float(a))
        for (x, y), a in zip(planar.xy, planar.yaw, strict=True)
    ]
    return Path(poses=poses)


def yaw_error(a: float, b: float) -> float:
    return abs((a - b + math.pi) % (2 * math.pi) - math.pi)


async def result_while_frozen(robot: ServiceProcess, goal: ClientGoal[Any, R, Any]) -> R:
    """SIGSTOP the robot process, wait (10 s at most) for ``goal``'s result, SIGCONT it."""
    os.kill(robot.pid, signal.SIGSTOP)
    try:
        return await goal.result(timeout=10.0)
    finally:
        os.kill(robot.pid, signal.SIGCONT)
