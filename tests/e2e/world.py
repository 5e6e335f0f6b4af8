"""What the scenarios do to the world and ask of the navigator.

:class:`World` resets the robot, spawns/moves/removes obstacles (the robot
service's ``{ns}/sim/srv/obstacles/...``, the simulation's own) and sends navigation
goals, recording their feedback. The office world: a corridor at y 8.5..11, three rooms
south (doors on y 8.5 at x 3.5, 10, 16.5), an open plan and a room north; start
(2.0, 9.75, 0).
"""

from __future__ import annotations

import asyncio
import contextlib
import math

from aiobt.msgs import (
    BackUp,
    ClearCostmapResponse,
    ClearEntireCostmap,
    ComputePathThroughPoses,
    ComputePathToPose,
    DriveOnHeading,
    Empty,
    FollowPath,
    LaserScan,
    NavigateThroughPoses,
    NavigateToPose,
    PoseStamped,
    SmoothPath,
    Spin,
    Wait,
)
from aiobt.msgs.sim import (
    Ack,
    MoveObstacle,
    ObstacleList,
    ObstacleMotion,
    ObstacleState,
    RemoveObstacle,
    SpawnObstacle,
)
from aiobt.testing.localize import set_estimate
from aiobt.testing.navwatch import Navigation, RobotTrack, Running, navigate, start_navigation
from aiobt.transport import ActionError, Bus, ServiceError
from aiobt.transport.keys import SIM_POSE, sim_namespace

START = (2.0, 9.75, 0.0)
Request = SpawnObstacle | MoveObstacle | RemoveObstacle
NAVIGATORS = (NavigateToPose.name, NavigateThroughPoses.name)
ACTIONS = (
    NavigateToPose,
    NavigateThroughPoses,
    ComputePathToPose,
    ComputePathThroughPoses,
    FollowPath,
    SmoothPath,
    Spin,
    BackUp,
    DriveOnHeading,
    Wait,
)
ARRIVED = 0.3  # m: the goal checker's 0.25 plus the last pose's lag (both on {ns}/pose, the
# localization's estimate: the stack navigates on it)
YAW_TOLERANCE = 0.3  # rad: the goal checker's 0.25 plus the last pose's lag


