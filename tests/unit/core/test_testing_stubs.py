"""The test helpers themselves: scripted stubs, counters, the log, the plugin fixtures."""

from __future__ import annotations

import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, parse_status, tick_statuses, tree_xml


def test_plugin_fixtures(manual_clock: ManualClock, stubs: Stubs, bt_factory: BehaviorTreeFactory):
    assert manual_clock.now() == 0.0
    assert stubs.log == []
    assert {"StubAction", "StubCondition", "StubAsyncAction", "Sequence"} <= set(
        bt_factory.registered_ids()
    )


@pytest.mark.parametrize(
    ("text", "status"),
    [("S", Status.SUCCESS), ("failure", Status.FAILURE), (" r ", Status.RUNNING),
     ("K", Status.SKIPPED), ("IDLE", Status.IDLE)],
)  # fmt: skip
def test_parse_status(text: str, status: Status):
    assert parse_status(text) is status


def test_parse_status_rejects_junk():
    with pytest.raises(ValueError, match="not a status"):
        parse_status("done")


async def test_python_script_overrides_port_script_and_last_repeats(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "RUNNING", "FAILURE")
    tree = bt_factory.create_tree_from_text(tree_xml('<StubAction name="A" results="S"/>'))
    assert await tick_statuses(tree.tick_exactly_once, 3) == [
        Status.RUNNING, Status.FAILURE, Status.FAILURE,
    ]  # fmt: skip
    record = stubs.record("A")
    assert (record.ticks, record.starts) == (3, 2)
    assert record.results == [Status.RUNNING, Status.FAILURE, Status.FAILURE]


async def test_port_script_and_callable_items(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    seen: list[str] = []

    def decide(node: object) -> Status:
        seen.append("called")
        return Status.FAILURE

    stubs.script("C", "SUCCESS", decide)
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Sequence><StubAction name="A" results="R;S"/><StubCondition name="C"/></Sequence>'
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 3) == [
        Status.RUNNING, Status.SUCCESS, Status.FAILURE,
    ]  # fmt: skip
    assert await tree.tick_exactly_once() is Status.FAILURE
    assert seen == ["called", "called"]  # the callable is the last item: it repeats
    assert stubs.events("A") == ["start", "running", "start", "start"]
    stubs.clear()
    assert stubs.log == []
    assert stubs.ticks("A") == 0


async def test_async_stub_counts_cancellation(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, manual_clock: ManualClock
):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<StubAsyncAction name="W" msec="100" result="F"/>'), clock=manual_clock
    )
    assert await tree.tick_exactly_once() is Status.RUNNING
    await tree.halt_tree("stop")
    assert (stubs.starts("W"), stubs.halts("W")) == (1, 1)
    assert await tree.tick_exactly_once() is Status.RUNNING
    await manual_clock.forward(0.1, step=0.05)
    assert await tree.tick_exactly_once() is Status.FAILURE
    assert stubs.events("W") == ["run", "cancelled", "run", "done"]
