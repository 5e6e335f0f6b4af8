"""What bench/system measures from the outside while the stack runs: sim time vs wall,
planner round trips, the first command after a blocking obstacle appears."""

from __future__ import annotations

import asyncio
import contextlib
import math
import random
import time
from collections.abc import AsyncIterator, Callable, Sequence
from typing import Generic, TypeVar

from aiobt.geometry.map_pose import MapPose, Reader
from aiobt.msgs import Clock, ComputePathToPose, Msg, PoseStamped, Twist
from aiobt.msgs.sim import Ack, RemoveObstacle, SpawnObstacle
from aiobt.transport import ActionError, Bus
from aiobt.transport.keys import sim_namespace

M = TypeVar("M", bound=Msg)


class Newest(Generic[M]):
    """A topic's newest message, for the instrument: subscribed (``bus.latest``, whose
    arrivals never wake the loop) only while :meth:`held` or for one :meth:`read`, so
    the 1,000 clock stamps and 500 poses a wall second at 10x cost the machine it
    measures nothing between the instrument's looks (its process, the router).
    ``opener``: what reads it, if not ``bus.latest(name, model)``."""

    def __init__(
        self,
        bus: Bus,
        name: str,
        model: type[M],
        poll: float = 0.002,
        opener: Callable[[], Reader[M]] | None = None,
    ) -> None:
        self._name, self._poll = name, poll
        self._opener: Callable[[], Reader[M]] = opener or (lambda: bus.latest(name, model))
        self._open: Reader[M] | None = None
        self._holds = 0

    @contextlib.asynccontextmanager
    async def held(self) -> AsyncIterator[None]:
        """Subscribed within (:meth:`peek` answers the newest)."""
        if self._open is None:
            self._open = self._opener()
        self._holds += 1
        try:
            yield
        finally:
            self._holds -= 1
            if self._holds == 0 and self._open is not None:
                self._open.close()
                self._open = None

    def peek(self) -> M | None:
        """The newest message so far (None when not held or none came yet)."""
        return None if self._open is None else self._open.get()

    async def wait_for(
        self,
        predicate: Callable[[M], bool],
        timeout: float,  # noqa: ASYNC109
    ) -> M | None:
        """The first message read (every ``poll`` wall s; subscribed meanwhile) that
        satisfies ``predicate``; None on timeout."""
        with contextlib.suppress(TimeoutError):
            async with self.held(), asyncio.timeout(timeout):
                while (message := self.peek()) is None or not predicate(message):  # noqa: ASYNC110
                    await asyncio.sleep(self._poll)
                return message
        return None

    async def read(self, timeout: float = 5.0) -> M:  # noqa: ASYNC109
        """The newest message (subscribing for it if not held); TimeoutError if none came."""
        message = await self.wait_for(lambda _: True, timeout)
        if message is None:
            raise TimeoutError(f"no {self._name} message within {timeout} s")
        return message


class SimClock(Newest[Clock]):
    """The robot's time on ``{ns}/clock`` (see :class:`Newest`)."""

    def __init__(self, bus: Bus) -> None:
        super().__init__(bus, "clock", Clock)

    @property
    def sim(self) -> float:
        """Sim time now, while :meth:`held` (nan otherwise)."""
        stamp = self.peek()
        return math.nan if stamp is None else stamp.clock

    async def mark(self) -> tuple[float, float]:
        return ((await self.read()).clock, time.monotonic())

    async def factor_since(self, mark: tuple[float, float]) -> float:
        """Sim seconds per wall second since ``mark``."""
        now = await self.mark()
        return (now[0] - mark[0]) / max(now[1] - mark[1], 1e-9)


class RobotPose(Newest[PoseStamped]):
    """The robot's newest pose in ``map`` (see :class:`Newest`) as the stack's services
    read it (:class:`~aiobt.geometry.map_pose.MapPose`: the odometry composed with
    localization's correction, ``{ns}/pose`` only until one comes), and a wait for it
    to stand still."""

    def __init__(self, bus: Bus, poll: float = 0.02) -> None:
        super().__init__(bus, "pose", PoseStamped, poll, lambda: MapPose.read(bus))

    async def wait_still(self, seconds: float, timeout: float, tolerance: float = 0.01) -> bool:  # noqa: ASYNC109
        """True once the robot moved less than ``tolerance`` m over ``seconds`` of sim time."""
        anchor: list[PoseStamped] = []

        def settled(pose: PoseStamped) -> bool:
            if not anchor or math.hypot(pose.x - anchor[0].x, pose.y - anchor[0].y) > tolerance:
                anchor[:] = [pose]
            return pose.header.stamp - anchor[0].header.stamp >= seconds

        return await self.wait_for(settled, timeout) is not None


class PlannerProbe:
    """Sends ComputePathToPose goals one after another (from the robot's pose to one of
    ``goals``), every ``period`` wall seconds; keeps each round trip (wall s) and each
    plan's ``planning_time`` (the planner's own wall time from taking the goal to its
    result: the rest of the round trip is the way there and back).

    The planner serves one goal at a time (a newer one aborts the older, as in Nav2),
    so every request, the probe's and :meth:`plan`'s, holds ``lock``."""

    def __init__(
        self,
        bus: Bus,
        robot: RobotPose,
        goals: Sequence[tuple[float, float, float]],
        period: float,
    ) -> None:
        self.client = bus.action_client(ComputePathToPose.name, ComputePathToPose)
        self.robot = robot
        self.goals = list(goals)
        self.period = period
        self.round_trips: list[float] = []
        self.planning_times: list[float] = []
        self.failures: list[str] = []
        self.lock = asyncio.Lock()

    async def run(self, stop: asyncio.Event) -> None:
        rng = random.Random(5)
        while not stop.is_set():
            await self._once(await self.robot.read(), rng.choice(self.goals))
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
        else:
            self.planning_times.append(result.planning_time)


class Commands:
    """The robot's ``cmd_vel`` stream: the newest command and an event per command
    (subscribed only while :meth:`close` is not called: the reactions, not the driving
    phase, so the instrument does not load the stack it measures)."""

    def __init__(self, bus: Bus) -> None:
        self.latest: Twist | None = None
        self.arrived = asyncio.Event()
        self._sub = bus.subscribe("cmd_vel", Twist, self._on_cmd)

    def close(self) -> None:
        self._sub.close()

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
    sim = sim_namespace(bus.namespace)  # the simulation's services
    async with clock.held():
        await clock.read()  # subscribed, a stamp in: the spawn's time is read at once
        ack = await bus.call("obstacles/spawn", spawn, Ack, timeout=10.0, namespace=sim)
        if not ack.ok:
            raise Refused(f"sim/srv/obstacles/spawn at ({x:.2f}, {y:.2f}): {ack.message}")
        sim0, wall0 = clock.sim, time.monotonic()
        try:
            cmd = await commands.first(lambda c: c.linear.x < 0.5 * speed, 10.0)
            if cmd is None:
                return None
            return (clock.sim - sim0, time.monotonic() - wall0)
        finally:
            remove = RemoveObstacle(id=ack.id)
            await bus.call("obstacles/remove", remove, Ack, timeout=10.0, namespace=sim)


def percentile(values: Sequence[float], q: float) -> float:
    """Nearest-rank percentile (nan for no values)."""
    if not values:
        return math.nan
    ordered = sorted(values)
    return ordered[max(1, math.ceil(q / 100.0 * len(ordered))) - 1]
