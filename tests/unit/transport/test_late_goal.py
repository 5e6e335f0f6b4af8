"""A goal copy that reaches the server after its client canceled it (in-process bus).

Under load a send_goal's first copy can go unanswered at the client and reach the
server late; the client cancels it quietly and retries with a new goal id. When that
cancel overtakes the late copy, the copy must not run: it would preempt the retried
goal the client follows (issue 13: ComputePathToPose ended ABORTED "preempted by goal
<an id the leaf never knew>").
"""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from aiobt.msgs import GoalState, Wait
from aiobt.transport import Bus, GoalRejected

pytestmark = pytest.mark.timeout(30)
WAIT = 10.0


async def test_a_goal_canceled_before_it_arrived_is_refused_and_preempts_nothing(
    local_bus: Bus,
) -> None:
    release = asyncio.Event()
    started: list[str] = []

    async def execute(goal: Any, handle: Any) -> Any:
        started.append(handle.goal_id)
        await release.wait()
        return Wait.Result()

    local_bus.action_server(Wait.name, Wait, execute)
    client = local_bus.action_client(Wait.name, Wait)
    assert await client.wait_for_server(WAIT)
    current = await client.send_goal(Wait.Goal(time=1.0), server_timeout=WAIT)

    assert await client.request_cancel("late-copy", WAIT) == []  # not there yet
    with pytest.raises(GoalRejected, match="canceled before it arrived"):
        await client.send_goal(Wait.Goal(time=2.0), goal_id="late-copy", server_timeout=WAIT)

    release.set()
    await current.result(WAIT)
    assert current.status is GoalState.SUCCEEDED
    assert started == [current.goal_id]


async def test_a_goal_id_canceled_while_running_is_not_remembered_as_early(
    local_bus: Bus,
) -> None:
    async def execute(goal: Any, handle: Any) -> Any:
        await asyncio.Event().wait()  # until canceled
        return Wait.Result()

    local_bus.action_server(Wait.name, Wait, execute)
    client = local_bus.action_client(Wait.name, Wait)
    assert await client.wait_for_server(WAIT)
    sent = await client.send_goal(Wait.Goal(time=1.0), server_timeout=WAIT)
    assert await client.request_cancel(sent.goal_id, WAIT) == [sent.goal_id]
    await sent.result(WAIT)
    assert sent.status is GoalState.CANCELED
    again = await client.send_goal(Wait.Goal(time=1.0), server_timeout=WAIT)  # a new id runs
    assert await client.request_cancel(again.goal_id, WAIT) == [again.goal_id]
