"""Watching a navigation from outside: the robot's track and the action servers' goals.

- :class:`RobotTrack` follows ``{ns}/pose``: the latest pose (its stamp is sim
  time), the distance driven, the top speed, and waits for conditions on it;
- :class:`ServerGoals` follows ``{ns}/action/<server>/status/*`` and ``result/*``
  of several servers: which goals each one has, in which state, which are still
  active, and the error code of each server's latest result;
- :func:`start_navigation` / :func:`navigate` send a NavigateToPose goal and keep
  its feedback until the end.

Both are callbacks in the event loop (no task, no polling); waits are bounded.
"""

from __future__ import annotations

import asyncio
import contextlib
import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any, TypeVar

from aiobt.msgs import ActionResult, GoalState, GoalStatus, Msg, NavigateToPose, PoseStamped
from aiobt.msgs.action import ActionDef
from aiobt.transport import ActionClient, Bus, ClientGoal
from aiobt.transport.topics import Subscription, declare_subscription

M = TypeVar("M", bound=Msg)
TELEPORT = 0.5  # m between two poses (at 50 Hz): a reset, not driving


async def wait_until(
    changed: asyncio.Event,
    predicate: Callable[[], object],
    timeout: float,  # noqa: ASYNC109
) -> bool:
    """True once ``predicate()`` is truthy, checked now and each time ``changed`` is set
    (the waiter clears it); False if ``timeout`` s pass first."""
    with contextlib.suppress(TimeoutError):
        async with asyncio.timeout(timeout):
            while not predicate():
                changed.clear()
                await changed.wait()
    return bool(predicate())


@dataclass(frozen=True, slots=True)
class Sample:
    stamp: float
    x: float
    y: float
    yaw: float


class RobotTrack:
    """The robot's pose stream: latest pose; poses, distance driven and top speed since
    :meth:`restart`."""

    def __init__(self, bus: Bus) -> None:
        self.latest: Sample | None = None
        self.samples: list[Sample] = []  # since restart()
        self.driven = 0.0
        self.top_speed = 0.0
        self._changed = asyncio.Event()
        self._sub = bus.subscribe("pose", PoseStamped, self._on_pose)

    def _on_pose(self, pose: PoseStamped) -> None:
        sample = Sample(pose.header.stamp, pose.x, pose.y, pose.yaw)
        last, self.latest = self.latest, sample
        self.samples.append(sample)
        if last is not None and sample.stamp > last.stamp:
            step = math.hypot(sample.x - last.x, sample.y - last.y)
            if step < TELEPORT:
                self.driven += step
                self.top_speed = max(self.top_speed, step / (sample.stamp - last.stamp))
        self._changed.set()

    def restart(self) -> None:
        """Count distance and top speed from now on."""
        self.driven = 0.0
        self.top_speed = 0.0
        self.samples.clear()

    def closest(self, x: float, y: float) -> float:
        """How near the robot came to (x, y) since :meth:`restart`."""
        return min((math.hypot(s.x - x, s.y - y) for s in self.samples), default=math.inf)

    def distance_to(self, x: float, y: float) -> float:
        if self.latest is None:
            return math.inf
        return math.hypot(self.latest.x - x, self.latest.y - y)

    async def wait_for(
        self,
        predicate: Callable[[Sample], bool],
        timeout: float,  # noqa: ASYNC109
    ) -> Sample | None:
        """The first pose (the latest included) that satisfies ``predicate``; None on timeout."""

        def holds() -> bool:
            return self.latest is not None and predicate(self.latest)

        return self.latest if await wait_until(self._changed, holds, timeout) else None

    async def wait_still(self, seconds: float, timeout: float, tolerance: float = 0.01) -> bool:  # noqa: ASYNC109
        """True once the robot moved less than ``tolerance`` m over ``seconds`` of sim time."""
        anchor: list[Sample] = []

        def settled(sample: Sample) -> bool:
            if not anchor or math.hypot(sample.x - anchor[0].x, sample.y - anchor[0].y) > tolerance:
                anchor[:] = [sample]
            return sample.stamp - anchor[0].stamp >= seconds

        return await self.wait_for(settled, timeout) is not None

    def close(self) -> None:
        self._sub.close()


