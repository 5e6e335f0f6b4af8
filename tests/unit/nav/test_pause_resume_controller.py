"""PauseResumeController: std_srvs/Trigger services switch between its branches."""

from __future__ import annotations

import pytest

from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.msgs import Trigger
from aiobt.nav.control.pause_resume_controller import PauseResumeController, State
from aiobt.testing.stubs import Stubs
from aiobt.transport import Bus
from tests.unit.nav.state_support import WAIT, nav_tree

S, F, R = Status.SUCCESS, Status.FAILURE, Status.RUNNING
pytestmark = pytest.mark.timeout(60)


def controller(children: str) -> str:
    return (
        '<PauseResumeController pause_service_name="/pause" resume_service_name="resume">'
        f"{children}</PauseResumeController>"
    )


ALL = (
    '<StubAction name="work" results="R"/><StubAction name="paused" results="R"/>'
    '<StubAction name="on_pause" results="S"/><StubAction name="on_resume" results="S"/>'
)


def state_of(node: TreeNode) -> State:
    assert isinstance(node, PauseResumeController)
    return node.state


async def call(bus: Bus, service: str) -> Trigger.Response:
    return await bus.call(service, Trigger.Request(), Trigger.Response, timeout=WAIT)


async def test_pause_and_resume_run_their_branches(local_bus: Bus) -> None:
    stubs = Stubs()
    tree = nav_tree(local_bus, controller(ALL), stubs=stubs)
    node = tree.root
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("work") == 1
    assert (await call(local_bus, "pause")).success
    assert await tree.tick_exactly_once() is R
    assert stubs.halts("work") == 1
    assert stubs.ticks("on_pause") == 1
    assert state_of(node) is State.PAUSED
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("paused") == 1
    refused = await call(local_bus, "pause")
    assert not refused.success
    assert "already PAUSED" in refused.message
    assert (await call(local_bus, "resume")).success
    assert await tree.tick_exactly_once() is R
    assert (stubs.halts("paused"), stubs.ticks("on_resume")) == (1, 1)
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("work") == 2
    assert not (await call(local_bus, "resume")).success  # not paused


async def test_resumed_success_is_success_and_failure_is_failure(local_bus: Bus) -> None:
    stubs = Stubs()
    tree = nav_tree(local_bus, controller('<StubAction name="work" results="S"/>'), stubs=stubs)
    assert await tree.tick_exactly_once() is S
    failing = nav_tree(local_bus, controller('<StubAction name="bad" results="F"/>'), stubs=stubs)
    assert await failing.tick_exactly_once() is F


async def test_missing_optional_branches_are_skipped(local_bus: Bus) -> None:
    stubs = Stubs()
    tree = nav_tree(local_bus, controller('<StubAction name="work" results="R"/>'), stubs=stubs)
    assert await tree.tick_exactly_once() is R
    assert (await call(local_bus, "pause")).success
    statuses = [await tree.tick_exactly_once() for _ in range(3)]
    assert statuses == [R, R, R]
    assert state_of(tree.root) is State.PAUSED
    assert (await call(local_bus, "resume")).success
    for _ in range(3):
        await tree.tick_exactly_once()
    assert state_of(tree.root) is State.RESUMED
    assert stubs.ticks("work") >= 2
