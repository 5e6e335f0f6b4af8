"""The in-process bus that the Nav2 node tests use: no router, real Zenoh."""

from __future__ import annotations

import pytest

from aiobt.msgs import Twist, Vector3
from aiobt.transport import Bus


@pytest.mark.timeout(20)
async def test_a_message_reaches_a_subscriber_of_the_same_process(local_bus: Bus) -> None:
    sub = local_bus.subscribe("cmd_vel", Twist)
    local_bus.publisher("cmd_vel", Twist).put(Twist(linear=Vector3(x=0.5)))
    assert (await sub.next(timeout=5.0)).linear.x == 0.5
