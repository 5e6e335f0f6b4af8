"""No navigation service reads the simulation's truth: with the whole stack up
(localization giving ``{ns}/pose``, the robot publishing no pose in map), a
publisher on ``{ns}/sim/pose`` matches no subscriber. Any subscription that
would receive it (``{ns}/sim/pose``, ``{ns}/sim/**``, ``{ns}/**``) matches it."""

from __future__ import annotations

import pytest

from aiobt.msgs import PoseStamped
from aiobt.testing.stack import NavStack, StackConfig
from aiobt.transport import open_bus
from aiobt.transport.keys import SIM_POSE

pytestmark = [pytest.mark.integration, pytest.mark.e2e, pytest.mark.timeout(300)]


async def test_no_navigation_service_subscribes_to_the_truth(router_endpoint: str) -> None:
    config = StackConfig(world="office", speed=1.0)
    with NavStack.launch(router_endpoint, config) as stack:
        async with open_bus(stack.settings()) as bus:
            await stack.wait_ready(bus, timeout=120.0)
            estimate = bus.subscribe("pose", PoseStamped, queue_size=1)
            await estimate.wait_latest(30.0)  # localization is in the loop
            estimate.close()
            truth = bus.publisher(SIM_POSE, PoseStamped)
            assert not await truth.wait_for_subscribers(3.0), (
                f"a process subscribes to {truth.key}:\n{stack.logs()}"
            )
            # the control: a subscriber the way a navigation service would have one
            async with open_bus(stack.settings()) as reader:
                reader.subscribe(SIM_POSE, PoseStamped)
                assert await truth.wait_for_subscribers(10.0)
