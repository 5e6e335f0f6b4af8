"""The navigator on the bus: action servers, the goal topic, robot state, the status stream.

A thin layer around :class:`~aiobt_services.navigator.navigator.Navigator`: it turns
action goals into :class:`NavRequest`s, publishes the feedback the navigator
makes, feeds it the map and the robot's pose and speed, and publishes the tree
status stream. Goals published on ``{ns}/goal_pose`` are sent to its own
``navigate_to_pose`` server, as Nav2's bt_navigator does.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from typing import Any

from aiobt.core.clock import Clock
from aiobt.geometry.map_pose import MapPose
from aiobt.msgs import (
    ActionResult,
    BtSnapshot,
    BtTransitions,
    BtTree,
    Msg,
    NavigateThroughPoses,
    NavigateToPose,
    OccupancyGrid,
    PoseStamped,
)
from aiobt.nav.context import NavContext
from aiobt.nav.robot_state import ODOM, POSE, robot_state
from aiobt.transport import Bus, Latest
from aiobt.transport.actions.goals import GoalHandle
from aiobt.transport.on_demand import OnDemand
from aiobt.transport.simtime import FRESH_TIMEOUT, clock_held
from aiobt_services.navigator.goals import (
    GLOBAL_FRAME,
    NAVIGATE_THROUGH_POSES,
    NAVIGATE_TO_POSE,
    MapBounds,
    NavRequest,
)
from aiobt_services.navigator.navigator import Navigator

log = logging.getLogger("aiobt_services.navigator.service")
SELF_GOAL_TIMEOUT = 2.0  # s for the navigator's own server to take a goal_pose goal
SNAPSHOT_POLL = 0.25  # wall s between looks for a bt/snapshot watcher while idle


def to_request(action: str, goal_id: str, goal: Any) -> NavRequest:
    """A goal of either action as a :class:`NavRequest`."""
    poses = tuple(goal.poses.goals) if action == NAVIGATE_THROUGH_POSES else (goal.pose,)
    return NavRequest(action, goal_id, poses, goal.behavior_tree)


class NavRobotState:
    """The robot as the navigator sees it, from the Nav2 nodes' shared robot state
    (one subscription per key in the process): map pose, smoothed speed."""

    def __init__(self, nav: NavContext, clock: Clock, pose_timeout: float) -> None:
        self._robot = robot_state(nav, "navigator")
        self._robot.prepare(POSE, ODOM)
        self._attached = asyncio.Event()
        self._robot.topics.pause()  # the robot's streams only while a navigation runs
        self._feed = OnDemand(self._attach, lambda: None, clock, released=self._released)
        self._pose_timeout = pose_timeout

    def _attach(self) -> list[MapPose | Latest[Any]]:
        readers = self._robot.topics.resume()  # paused: nothing from before is kept
        self._attached.set()
        return [self._robot.read_again(), readers[ODOM]]

    def _released(self) -> None:
        self._attached.clear()
        self._robot.topics.pause()

    def active(self) -> contextlib.AbstractAsyncContextManager[bool]:
        """The robot's streams subscribed around a navigation (a fresh pose and
        odometry waited for, bounded by ``pose_timeout``), let go after it."""
        return self._feed.active(self._pose_timeout)

    def current_pose(self) -> PoseStamped | None:
        return self._robot.pose_in(GLOBAL_FRAME)

    async def wait_for_pose(self, timeout: float) -> bool:  # noqa: ASYNC109
        if self.current_pose() is not None:
            return True
        try:
            async with asyncio.timeout(timeout):  # not wait_for: see Navigation._wait
                await self._attached.wait()  # the streams are read while a navigation runs
                await self._robot.map_pose.wait_latest()
        except TimeoutError:  # also: let go again meanwhile (nothing more is read)
            return False
        return self.current_pose() is not None

    def linear_speed(self) -> float:
        return self._robot.speed() or 0.0


class BusStatusSink:
    """The tree status stream's publishers: ``bt/tree`` (latched), ``bt/transitions``,
    ``bt/snapshot``."""

    def __init__(self, bus: Bus) -> None:
        self._tree = bus.latched_publisher("bt/tree", BtTree)
        self._transitions = bus.publisher("bt/transitions", BtTransitions, reliable=True)
        self._snapshot = bus.publisher("bt/snapshot", BtSnapshot, reliable=True)

    def tree(self, message: BtTree) -> None:
        self._tree.put(message)

    def transitions(self, message: BtTransitions) -> None:
        self._transitions.put(message)

    def snapshot(self, message: BtSnapshot) -> None:
        self._snapshot.put(message)

    @property
    def watched(self) -> bool:
        """Whether anybody subscribes to ``bt/snapshot``."""
        return self._snapshot.matched


class _HandleChannel:
    """A navigation's view of its action goal handle."""

    def __init__(self, action: str, handle: GoalHandle[Any, Any, Any]) -> None:
        self.action = action
        self.handle = handle

    def take_new_request(self) -> NavRequest | None:
        goal = self.handle.take_new_goal()
        if goal is None:
            return None
        return to_request(self.action, self.handle.goal_id, goal)

    def publish_feedback(self, feedback: Msg) -> None:
        self.handle.publish_feedback(feedback)


