"""An action server's Observers: whether anybody watches its status keys (in-process bus)."""

from __future__ import annotations

import asyncio

import pytest

from aiobt.core.clock import SystemClock
from aiobt.msgs import GoalState, GoalStatus
from aiobt.transport import Bus
from aiobt.transport.actions.observers import Observers
from aiobt.transport.topics import declare_subscription

pytestmark = pytest.mark.timeout(30)


async def test_a_subscriber_the_matching_listener_has_not_reported_yet_gets_the_status(
    local_bus: Bus,
) -> None:
    keys = local_bus.keys.action("wait")
    observers = Observers(local_bus.session, keys, SystemClock())
    assert not observers("status")  # nobody watches: nothing is put
    got: list[GoalStatus] = []
    arrived = asyncio.Event()

    def on_status(status: GoalStatus) -> None:
        got.append(status)
        arrived.set()

    sub = declare_subscription(
        local_bus.session,
        local_bus.bridge,
        keys.any_status,
        GoalStatus,
        callback_fn=on_status,
        latched=False,
        queue_size=10,
    )
    # the listener's news of the subscriber is late (as seen under load): the flag still
    # says nobody watches, though Zenoh already matches the subscriber
    observers._flags["status"] = False
    observers.put_status("g1", GoalState.ACCEPTED)
    async with asyncio.timeout(10.0):
        await arrived.wait()
    assert [(s.goal_id, s.status) for s in got] == [("g1", GoalState.ACCEPTED)]
    sub.close()
    observers.close()