class World:
    """The robot service's controls and the navigator's clients, for one test."""

    def __init__(self, bus: Bus, track: RobotTrack) -> None:
        self.bus = bus
        self.sim = sim_namespace(bus.namespace)  # the simulation's services
        self.track = track
        self.truth = bus.latest(SIM_POSE, PoseStamped)  # the sim's truth: for failure reports only
        self.to_pose = bus.action_client(NavigateToPose.name, NavigateToPose)
        self.through = bus.action_client(NavigateThroughPoses.name, NavigateThroughPoses)

    async def _ack(self, service: str, request: Request) -> str:
        ack = await self.bus.call(f"obstacles/{service}", request, Ack, 10.0, namespace=self.sim)
        assert ack.ok, f"sim/srv/obstacles/{service} {request}: {ack.message}"
        return ack.id

    async def _obstacles(self) -> ObstacleList:
        return await self.bus.call(
            "obstacles/list", Empty(), ObstacleList, timeout=10.0, namespace=self.sim
        )

    async def spawn(self, x: float, y: float, **shape: float | str) -> str:
        """A box (default 0.5 x 0.5 x 1 m) at (x, y); returns its id."""
        return await self._ack("spawn", SpawnObstacle(x=x, y=y, **shape))

    async def move(
        self, oid: str, x: float, y: float, motion: tuple[float, float, float] | None = None
    ) -> None:
        """Move obstacle ``oid`` to (x, y); ``motion`` (to_x, to_y, speed): back and forth."""
        moving = ObstacleMotion(to_x=motion[0], to_y=motion[1], speed=motion[2]) if motion else None
        await self._ack("move", MoveObstacle(id=oid, x=x, y=y, motion=moving))

    async def remove(self, oid: str) -> None:
        await self._ack("remove", RemoveObstacle(id=oid))

    async def obstacle(self, oid: str) -> ObstacleState:
        """Where obstacle ``oid`` is now."""
        listing = await self._obstacles()
        found = [o for o in listing.obstacles if o.id == oid]
        assert found, f"no obstacle {oid!r}: {listing}"
        return found[0]

    async def clear(self) -> None:
        """No goal on any navigator, no obstacle (nor its mark in a costmap), the robot
        standing at the start."""
        for client in (self.to_pose, self.through):
            with contextlib.suppress(ServiceError, ActionError, TimeoutError):
                await client.cancel_all(timeout=5.0)
        listing = await self._obstacles()
        for obstacle in listing.obstacles:
            await self.remove(obstacle.id)
        await self.teleport(*START)
        self.track.restart()

    async def teleport(self, x: float, y: float, yaw: float) -> None:
        """The robot carried to (x, y, yaw) through the simulation; localization told, as
        a user would (initialpose); then the costmaps cleared: no mark of a removed
        obstacle, nor of a scan laid on the old pose while localization had not yet taken
        the new one."""
        ack = await self.bus.call("reset_pose", PoseStamped.from_xy_yaw(x, y, yaw), Ack,
                                  timeout=10.0, namespace=self.sim)  # fmt: skip
        assert ack.ok, f"sim/srv/reset_pose: {ack.message}"
        estimate = await set_estimate(self.bus, x, y, yaw)
        await self._settled_after(estimate.header.stamp)
        for costmap in ("global_costmap", "local_costmap"):
            name = ClearEntireCostmap.service_name(costmap)
            cleared = await self.bus.call(
                name, ClearEntireCostmap.Request(), ClearCostmapResponse, timeout=30.0
            )
            assert cleared.success, f"{name}: {cleared.message}"
        there = await self.track.wait_for(lambda s: math.dist((s.x, s.y), (x, y)) < 0.1, 10.0)
        assert there is not None, (
            f"the robot is not at {(x, y)} after reset: {self.track.latest}; {self.whereabouts()}"
        )

    async def _settled_after(self, stamp: float) -> None:
        """Wait for a scan stamped after ``stamp`` (the filter's estimate at the new
        place) and a pose after that scan: from then on the newest scan a costmap folds
        is marked from a pose at the new place, not one from before it."""
        scans = self.bus.subscribe("scan", LaserScan, queue_size=4)
        try:
            async with asyncio.timeout(10.0):
                async for scan in scans:
                    if scan.header.stamp > stamp:
                        break
        except TimeoutError:
            raise AssertionError(f"no scan stamped after {stamp:.2f} within 10 s") from None
        finally:
            scans.close()
        newer = await self.track.wait_for(lambda s: s.stamp > scan.header.stamp, 10.0)
        assert newer is not None, f"no pose after the scan at {scan.header.stamp:.2f}"

    async def navigate(
        self,
        x: float,
        y: float,
        yaw: float = 0.0,
        tree: str = "",
        timeout: float = 90.0,  # noqa: ASYNC109
    ) -> Navigation:
        """NavigateToPose to (x, y, yaw); waits for the end (bounded)."""
        return await navigate(self.to_pose, PoseStamped.from_xy_yaw(x, y, yaw), tree, timeout)

    async def start(self, x: float, y: float, yaw: float = 0.0, tree: str = "") -> Running:
        """Send NavigateToPose to (x, y, yaw) and return at once (``.end(timeout)`` waits)."""
        return await start_navigation(self.to_pose, PoseStamped.from_xy_yaw(x, y, yaw), tree)

    def whereabouts(self) -> str:
        """For a failure: the sim's true pose and the estimated track, a sample every 2 s."""
        truth = self.truth.get()
        true = "none" if truth is None else f"({truth.x:.2f}, {truth.y:.2f}, {truth.yaw:.2f})"
        shown, last = [], -math.inf
        for sample in self.track.samples:
            if sample.stamp - last >= 2.0:
                shown.append(f"{sample.stamp:.1f}:({sample.x:.2f},{sample.y:.2f})")
                last = sample.stamp
        return f"the sim's truth {true}; the estimated track {' '.join(shown)}"

    def assert_at(self, x: float, y: float, yaw: float | None = None) -> None:
        """The robot stands within ARRIVED m (and YAW_TOLERANCE rad) of the pose."""
        here = self.track.latest
        assert here is not None, "no pose from the robot"
        assert math.dist((here.x, here.y), (x, y)) <= ARRIVED, (
            f"at {here}, not ({x}, {y}); {self.whereabouts()}"
        )
        if yaw is not None:
            error = abs((here.yaw - yaw + math.pi) % (2 * math.pi) - math.pi)
            assert error <= YAW_TOLERANCE, (
                f"heading {here.yaw:.2f}, wanted {yaw:.2f}; the last headings "
                f"{' '.join(f'{s.stamp:.2f}:{s.yaw:.3f}' for s in self.track.samples[-40::4])}; "
                f"{self.whereabouts()}"
            )
