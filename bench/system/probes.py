"""What bench/system measures from the outside while the stack runs: sim time vs wall,
planner round trips, the first command after a blocking obstacle appears."""

from __future__ import annotations

import asyncio
import math
import random
import time
from collections.abc import Sequence

from aiobt.msgs import Clock, ComputePathToPose, PoseStamped, Twist
from aiobt.transport import ActionError, Bus
from aiobt_services.robot.messages import Ack, RemoveObstacle, SpawnObstacle


class SimClock:
    """The newest ``{ns}/clock`` value and the wall time it arrived."""

    def __init__(self, bus: Bus) -> None:
        self.sim = math.nan
        self.wall = math.nan
        bus.subscribe("clock", Clock, self._on_clock, queue_size=1)

    def _on_clock(self, msg: Clock) -> None:
        self.sim, self.wall = msg.clock, time.monotonic()

    def mark(self) -> tuple[float, float]:
        return (self.sim, time.monotonic())

    def factor_since(self, mark: tuple[float, float]) -> float:
        """Sim seconds per wall second since ``mark``."""
        return (self.sim - mark[0]) / max(time.monotonic() - mark[1], 1e-9)


class PlannerProbe:
    """Sends ComputePathToPose goals one after another (from the robot's pose to one of
    ``goals``), every ``period`` wall seconds; keeps each round trip (wall s).

    The planner serves one goal at a time (a newer one aborts the older, as in Nav2),
    so every request, the probe's and :meth:`plan`'s, holds ``lock``."""

    def __init__(self, bus: Bus, goals: Sequence[tuple[float, float, float]], period: float):
        self.client = bus.action_client(ComputePathToPose.name, ComputePathToPose)
        self.goals = list(goals)
        self.period = period
        self.round_trips: list[float] = []
        self.failures: list[str] = []
        self.pose: PoseStamped | None = None
        self.lock = asyncio.Lock()
        bus.subscribe("pose", PoseStamped, self._on_pose, queue_size=1)

    def _on_pose(self, msg: PoseStamped) -> None:
        self.pose = msg

    async def run(self, stop: asyncio.Event) -> None:
        rng = random.Random(5)
        while not stop.is_set():
            if self.pose is not None:
                await self._once(self.pose, rng.choice(self.goals))
            try:
                await asyncio.wait_for(stop.wait(), self.period)
            except TimeoutError:
                continue

    async def plan(
        self, start: PoseStamped, goal: tuple[float, float, float]
    ) -> tuple[ComputePathToPose.Result, float]:
        """One ComputePathToPose and its round trip (wall s); raises ActionError, TimeoutError."""
        request = ComputePathToPose.Goal(
            goal=PoseStamped.from_xy_yaw(*goal), start=start, use_start=True, planner_id="GridBased"
        )
        async with self.lock:
            began = time.monotonic()
            sent = await self.client.send_goal(request, server_timeout=10.0)
            result = await sent.result(timeout=30.0)
            return result, time.monotonic() - began

    async def _once(self, start: PoseStamped, goal: tuple[float, float, float]) -> None:
        try:
            result, round_trip = await self.plan(start, goal)
        except (ActionError, TimeoutError) as exc:
            self.failures.append(f"{type(exc).__name__}: {exc}")
            return
        self.round_trips.append(round_trip)
        if result.error_code != 0:
            self.failures.append(f"{result.error_code} {result.error_msg}")


class Commands:
    """The robot's ``cmd_vel`` stream: the newest command and an event per command."""

    def __init__(self, bus: Bus) -> None:
        self.latest: Twist | None = None
        self.arrived = asyncio.Event()
        bus.subscribe("cmd_vel", Twist, self._on_cmd)

    def _on_cmd(self, msg: Twist) -> None:
        self.latest = msg
        self.arrived.set()

    async def first(self, holds: object, timeout: float) -> Twist | None:  # noqa: ASYNC109
        """The first command from now on for which ``holds(cmd)`` is true, or None."""
        deadline = time.monotonic() + timeout
        while (left := deadline - time.monotonic()) > 0:
            self.arrived.clear()
            try:
                await asyncio.wait_for(self.arrived.wait(), left)
            except TimeoutError:
                return None
            if self.latest is not None and holds(self.latest):  # type: ignore[operator]
                return self.latest
        return None


class Refused(Exception):
    """The robot service would not put the box there (a wall, the world's edge)."""


async def reaction(
    bus: Bus, clock: SimClock, commands: Commands, pose: PoseStamped, ahead: float
) -> tuple[float, float] | None:
    """Spawn a box ``ahead`` m in front of the driving robot; sim and wall seconds from
    the spawn's acknowledgement to the first cmd_vel at under half the speed commanded
    before it (None: no such command within 10 wall s). The box is removed after.
    Raises :class:`Refused` if the box cannot go there."""
    before = commands.latest
    speed = before.linear.x if before is not None else 0.0
    x = pose.x + ahead * math.cos(pose.yaw)
    y = pose.y + ahead * math.sin(pose.yaw)
    spawn = SpawnObstacle(x=x, y=y, size_x=0.3, size_y=0.8, yaw=pose.yaw)
    ack = await bus.call("obstacles/spawn", spawn, Ack, timeout=10.0)
    if not ack.ok:
        raise Refused(f"obstacles/spawn at ({x:.2f}, {y:.2f}): {ack.message}")
    sim0, wall0 = clock.mark()
    try:
        cmd = await commands.first(lambda c: c.linear.x < 0.5 * speed, 10.0)
        if cmd is None:
            return None
        return (clock.sim - sim0, time.monotonic() - wall0)
    finally:
        await bus.call("obstacles/remove", RemoveObstacle(id=ack.id), Ack, timeout=10.0)


def percentile(values: Sequence[float], q: float) -> float:
    """Nearest-rank percentile (nan for no values)."""
    if not values:
        return math.nan
    ordered = sorted(values)
    return ordered[max(1, math.ceil(q / 100.0 * len(ordered))) - 1]
