"""Cancelling goals that wait for a running one to stop, via a real router.

An accepted goal that is not executing yet (it waits while the goal it preempts
cleans up, or behind another waiting goal) ends CANCELED at once when canceled,
never runs, and the goals after it are still served in order.
"""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator, Callable
from typing import Any

import pytest

from aiobt.msgs import FollowPath, GoalState, GoalStatus, Path, PoseStamped, Wait, decode
from aiobt.transport import ActionServer, Bus, GoalHandle
from tests.integration.transport.action_support import WAIT, one_after_another, until

pytestmark = pytest.mark.integration
WaitHandle = GoalHandle[Wait.Goal, Wait.Result, Wait.Feedback]
FollowHandle = GoalHandle[FollowPath.Goal, FollowPath.Result, FollowPath.Feedback]


class SlowCleanup:
    """Executions whose cleanup (in ``finally``) holds until the test releases it."""

    def __init__(self) -> None:
        self.events: list[str] = []
        self.cleaning = asyncio.Event()
        self.release = asyncio.Event()

    async def cleanup(self, goal_id: str, slow: bool) -> None:
        if slow:
            self.cleaning.set()
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(self.release.wait(), WAIT)
        self.events.append(f"end {goal_id}")

    async def wait(self, goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        """A Wait execute: a goal longer than 1 s cleans up slowly."""
        self.events.append(f"start {handle.goal_id}")
        try:
            await asyncio.sleep(goal.time)
            return Wait.Result(total_elapsed_time=goal.time)
        finally:
            await self.cleanup(handle.goal_id, goal.time > 1.0)

    async def follow(self, goal: FollowPath.Goal, handle: FollowHandle) -> FollowPath.Result:
        """A FollowPath execute (replace policy): controller "slow" cleans up slowly."""
        self.events.append(f"start {handle.goal_id}")
        first_id = handle.goal_id
        try:
            while goal.path.header.frame_id != "done":
                handle.publish_feedback(FollowPath.Feedback(distance_to_goal=1.0))
                goal = handle.take_new_goal() or goal
                await asyncio.sleep(0.01)
            return FollowPath.Result()
        finally:
            await self.cleanup(first_id, goal.controller_id == "slow")


@contextlib.asynccontextmanager
async def observed_status(
    bus: Bus, server: ActionServer[Any, Any, Any]
) -> AsyncIterator[Callable[[str], list[GoalStatus]]]:
    """Collects the GoalStatus messages of ``server``; yields ``statuses_of(goal_id)``."""
    seen: list[GoalStatus] = []
    key = f"{server.keys.base}/status/*"
    observer = bus.session.declare_subscriber(
        key, lambda s: seen.append(decode(GoalStatus, s.payload.to_bytes()))
    )
    try:
        await until(lambda: server._observed("status"))
        yield lambda goal_id: [s for s in seen if s.goal_id == goal_id]
    finally:
        observer.undeclare()  # type: ignore[no-untyped-call]


def states(statuses: list[GoalStatus]) -> list[GoalState]:
    return [s.status for s in statuses]


async def test_cancel_of_a_goal_waiting_for_the_preempted_one_to_stop(
    bus: Bus, client_bus: Bus
) -> None:
    slow = SlowCleanup()
    server = bus.action_server("wait", Wait, slow.wait)
    client = client_bus.action_client("wait", Wait)
    async with observed_status(client_bus, server) as statuses_of:
        first = await client.send_goal(Wait.Goal(time=30.0), server_timeout=WAIT)
        second = await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
        await asyncio.wait_for(slow.cleaning.wait(), WAIT)  # first stops; second waits
        fetching = asyncio.create_task(client.fetch_result(second.goal_id, timeout=WAIT))
        await asyncio.wait({fetching}, timeout=0.3)
        assert not fetching.done()  # a waiting goal's result is awaited, not "unknown"
        assert await client.request_cancel(second.goal_id, timeout=WAIT) == [second.goal_id]
        result = await second.result(timeout=WAIT)
        assert (second.status, result.error_msg) == (GoalState.CANCELED, "canceled")
        assert slow.events == [f"start {first.goal_id}"]  # at once: first still cleans up
        assert await fetching == (GoalState.CANCELED, result)
        slow.release.set()
        first_result = await first.result(timeout=WAIT)
        assert first.status is GoalState.ABORTED
        assert first_result.error_msg == f"preempted by goal {second.goal_id}"
        third = await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
        await third.result(timeout=WAIT)
        assert third.status is GoalState.SUCCEEDED
        await until(lambda: len(statuses_of(second.goal_id)) >= 3)
        assert states(statuses_of(second.goal_id)) == [
            GoalState.ACCEPTED,
            GoalState.CANCELING,
            GoalState.CANCELED,
        ]
    assert slow.events == [  # the canceled goal never ran
        f"start {first.goal_id}",
        f"end {first.goal_id}",
        f"start {third.goal_id}",
        f"end {third.goal_id}",
    ]


async def test_a_newer_goal_takes_the_one_waiting_slot_as_in_nav2(
    bus: Bus, client_bus: Bus
) -> None:
    slow = SlowCleanup()
    bus.action_server("wait", Wait, slow.wait)
    client = client_bus.action_client("wait", Wait)
    first = await client.send_goal(Wait.Goal(time=30.0), server_timeout=WAIT)
    second = await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
    await asyncio.wait_for(slow.cleaning.wait(), WAIT)  # first stops; second waits
    third = await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
    # Nav2's SimpleActionServer keeps one pending goal: the newer one replaces it
    second_result = await second.result(timeout=WAIT)
    assert (second.status, second_result.error_msg) == (
        GoalState.ABORTED,
        f"preempted by goal {third.goal_id}",
    )
    result = await third.cancel(timeout=WAIT)  # the waiting goal can still be canceled
    assert result is not None
    assert (third.status, result.error_msg) == (GoalState.CANCELED, "canceled")
    assert slow.events == [f"start {first.goal_id}"]  # first still cleans up
    slow.release.set()
    first_result = await first.result(timeout=WAIT)
    assert first.status is GoalState.ABORTED
    assert first_result.error_msg == f"preempted by goal {second.goal_id}"
    fourth = await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
    await fourth.result(timeout=WAIT)
    assert fourth.status is GoalState.SUCCEEDED
    assert slow.events == one_after_another(first, fourth)


async def test_cancel_all_leaves_out_a_goal_being_preempted(bus: Bus, client_bus: Bus) -> None:
    slow = SlowCleanup()
    server = bus.action_server("wait", Wait, slow.wait)
    client = client_bus.action_client("wait", Wait)
    async with observed_status(client_bus, server) as statuses_of:
        first = await client.send_goal(Wait.Goal(time=30.0), server_timeout=WAIT)
        second = await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
        third = await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
        await asyncio.wait_for(slow.cleaning.wait(), WAIT)
        # first is being preempted (its outcome is decided): neither call names it
        assert await client.request_cancel(first.goal_id, timeout=WAIT) == []
        canceling = await client.cancel_all(timeout=WAIT)
        assert canceling == [third.goal_id]  # second was replaced by third, not canceled
        second_result = await second.result(timeout=WAIT)
        assert (second.status, second_result.error_msg) == (
            GoalState.ABORTED,
            f"preempted by goal {third.goal_id}",
        )
        third_result = await third.result(timeout=WAIT)
        assert (third.status, third_result.error_msg) == (GoalState.CANCELED, "canceled")
        assert slow.events == [f"start {first.goal_id}"]  # its cleanup is not interrupted
        slow.release.set()
        first_result = await first.result(timeout=WAIT)
        await until(lambda: len(statuses_of(first.goal_id)) >= 3)
        assert states(statuses_of(first.goal_id)) == [  # never CANCELING
            GoalState.ACCEPTED,
            GoalState.EXECUTING,
            GoalState.ABORTED,
        ]
    assert first.status is GoalState.ABORTED  # it was being preempted before the cancel
    assert first_result.error_msg == f"preempted by goal {second.goal_id}"
    fourth = await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
    await fourth.result(timeout=WAIT)
    assert fourth.status is GoalState.SUCCEEDED
    assert slow.events == one_after_another(first, fourth)
    assert await client.cancel_all(timeout=WAIT) == []


def follow_goal(controller: str, done: bool = False) -> FollowPath.Goal:
    path = Path(poses=[PoseStamped.from_xy_yaw(1, 1)])
    path.header.frame_id = "done" if done else "map"
    return FollowPath.Goal(path=path, controller_id=controller)


async def test_replace_goals_sent_during_a_cancel_wait_for_the_cleanup_newest_first(
    bus: Bus, client_bus: Bus
) -> None:
    slow = SlowCleanup()
    bus.action_server("follow_path", FollowPath, slow.follow, preemption="replace")
    client = client_bus.action_client("follow_path", FollowPath)
    first = await client.send_goal(follow_goal("slow"), server_timeout=WAIT)
    async for _ in first.feedback():
        break
    assert await client.request_cancel(first.goal_id, timeout=WAIT) == [first.goal_id]
    await asyncio.wait_for(slow.cleaning.wait(), WAIT)
    # the canceled execute is stopping: newer goals wait for it, not get handed to it
    second = await client.send_goal(follow_goal("B", done=True), server_timeout=WAIT)
    third = await client.send_goal(follow_goal("C", done=True), server_timeout=WAIT)
    result = await second.result(timeout=WAIT)  # replaced in the waiting slot
    assert (second.status, result.error_msg) == (
        GoalState.ABORTED,
        f"preempted by goal {third.goal_id}",
    )
    assert not third.done
    slow.release.set()
    first_result = await first.result(timeout=WAIT)
    assert (first.status, first_result.error_msg) == (GoalState.CANCELED, "canceled")
    await third.result(timeout=WAIT)
    assert third.status is GoalState.SUCCEEDED
    assert slow.events == one_after_another(first, third)
