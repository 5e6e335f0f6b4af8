"""Action server edges, via a real router: executes that do not stop when cancelled,
executes that return a Result after a cancel or preemption, shutdown with goals live."""

from __future__ import annotations

import asyncio
import contextlib
import logging
from typing import Any

import pytest

from aiobt.msgs import GoalState, Wait
from aiobt.transport import Bus, BusSettings, GoalHandle, GoalRejected, open_bus
from aiobt.transport.actions import protocol as p
from aiobt.transport.actions import runner as runner_module
from aiobt.transport.actions.goals import GoalRecord
from tests.integration.transport.action_support import WAIT, one_after_another, until

pytestmark = pytest.mark.integration
WaitHandle = GoalHandle[Wait.Goal, Wait.Result, Wait.Feedback]


class Stubborn:
    """A Wait execute that swallows the first cancellation and ends soon after a second;
    counts the executes alive at once."""

    def __init__(self) -> None:
        self.alive = 0
        self.peak = 0
        self.events: list[str] = []
        self.cancels: dict[str, int] = {}

    async def execute(self, goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        goal_id = handle.goal_id
        self.alive += 1
        self.peak = max(self.peak, self.alive)
        self.events.append(f"start {goal_id}")
        try:
            while True:
                try:
                    await asyncio.sleep(goal.time)
                    return Wait.Result(total_elapsed_time=goal.time)
                except asyncio.CancelledError:
                    self.cancels[goal_id] = self.cancels.get(goal_id, 0) + 1
                    if self.cancels[goal_id] >= 2:
                        await asyncio.sleep(0.05)  # stops the motors, then gives in
                        raise
        finally:
            self.alive -= 1
            self.events.append(f"end {goal_id}")


@pytest.fixture
def short_stop(monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture) -> None:
    monkeypatch.setattr(runner_module, "_STOP_TIMEOUT", 0.3)
    caplog.set_level(logging.WARNING, logger="aiobt.transport.actions")


def stop_warnings(caplog: pytest.LogCaptureFixture, goal_id: str) -> list[str]:
    return [
        r.getMessage()
        for r in caplog.records
        if r.levelno == logging.WARNING and goal_id in r.getMessage()
    ]


@pytest.mark.usefixtures("short_stop")
async def test_a_preempting_goal_waits_until_the_stubborn_execute_has_ended(
    bus: Bus, client_bus: Bus, caplog: pytest.LogCaptureFixture
) -> None:
    stubborn = Stubborn()
    bus.action_server("wait", Wait, stubborn.execute)
    client = client_bus.action_client("wait", Wait)
    first = await client.send_goal(Wait.Goal(time=30.0), server_timeout=WAIT)
    await until(lambda: stubborn.events)
    second = await client.send_goal(Wait.Goal(time=0.05), server_timeout=WAIT)
    await second.result(timeout=WAIT)
    assert stubborn.peak == 1  # never two executes at once
    first_result = await first.result(timeout=WAIT)
    assert stubborn.events == one_after_another(first, second)
    assert stubborn.cancels == {first.goal_id: 2}  # cancelled again after the stop timeout
    assert first.status is GoalState.ABORTED
    assert first_result.error_msg == f"preempted by goal {second.goal_id}"
    assert second.status is GoalState.SUCCEEDED
    assert stop_warnings(caplog, first.goal_id)


@pytest.mark.usefixtures("short_stop")
async def test_the_newest_goal_waiting_for_a_stubborn_canceled_execute_runs_after_it(
    bus: Bus, client_bus: Bus, caplog: pytest.LogCaptureFixture
) -> None:
    stubborn = Stubborn()
    bus.action_server("wait", Wait, stubborn.execute)
    client = client_bus.action_client("wait", Wait)
    first = await client.send_goal(Wait.Goal(time=30.0), server_timeout=WAIT)
    await until(lambda: stubborn.events)
    assert await client.request_cancel(first.goal_id, timeout=WAIT) == [first.goal_id]
    await until(lambda: stubborn.cancels.get(first.goal_id) == 1)
    # a repeated cancel request does not cancel its task again (its cleanup runs on)
    assert await client.request_cancel(first.goal_id, timeout=WAIT) == [first.goal_id]
    second = await client.send_goal(Wait.Goal(time=0.05), server_timeout=WAIT)
    third = await client.send_goal(Wait.Goal(time=0.05), server_timeout=WAIT)
    # one waiting slot (Nav2): the newer goal replaces the waiting one, which never runs
    second_result = await second.result(timeout=WAIT)
    assert (second.status, second_result.error_msg) == (
        GoalState.ABORTED,
        f"preempted by goal {third.goal_id}",
    )
    assert stubborn.cancels == {first.goal_id: 1}
    await third.result(timeout=WAIT)
    assert stubborn.peak == 1
    first_result = await first.result(timeout=WAIT)
    assert stubborn.events == one_after_another(first, third)
    assert (first.status, first_result.error_msg) == (GoalState.CANCELED, "canceled")
    assert third.status is GoalState.SUCCEEDED
    assert stop_warnings(caplog, first.goal_id)


async def test_an_execute_returning_a_result_after_a_cancel_or_preemption(
    bus: Bus, client_bus: Bus
) -> None:
    started: list[str] = []

    async def execute(goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        started.append(handle.goal_id)
        try:
            await asyncio.sleep(goal.time)
        except asyncio.CancelledError:
            await asyncio.sleep(0.05)  # stop the base, then report
            return Wait.Result(total_elapsed_time=0.25, error_msg="stopped early")
        return Wait.Result(total_elapsed_time=goal.time)

    bus.action_server("wait", Wait, execute)
    client = client_bus.action_client("wait", Wait)
    canceled = await client.send_goal(Wait.Goal(time=30.0), server_timeout=WAIT)
    await until(lambda: started)
    result = await canceled.cancel(timeout=WAIT)
    assert canceled.status is GoalState.CANCELED  # carrying what execute returned
    assert result == Wait.Result(total_elapsed_time=0.25, error_msg="stopped early")
    assert await client.fetch_result(canceled.goal_id, timeout=WAIT) == (
        GoalState.CANCELED,
        result,
    )
    preempted = await client.send_goal(Wait.Goal(time=30.0), server_timeout=WAIT)
    await until(lambda: len(started) == 2)
    newer = await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
    preempted_result = await preempted.result(timeout=WAIT)
    await newer.result(timeout=WAIT)
    assert preempted.status is GoalState.ABORTED
    assert preempted_result.error_msg == f"preempted by goal {newer.goal_id}"
    assert newer.status is GoalState.SUCCEEDED


async def test_closing_the_server_bus_aborts_the_running_and_waiting_goals(
    bus_settings: BusSettings, client_bus: Bus
) -> None:
    started = asyncio.Event()
    cleaning = asyncio.Event()
    release = asyncio.Event()

    async def execute(goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        started.set()
        try:
            await asyncio.sleep(goal.time)
            return Wait.Result(total_elapsed_time=goal.time)
        finally:
            if goal.time > 1.0:
                cleaning.set()
                with contextlib.suppress(TimeoutError):
                    await asyncio.wait_for(release.wait(), WAIT)

    async with open_bus(bus_settings) as server_bus:
        server = server_bus.action_server("wait", Wait, execute)
        client = client_bus.action_client("wait", Wait)
        running = await client.send_goal(Wait.Goal(time=30.0), server_timeout=WAIT)
        await asyncio.wait_for(started.wait(), WAIT)
        waiting = await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
        await asyncio.wait_for(cleaning.wait(), WAIT)  # running stops; waiting waits
        closing = asyncio.create_task(server_bus.close())
        try:
            waiting_result = await waiting.result(timeout=WAIT)
            with pytest.raises(GoalRejected, match="action server shutting down"):
                await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
            assert not running.done  # its cleanup is not cut short
            release.set()
            running_result = await running.result(timeout=WAIT)
        finally:
            release.set()
            await asyncio.wait_for(closing, WAIT)
        assert server.active_goal_id is None
    for goal, result in ((running, running_result), (waiting, waiting_result)):
        assert (goal.status, result.error_msg) == (
            GoalState.ABORTED,
            "action server shutting down",
        )


async def test_a_shutdown_aborts_an_execute_that_catches_it_and_returns(
    bus_settings: BusSettings, client_bus: Bus
) -> None:
    started = asyncio.Event()

    async def execute(goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        started.set()
        with contextlib.suppress(asyncio.CancelledError):
            await asyncio.sleep(goal.time)
        return Wait.Result(total_elapsed_time=0.0)  # error_code 0, "success"

    async with open_bus(bus_settings) as server_bus:
        server_bus.action_server("wait", Wait, execute)
        client = client_bus.action_client("wait", Wait)
        goal = await client.send_goal(Wait.Goal(time=30.0), server_timeout=WAIT)
        await asyncio.wait_for(started.wait(), WAIT)
    result = await goal.result(timeout=WAIT)
    assert (goal.status, result.error_msg) == (GoalState.ABORTED, "action server shutting down")


async def test_a_client_closing_mid_goal_says_so(bus: Bus, bus_settings: BusSettings) -> None:
    started = asyncio.Event()

    async def execute(goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        started.set()
        await asyncio.sleep(goal.time)
        return Wait.Result(total_elapsed_time=goal.time)

    bus.action_server("wait", Wait, execute)
    async with open_bus(bus_settings) as client_bus:
        goal = await client_bus.action_client("wait", Wait).send_goal(
            Wait.Goal(time=30.0), server_timeout=WAIT
        )
        await asyncio.wait_for(started.wait(), WAIT)
    with pytest.raises(p.GoalLost, match="the client closed"):
        await goal.result(timeout=WAIT)


async def test_a_second_aclose_does_nothing(
    bus_settings: BusSettings, client_bus: Bus, caplog: pytest.LogCaptureFixture
) -> None:
    async def execute(goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        return Wait.Result(total_elapsed_time=goal.time)

    caplog.set_level(logging.DEBUG)
    async with open_bus(bus_settings) as server_bus:
        server = server_bus.action_server("wait", Wait, execute)
        client = client_bus.action_client("wait", Wait)
        goal = await client.send_goal(Wait.Goal(time=0.0), server_timeout=WAIT)
        await goal.result(timeout=WAIT)
        await asyncio.wait_for(server.aclose(), WAIT)
        await asyncio.wait_for(server.aclose(), WAIT)
    # ... and once more when the bus closed
    assert [r for r in caplog.records if r.levelno >= logging.WARNING] == []


class FakeQuery:
    """Records what the server replies to a query (goal stream or cancel)."""

    key_expr = "fake"

    def __init__(self, payload: bytes = b"") -> None:
        self.sent: list[tuple[bytes, bytes]] = []  # (attachment, payload)
        self.dropped = 0
        self.payload = zenoh_like_payload(payload)

    def reply(self, key_expr: str, payload: bytes, **kwargs: Any) -> None:
        self.sent.append((kwargs.get("attachment") or b"", payload))

    def drop(self) -> None:
        self.dropped += 1


def zenoh_like_payload(payload: bytes) -> Any:
    return type("Payload", (), {"to_bytes": lambda self: payload})()


async def test_a_goal_canceled_before_its_execute_took_a_step_still_ends(bus: Bus) -> None:
    """The cancel reaches the loop before the new task's first step (the client sent
    the goal and then its cancel, e.g. after ServerUnavailable): its body never runs."""
    started: list[str] = []

    async def execute(goal: Wait.Goal, handle: WaitHandle) -> Wait.Result:
        started.append(handle.goal_id)
        return Wait.Result(total_elapsed_time=goal.time)

    server = bus.action_server("wait", Wait, execute)
    goal_query, cancel_query = FakeQuery(), FakeQuery(b'{"goal_id": "g1"}')
    # the loop-side entry points, in the order the bridge would run them in one tick
    server._begin(GoalRecord("g1", goal_query), Wait.Goal(time=1.0))  # type: ignore[arg-type]
    server._on_cancel(cancel_query)  # type: ignore[arg-type]
    await until(lambda: goal_query.dropped)
    assert cancel_query.sent[0][1] == b'{"goals_canceling":["g1"]}'
    assert [tag for tag, _ in goal_query.sent] == [p.ACCEPTED, p.result_tag(GoalState.CANCELED)]
    assert started == []
    assert server.active_goal_id is None