class NavigatorService:
    """Serves ``navigate_to_pose`` and ``navigate_through_poses`` on ``bus``."""

    def __init__(
        self, bus: Bus, navigator: Navigator, clock: Clock, robot: NavRobotState | None = None
    ) -> None:
        self.bus = bus
        self.navigator = navigator
        self.clock = clock
        self.robot = robot  # its streams subscribed while a goal runs
        self._tasks: set[asyncio.Task[None]] = set()

    def start(self, snapshot_period: float) -> None:
        bus, clock = self.bus, self.clock
        bus.action_server(
            NAVIGATE_TO_POSE,
            NavigateToPose,
            self._execute_to_pose,
            preemption="replace",
            clock=clock,
        )
        bus.action_server(
            NAVIGATE_THROUGH_POSES,
            NavigateThroughPoses,
            self._execute_through_poses,
            preemption="replace",
            clock=clock,
        )
        self._self_client = bus.action_client(NAVIGATE_TO_POSE, NavigateToPose)
        bus.subscribe("map", OccupancyGrid, self._on_map, latched=True, queue_size=1)
        bus.subscribe("goal_pose", PoseStamped, self._on_goal_pose, queue_size=10)
        self._spawn(self._publish_snapshots(snapshot_period))

    def _spawn(self, work: Any) -> None:
        task = asyncio.ensure_future(work)
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)

    async def aclose(self) -> None:
        """Halt the running navigation (before the bus closes: its leaves cancel their
        goals on the servers), then stop the snapshots."""
        await self.navigator.shutdown("navigator shutting down")
        for task in list(self._tasks):
            task.cancel()
        await asyncio.gather(*self._tasks, return_exceptions=True)

    # -- actions ---------------------------------------------------------------------------
    async def _execute_to_pose(self, goal: Any, handle: GoalHandle[Any, Any, Any]) -> ActionResult:
        return await self._execute(NAVIGATE_TO_POSE, goal, handle)

    async def _execute_through_poses(
        self, goal: Any, handle: GoalHandle[Any, Any, Any]
    ) -> ActionResult:
        return await self._execute(NAVIGATE_THROUGH_POSES, goal, handle)

    async def _execute(
        self, action: str, goal: Any, handle: GoalHandle[Any, Any, Any]
    ) -> ActionResult:
        request = to_request(action, handle.goal_id, goal)
        log.info("%s goal %s accepted", action, request.goal_id)
        if self.robot is None:
            return await self.navigator.navigate(request, _HandleChannel(action, handle))
        async with self.robot.active():
            return await self.navigator.navigate(request, _HandleChannel(action, handle))

    # -- topics ----------------------------------------------------------------------------
    def _on_map(self, grid: OccupancyGrid) -> None:
        bounds = MapBounds.of(grid)
        if bounds != self.navigator.map_bounds:
            log.info("map received: goals must lie in %s", bounds)
        self.navigator.map_bounds = bounds

    def _on_goal_pose(self, pose: PoseStamped) -> None:
        position = pose.pose.position
        log.info(
            "goal_pose (%g, %g) received: sending it to navigate_to_pose", position.x, position.y
        )
        self._spawn(self._send_own_goal(pose))

    async def _send_own_goal(self, pose: PoseStamped) -> None:
        goal = NavigateToPose.Goal(pose=pose)
        try:
            await self._self_client.send_goal(goal, server_timeout=SELF_GOAL_TIMEOUT)
        except Exception as exc:  # a rejected goal or no server: say so, keep serving
            log.error("goal_pose goal not accepted: %s", exc)

    async def _publish_snapshots(self, period: float) -> None:
        """A snapshot every ``period`` of robot time while a navigation runs or anybody
        watches; idle and unwatched, the robot's clock is not needed (not listened to):
        Zenoh's matching status is looked at every ``SNAPSHOT_POLL`` wall s."""
        sink = self.navigator.stream.sink
        while True:
            watched = not isinstance(sink, BusStatusSink) or sink.watched
            if self.navigator.current is None and not watched:
                await asyncio.sleep(SNAPSHOT_POLL)  # wall time: a poll, not the robot's
                continue
            async with clock_held(self.clock, FRESH_TIMEOUT):  # stamped on fresh time
                sink.snapshot(self.navigator.snapshot())
            await self.clock.sleep(period)
