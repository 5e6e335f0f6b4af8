"""The safety chain's processes and what the tests watch of them.

``start_chain`` runs the robot (small world), and on its sim time the velocity
smoother, the collision monitor and the controller (commanding ``cmd_vel_nav``, its
local costmap's obstacle layer off), each optional, the smoother and the monitor
separate or composed in one process. :class:`Trace` records, from the
robot, the true pose (``pose``: no pose noise is configured, so it is the sim's truth),
odometry and the sim clock, and from the monitor its states.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import pytest
import yaml

from aiobt.msgs import Clock, Odometry, PoseStamped, Twist
from aiobt.msgs.safety import CollisionMonitorState
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings
from aiobt_services.collision_monitor.main import DEFAULT_PARAMS
from tests.integration.services import TRUTH

Spawn = Callable[[Sequence[str]], ServiceProcess]
ROBOT_RADIUS = 0.22
START = ("--start", "-1.8", "0", "0")
EXACT_ODOMETRY = ("--odom-noise", "0", "--slip", "0")  # the smoother's ramp is read from it


def monitor_params(tmp: Path, change: Callable[[dict[str, Any]], None]) -> str:
    """The shipped default parameters with ``change`` applied, as a file; its path."""
    config = yaml.safe_load(DEFAULT_PARAMS.read_text())
    change(config["collision_monitor"]["ros__parameters"])
    path = tmp / "collision_monitor.yaml"
    path.write_text(yaml.safe_dump(config))
    return str(path)


async def start_chain(
    spawn: Spawn,
    bus: Bus,
    settings: BusSettings,
    *,
    speed: str = "4",
    smoother: Sequence[str] | None = (),
    monitor: Sequence[str] | None = (),
    controller: Sequence[str] | None = (),
    composed: bool = False,
) -> dict[str, ServiceProcess]:
    """The processes (a part given as None is not started), once each is up;
    ``composed``: the smoother and the monitor as one ``aiobt safety_chain`` process
    (Nav2's composition), each with its flags as given."""
    common = ["--connect", settings.connect[0], "--namespace", settings.namespace]
    robot = ["-m", "aiobt_services.robot", "--world", "small", "--speed", speed, *START,
             *EXACT_ODOMETRY, *TRUTH]  # fmt: skip
    procs = {"robot": spawn([*robot, *common])}
    parts = {"velocity_smoother": smoother, "collision_monitor": monitor, "controller": controller}
    tokens = {"robot": ["robot"]}
    if composed:
        assert smoother is not None, "the smoother is composed"
        assert monitor is not None, "the monitor is composed"
        parts = {"safety_chain": [*smoother, *monitor], "controller": controller}
        tokens["safety_chain"] = ["velocity_smoother", "collision_monitor"]
    for name, extra in parts.items():
        if extra is not None:
            chain = ["--cmd-vel-topic", "cmd_vel_nav", "--no-obstacle-layer"]
            flags = chain if name == "controller" else []
            program = (
                ["aiobt.cli.main", name] if name == "safety_chain" else [f"aiobt_services.{name}"]
            )
            procs[name] = spawn(["-m", *program, "--sim-time", *common, *flags, *extra])
    for name, proc in procs.items():
        for token in tokens.get(name, [name]):
            if not await bus.presence(bus.keys.topic(f"nodes/{token}")).wait(60.0):
                pytest.fail(f"{token} ({name}) did not come up:\n{proc.output()}")
    return procs


class Trace:
    """Poses, odometry, monitor states and base commands, stamped on the sim clock."""

    def __init__(self, bus: Bus, command_key: str = "cmd_vel") -> None:
        self.poses: list[PoseStamped] = []
        self.odom: list[Odometry] = []
        self.states: list[CollisionMonitorState] = []
        self.commands: list[tuple[float, Twist]] = []  # (sim time at arrival, command)
        self.now = 0.0
        self._changed = asyncio.Event()
        bus.subscribe("pose", PoseStamped, self._on(self.poses))
        bus.subscribe("odom", Odometry, self._on(self.odom))
        bus.subscribe("collision_monitor/state", CollisionMonitorState, self._on(self.states),
                      latched=True)  # fmt: skip
        bus.subscribe(command_key, Twist, lambda m: self._note(self.commands, (self.now, m)))
        bus.subscribe("clock", Clock, self._on_clock)

    def _on(self, into: list[Any]) -> Callable[[Any], None]:
        return lambda msg: self._note(into, msg)

    def _note(self, into: list[Any], item: Any) -> None:
        into.append(item)
        self._changed.set()

    def _on_clock(self, msg: Clock) -> None:
        self.now = max(self.now, msg.clock)

    @property
    def speed(self) -> float:
        return self.odom[-1].twist.linear.x if self.odom else 0.0

    async def until(self, holds: Callable[[], bool], timeout: float, what: str) -> None:  # noqa: ASYNC109
        """Wait (``timeout`` wall s at most) for ``holds()``; fail naming ``what``."""
        try:
            async with asyncio.timeout(timeout):
                while not holds():
                    self._changed.clear()
                    await self._changed.wait()
        except TimeoutError:
            pytest.fail(f"no {what} within {timeout} s (states: {self.actions()})")

    def actions(self) -> list[str]:
        return [f"{s.action}:{s.polygon_name}" for s in self.states]

    def still_since(self, seconds: float) -> bool:
        """The base has reported no motion for ``seconds`` of sim time."""
        if not self.odom or abs(self.speed) > 1e-3:
            return False
        moving = [o.header.stamp for o in self.odom if abs(o.twist.linear.x) > 1e-3]
        return not moving or self.odom[-1].header.stamp - moving[-1] >= seconds