class ServerGoals:
    """Goal states and last result codes of action servers, from their status and result
    streams (create it before the goals are sent: servers publish only when observed)."""

    def __init__(self, bus: Bus, actions: Iterable[type[ActionDef[Any, Any, Any]]]) -> None:
        self.states: dict[str, dict[str, GoalState]] = {}
        self.last_code: dict[str, int] = {}  # the error code of each server's latest result
        self.results: dict[str, int] = {}  # how many results each server put
        self._changed = asyncio.Event()
        self._subs: list[Subscription[Any]] = []
        for action in actions:
            self.states[action.name] = {}
            keys = bus.keys.action(action.name)
            self._watch(bus, keys.any_status, GoalStatus, self._status_recorder(action.name))
            self._watch(
                bus, keys.any_result, action.result_type(), self._result_recorder(action.name)
            )

    def _watch(self, bus: Bus, key: str, model: type[M], record: Callable[[M], None]) -> None:
        self._subs.append(
            declare_subscription(
                bus.session,
                bus.bridge,
                key,
                model,
                callback_fn=record,
                latched=False,
                queue_size=1000,
            )
        )

    def _status_recorder(self, server: str) -> Callable[[GoalStatus], None]:
        def record(status: GoalStatus) -> None:
            known = self.states[server].get(status.goal_id)
            if known is None or not known.is_terminal:  # a late EXECUTING never undoes an end
                self.states[server][status.goal_id] = status.status
            self._changed.set()

        return record

    def _result_recorder(self, server: str) -> Callable[[ActionResult], None]:
        def record(result: ActionResult) -> None:
            self.last_code[server] = result.error_code
            self.results[server] = self.results.get(server, 0) + 1
            self._changed.set()

        return record

    def summary(self) -> str:
        """Goals seen and results received per server (for a failing assertion's message)."""
        return (
            ", ".join(
                f"{server}: {len(goals)} goals, {self.results.get(server, 0)} results"
                for server, goals in self.states.items()
                if goals or server in self.results
            )
            or "nothing received"
        )

    def active(self) -> dict[str, list[str]]:
        """Goals not yet SUCCEEDED, CANCELED or ABORTED, per server (servers with none left out)."""
        found: dict[str, list[str]] = {}
        for server, goals in self.states.items():
            live = [goal for goal, state in goals.items() if not state.is_terminal]
            if live:
                found[server] = live
        return found

    def forget_unfinished(self, server: str) -> None:
        """``server``'s process died: the goals it had not ended went with it (no status
        will ever end them), so they are no longer counted as active."""
        goals = self.states[server]
        for goal in [goal for goal, state in goals.items() if not state.is_terminal]:
            del goals[goal]

    def ended(self, server: str, state: GoalState) -> int:
        """How many goals of ``server`` ended in ``state``."""
        return sum(1 for s in self.states[server].values() if s is state)

    async def wait_for(self, predicate: Callable[[], bool], timeout: float) -> bool:  # noqa: ASYNC109
        """True once ``predicate()`` holds (checked on every status change)."""
        return await wait_until(self._changed, predicate, timeout)

    async def wait_idle(self, timeout: float) -> bool:  # noqa: ASYNC109
        """True once no server has an active goal."""
        return await self.wait_for(lambda: not self.active(), timeout)

    async def wait_settled(self, timeout: float) -> bool:  # noqa: ASYNC109
        """True once no server has an active goal and each has put as many results as
        goals ended: a goal's result and its last status come on separate keys, so the
        result (and :attr:`last_code`) may trail the status, and a client's answer."""

        def settled() -> bool:
            return not self.active() and all(
                self.results.get(server, 0) >= len(goals) for server, goals in self.states.items()
            )

        return await self.wait_for(settled, timeout)

    def close(self) -> None:
        for sub in self._subs:
            sub.close()


@dataclass
class Navigation:
    """A navigation goal's end: state, result and what its feedback said on the way."""

    state: GoalState
    result: ActionResult
    feedback: list[NavigateToPose.Feedback] = field(default_factory=list)

    @property
    def recoveries(self) -> int:
        return max((f.number_of_recoveries for f in self.feedback), default=0)


NavClient = ActionClient[NavigateToPose.Goal, NavigateToPose.Result, NavigateToPose.Feedback]
NavGoal = ClientGoal[NavigateToPose.Goal, NavigateToPose.Result, NavigateToPose.Feedback]


@dataclass
class Running:
    """A sent NavigateToPose goal and the feedback it has given so far."""

    goal: NavGoal
    feedback: list[NavigateToPose.Feedback]

    async def end(self, timeout: float) -> Navigation:  # noqa: ASYNC109
        """Wait (bounded) for the result."""
        result = await self.goal.result(timeout)
        return Navigation(self.goal.status, result, self.feedback)


async def start_navigation(client: NavClient, pose: PoseStamped, tree: str = "") -> Running:
    """Send NavigateToPose to ``pose`` (``tree``: "" for the navigator's default)."""
    feedback: list[NavigateToPose.Feedback] = []
    goal = NavigateToPose.Goal(pose=pose, behavior_tree=tree)
    sent = await client.send_goal(goal, server_timeout=10.0, on_feedback=feedback.append)
    return Running(sent, feedback)


async def navigate(
    client: NavClient,
    pose: PoseStamped,
    tree: str = "",
    timeout: float = 90.0,  # noqa: ASYNC109
) -> Navigation:
    """NavigateToPose to ``pose`` and its end (bounded wait)."""
    return await (await start_navigation(client, pose, tree)).end(timeout)
