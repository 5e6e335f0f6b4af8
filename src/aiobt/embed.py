"""aiobt inside your own asyncio program: the bus, Nav2 trees, navigation goals.

    import asyncio
    from aiobt.embed import connect

    async def main() -> None:
        async with connect(namespace="robot", sim_time=True) as robot:
            # send a goal to the navigator (aiobt navigator / aiobt up) and wait
            outcome = await robot.navigate_to(1.5, -0.5, yaw=0.0, on_feedback=print)
            print(outcome.succeeded, outcome.error_code, outcome.error_msg)

            # or run a Nav2 tree yourself, ticked in this program
            tree = robot.load_tree("trees/nav2/navigate_to_pose_w_replanning_and_recovery.xml",
                                   goal="1.5;-0.5;0.0")
            status = await tree.tick_while_running(period=0.01)

    asyncio.run(main())

:func:`connect` opens one Zenoh session (client of the router at ``connect``),
registers Nav2's node set on ``robot.factory`` bound to that session, and gives
the tree the simulation's clock when ``sim_time`` (what the services use when
the robot runs faster than real time). Everything is closed on exit.
"""

from __future__ import annotations

import asyncio
import contextlib
import math
from collections.abc import AsyncIterator, Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from aiobt.core.blackboard import Blackboard
from aiobt.core.clock import Clock, SystemClock
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.msgs import Goals, GoalState, NavigateThroughPoses, NavigateToPose, PoseStamped
from aiobt.nav import register_nav2_nodes
from aiobt.transport import (
    DEFAULT_ROUTER,
    Bus,
    BusSettings,
    ClientGoal,
    SimClockFollower,
    open_bus,
)

Feedback = NavigateToPose.Feedback | NavigateThroughPoses.Feedback
XY = tuple[float, float] | tuple[float, float, float]


@dataclass(slots=True, frozen=True)
class NavigationOutcome:
    """How a navigation ended: ``state`` SUCCEEDED, ABORTED or CANCELED, Nav2's error code."""

    state: GoalState
    error_code: int
    error_msg: str

    @property
    def succeeded(self) -> bool:
        return self.state is GoalState.SUCCEEDED


class RobotClient:
    """One robot namespace seen from your program (see :func:`connect`)."""

    def __init__(self, bus: Bus, clock: Clock, server_timeout: float) -> None:
        self.bus = bus
        self.clock = clock
        self.server_timeout = server_timeout
        self.factory = BehaviorTreeFactory()
        register_nav2_nodes(self.factory, bus, clock=clock)
        self._to_pose = bus.action_client(NavigateToPose.name, NavigateToPose)
        self._through = bus.action_client(NavigateThroughPoses.name, NavigateThroughPoses)

    def load_tree(self, source: str | Path, tree_id: str | None = None, **entries: object) -> Tree:
        """A tree from an XML file (or XML text), Nav2's nodes bound to this bus, on this
        robot's clock; ``entries`` go on its root blackboard (``goal="x;y;yaw"`` ...)."""
        blackboard = Blackboard.create()
        for key, value in entries.items():
            blackboard.set(key, value)
        text = str(source)
        if text.lstrip().startswith("<"):
            self.factory.register_behavior_tree_from_text(text)
        else:
            self.factory.register_behavior_tree_from_file(text)
        return self.factory.create_tree(tree_id, blackboard=blackboard, clock=self.clock)

    async def navigate_to(
        self,
        x: float,
        y: float,
        yaw: float = 0.0,
        *,
        behavior_tree: str = "",
        on_feedback: Callable[[Feedback], object] | None = None,
    ) -> NavigationOutcome:
        """Send a ``navigate_to_pose`` goal and wait for its end (cancelled if you cancel).

        Raises :class:`~aiobt.transport.ActionError` subclasses: ``ServerUnavailable``
        (no navigator within ``server_timeout``), ``GoalRejected``, ``GoalLost`` (the
        navigator went away mid-goal)."""
        goal = NavigateToPose.Goal(pose=pose(x, y, yaw), behavior_tree=behavior_tree)
        sent = await self._to_pose.send_goal(
            goal, server_timeout=self.server_timeout, on_feedback=on_feedback
        )
        return await _outcome(sent)

    async def navigate_through(
        self,
        poses: Sequence[XY],
        *,
        behavior_tree: str = "",
        on_feedback: Callable[[Feedback], object] | None = None,
    ) -> NavigationOutcome:
        """Send a ``navigate_through_poses`` goal through ``(x, y[, yaw])`` poses and wait."""
        goals = Goals(goals=[pose(*p) for p in poses])
        goal = NavigateThroughPoses.Goal(poses=goals, behavior_tree=behavior_tree)
        sent = await self._through.send_goal(
            goal, server_timeout=self.server_timeout, on_feedback=on_feedback
        )
        return await _outcome(sent)

    async def publish_goal(
        self, x: float, y: float, yaw: float = 0.0, before_put: Callable[[], object] = tuple
    ) -> None:
        """Put a goal on ``{ns}/goal_pose`` (the navigator starts or updates a navigation);
        waits up to ``server_timeout`` for a subscriber, so the goal is not lost.
        ``before_put`` is called just before the put."""
        publisher = self.bus.publisher("goal_pose", PoseStamped, reliable=True)
        try:
            if not await publisher.wait_for_subscribers(self.server_timeout):
                raise TimeoutError(
                    f"{self.bus.namespace}/goal_pose: no subscriber (navigator) within "
                    f"{self.server_timeout:g} s"
                )
            goal = pose(x, y, yaw)
            before_put()
            publisher.put(goal)
        finally:
            publisher.close()


async def _outcome(sent: ClientGoal[Any, Any, Any]) -> NavigationOutcome:
    """Wait for ``sent`` to end; a caller that is cancelled cancels the goal first."""
    try:
        result = await sent.result()
    except asyncio.CancelledError:
        await sent.cancel()
        raise
    return NavigationOutcome(GoalState(sent.status), result.error_code, result.error_msg)


def pose(x: float, y: float, yaw: float = 0.0) -> PoseStamped:
    """A goal pose in ``map``; ValueError names a coordinate that is not a finite number."""
    for name, value in (("x", x), ("y", y), ("yaw", yaw)):
        if not math.isfinite(value):
            raise ValueError(f"goal {name} must be a finite number, got {value}")
    return PoseStamped.from_xy_yaw(x, y, yaw)


@contextlib.asynccontextmanager
async def connect(
    namespace: str = "robot",
    connect: str | Sequence[str] = DEFAULT_ROUTER,
    *,
    sim_time: bool = False,
    server_timeout: float = 10.0,
    settings: BusSettings | None = None,
) -> AsyncIterator[RobotClient]:
    """Open the bus (``settings``, or a client of ``connect`` on ``namespace``) and yield a
    :class:`RobotClient`; ``sim_time`` waits (``server_timeout``) for ``{ns}/clock``."""
    endpoints = (connect,) if isinstance(connect, str) else tuple(connect)
    settings = settings or BusSettings(
        connect=endpoints, namespace=namespace, connect_timeout=server_timeout
    )
    async with open_bus(settings) as bus:
        clock: Clock = SystemClock()
        follower = None
        if sim_time:
            follower = SimClockFollower(bus)
            await follower.wait_started(server_timeout)
            clock = follower.clock
        try:
            yield RobotClient(bus, clock, server_timeout)
        finally:
            if follower is not None:
                follower.close()
