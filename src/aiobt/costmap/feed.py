"""The robot's pose and lidar, read while a server (the planner, the route server) has
requests to serve, into its global costmap (:class:`~aiobt.costmap.world.FedCostmap`).

The pose in ``map`` is the odometry composed with localization's correction on
``{ns}/tf`` (:class:`~aiobt.geometry.map_pose.MapPose`, as Nav2's costmap looks the
robot up in TF), or ``{ns}/pose`` until a pose is composed with a correction (a robot
with its own localization).

At a sim speed-up of 10 the robot sends 500 odometry messages and 100 scans a wall
second; a planner with nothing to plan has no use for them. A request that needs the
robot (a plan, a smoothing, ``is_path_valid``, ``get_costs``, a clearing around the
robot) attaches them if detached, waits (bounded by ``timeout`` wall s) for a first
pose and a first scan, takes the newest of each, then runs; while attached, requests
read the costmap as the periodic folds left it (:class:`FedCostmap`) and wait for
nothing. The streams stay ``linger`` robot s after the last request (a navigator
replans every second or so, so they stay while it navigates).

Attached, the streams are read, not handed over: Zenoh's thread keeps the newest
scan and the last odometry messages (``bus.latest``), and the planner looks every
``poll`` wall s whether a scan is due for folding (Nav2's global costmap updates at
1 Hz); it decodes that scan and composes the pose stamped nearest it, nothing else.
A request takes the newest pose, and folds only the first scan after attaching.
Handing every message to the event loop cost about a third of the planner's CPU
while driving at 10x (a loop wake-up and a decode for each of 600 a wall second).

What is lost: scans seen while nobody asked (the robot driven by something else:
teleoperation, a controller goal with no planning) are not marked in the global
costmap; the first request after that sees only the scan from where the robot is now.
"""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator, Awaitable, Callable
from typing import Any, TypeVar

from aiobt.core.clock import Clock
from aiobt.costmap.world import POSES_KEPT, FedCostmap
from aiobt.geometry.map_pose import MapPose
from aiobt.msgs import LaserScan
from aiobt.transport import Bus, Latest
from aiobt.transport.on_demand import LINGER, OnDemand

Req = TypeVar("Req")
Resp = TypeVar("Resp")
R = TypeVar("R")
FEED_TIMEOUT = 1.0  # wall s a request after idle waits for a pose and a scan
POLL = 0.05  # wall s between two looks for a scan due (a 1 Hz fold is 0.1 wall s at 10x)


class RobotFeed:
    """Pose and scan into ``world`` while requests come (see the module's docstring)."""

    def __init__(
        self,
        bus: Bus,
        world: FedCostmap,
        clock: Clock,
        *,
        timeout: float = FEED_TIMEOUT,
        linger: float = LINGER,
        poll: float = POLL,
    ) -> None:
        if not timeout > 0.0:
            raise ValueError(f"robot feed: timeout must be > 0 wall s, got {timeout!r}")
        if not poll > 0.0:
            raise ValueError(f"robot feed: poll must be > 0 wall s, got {poll!r}")
        self._bus = bus
        self._world = world
        self._timeout = timeout
        self._poll = poll
        self._poses: MapPose | None = None
        self._scan: Latest[LaserScan] | None = None
        self._pose_read: object = None
        self._poller: asyncio.Task[None] | None = None
        self.on_demand = OnDemand(
            self._attach, world.forget, clock, linger=linger, wait_on_attach_only=True,
            released=self._stop_polling,
        )  # fmt: skip

    def _attach(self) -> list[MapPose | Latest[Any]]:
        # at 10x 500 odometry messages a wall second: the last POSES_KEPT, to mark each
        # scan from the pose at its stamp
        self._poses = MapPose.read(self._bus, keep=POSES_KEPT)
        self._scan = self._bus.latest("scan", LaserScan)
        self._pose_read = None
        self._poller = asyncio.ensure_future(self._polling())
        return [self._poses, self._scan]

    def _stop_polling(self) -> None:
        if self._poller is not None:
            self._poller.cancel()
            self._poller = None

    async def _polling(self) -> None:
        while True:
            await asyncio.sleep(self._poll)  # wall time: how often Zenoh's buffers are read
            self.read()

    def read(self, *, fold: bool = True) -> None:
        """Take the newest pose and, if ``fold``, the newest scan if it is due for folding
        (marked from the pose stamped nearest it; a scan newer than every pose waits for
        its pose, unless it is the first since attaching)."""
        poses, scans, world = self._poses, self._scan, self._world
        if poses is None or scans is None or (newest := poses.get()) is None:
            return
        if newest is not self._pose_read:
            self._pose_read = newest
            world.on_pose(newest)
        scan = scans.get() if fold else None
        if scan is None or not world.scan_due(stamp := scan.header.stamp):
            return
        if not world.waits_for_pose(stamp, newest.header.stamp):  # else: the next look
            world.take_scan(scan, poses.newest_first())

    @contextlib.asynccontextmanager
    async def fresh(self) -> AsyncIterator[bool]:
        """Within: the robot's streams attached, the newest pose taken and, after
        attaching, the first scan folded in (True if a pose and a scan came within the
        timeout). Later scans are folded by the periodic look, never on a request's
        path: a request reads the costmap as the last fold left it, as Nav2's does."""
        async with self.on_demand.active(self._timeout) as came:
            self.read(fold=not self._world.folded_since_forget)
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
        self._stop_polling()
