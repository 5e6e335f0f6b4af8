"""A remote leaf whose action server process is killed mid-goal fails fast, naming it."""

from __future__ import annotations

import asyncio
from collections.abc import Callable, Sequence

import pytest

from aiobt.core.status import Status
from aiobt.msgs import Wait
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings
from tests.unit.nav.support import nav_tree, tick_until_true

pytestmark = [pytest.mark.integration, pytest.mark.timeout(60)]
Spawn = Callable[[Sequence[str]], ServiceProcess]
SERVER = "tests.integration.transport.action_server_proc"  # serves "wait"


async def test_killing_the_server_mid_goal_fails_the_leaf_within_1_5_s(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    common = ["--connect", bus_settings.connect[0], "--namespace", bus_settings.namespace]
    server = spawn(["-m", SERVER, *common])
    if not await bus.action_client("wait", Wait).wait_for_server(30.0):
        pytest.fail(f"the wait server did not come up:\n{server.output()}")
    tree = nav_tree(bus, '<Wait wait_duration="60" server_timeout="5000" error_msg="{msg}"/>')
    node = tree.find("Wait")
    accepted = await tick_until_true(tree, lambda: getattr(node, "_handle", None) is not None)
    assert accepted is Status.RUNNING
    loop = asyncio.get_running_loop()
    server.kill()
    killed = loop.time()
    async with asyncio.timeout(10.0):
        status = await tree.tick_while_running(period=0.01)
    assert status is Status.FAILURE
    assert loop.time() - killed < 1.5
    assert "wait" in tree.root_blackboard["msg"]
    assert "lost" in tree.root_blackboard["msg"]
