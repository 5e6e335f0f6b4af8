"""The robot's pose and lidar, subscribed while the planner has requests to serve.

At a sim speed-up of 10 the robot sends 500 poses and 100 scans a wall second; a
planner with nothing to plan has no use for them. A request that needs the robot
(a plan, a smoothing, ``is_path_valid``, ``get_costs``, a clearing around the
robot) attaches them if detached, waits (bounded by ``timeout`` wall s) for a
fresh pose and a fresh scan, which is folded into the global costmap as it
comes, then runs; while attached, requests read the costmap as the periodic
folds left it (:class:`GlobalCostmap`) and wait for nothing.
The streams stay ``linger`` robot s after the last request (a navigator replans
every second or so, so they stay while it navigates). What is lost: scans seen
while nobody asked (the robot driven by something else: teleoperation, a
controller goal with no planning) are not marked in the global costmap; the
first request after that sees only the scan from where the robot is now.
"""

from __future__ import annotations

import contextlib
from collections.abc import AsyncIterator, Awaitable, Callable
from typing import Any, TypeVar

from aiobt.core.clock import Clock
from aiobt.msgs import LaserScan, PoseStamped
from aiobt.transport import Bus, Subscription
from aiobt.transport.on_demand import LINGER, OnDemand

from .state import POSES_KEPT, GlobalCostmap

Req = TypeVar("Req")
Resp = TypeVar("Resp")
R = TypeVar("R")
FEED_TIMEOUT = 1.0  # wall s a request after idle waits for a pose and a scan


class RobotFeed:
    """Pose and scan into ``world`` while requests come (see the module's docstring)."""

    def __init__(
        self,
        bus: Bus,
        world: GlobalCostmap,
        clock: Clock,
        *,
        timeout: float = FEED_TIMEOUT,
        linger: float = LINGER,
    ) -> None:
        if not timeout > 0.0:
            raise ValueError(f"planner feed: timeout must be > 0 wall s, got {timeout!r}")
        self._bus = bus
        self._world = world
        self._timeout = timeout
        self._scan: Subscription[LaserScan] | None = None
        self.on_demand = OnDemand(
            self._attach, world.forget, clock, linger=linger, wait_on_attach_only=True
        )

    def _attach(self) -> list[Subscription[Any]]:
        world, bus = self._world, self._bus
        self._scan = bus.subscribe("scan", LaserScan, world.on_scan, queue_size=1)
        # at 10x 500 poses a wall second: the last POSES_KEPT, to mark each scan from its own
        poses = bus.subscribe("pose", PoseStamped, world.on_pose, queue_size=POSES_KEPT)
        return [poses, self._scan]

    @contextlib.asynccontextmanager
    async def fresh(self) -> AsyncIterator[bool]:
        """Within: the robot's streams attached and, after attaching, the first scan
        folded in (True if a pose and a scan came within the timeout)."""
        async with self.on_demand.active(self._timeout) as came:
            scan = None if self._scan is None else self._scan.latest
            if scan is not None:
                self._world.on_scan(scan)  # one that came before the pose is taken now
            yield came

    def action(
        self, execute: Callable[[Req, Any], Awaitable[R]]
    ) -> Callable[[Req, Any], Awaitable[R]]:
        """An action's ``execute`` run within :meth:`fresh`."""

        async def fed(goal: Req, handle: Any) -> R:
            async with self.fresh():
                return await execute(goal, handle)

        return fed

    def call(self, handler: Callable[[Req], Resp]) -> Callable[[Req], Awaitable[Resp]]:
        """A service ``handler`` run within :meth:`fresh`."""

        async def fed(request: Req) -> Resp:
            async with self.fresh():
                return handler(request)

        return fed

    def close(self) -> None:
        self.on_demand.detach()
