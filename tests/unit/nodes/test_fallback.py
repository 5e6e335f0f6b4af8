"""Fallback, ReactiveFallback, AsyncFallback: scenarios with stub leaves."""

from __future__ import annotations

from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tick_statuses, tree_xml

S, F, R, K, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED, Status.IDLE

THREE = '<StubAction name="A"/><StubAction name="B"/><StubAction name="C"/>'


async def test_fallback_stops_at_first_success_and_restarts(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "FAILURE")
    stubs.script("B", "RUNNING", "SUCCESS")
    tree = bt_factory.create_tree_from_text(tree_xml(f"<Fallback>{THREE}</Fallback>"))
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, S, S]
    assert stubs.log == ["A:start", "B:start", "B:running", "A:start", "B:start"]
    assert stubs.ticks("C") == 0
    assert all(node.status is IDLE for node in tree.nodes())


async def test_fallback_all_fail(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    for name in "ABC":
        stubs.script(name, "FAILURE")
    tree = bt_factory.create_tree_from_text(tree_xml(f"<Fallback>{THREE}</Fallback>"))
    assert await tree.tick_exactly_once() is F
    assert [stubs.starts(n) for n in "ABC"] == [1, 1, 1]


async def test_fallback_all_skipped_is_skipped(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Fallback><StubAction name="A" results="K"/><StubAction name="B" results="K"/>'
            "</Fallback>"
        )
    )
    assert await tree.tick_exactly_once() is K


async def test_fallback_halt_halts_running_child(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "FAILURE")
    stubs.script("B", "RUNNING")
    tree = bt_factory.create_tree_from_text(tree_xml(f"<Fallback>{THREE}</Fallback>"))
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree("stop")
    assert stubs.halts("B") == 1
    assert stubs.halts("A") == 0
    assert await tree.tick_exactly_once() is R
    assert stubs.starts("A") == 2  # started over from the first child


async def test_reactive_fallback_rechecks_condition_and_halts_action(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("C", "FAILURE", "FAILURE", "SUCCESS")
    stubs.script("A", "RUNNING")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<ReactiveFallback><StubCondition name="C"/><StubAction name="A"/></ReactiveFallback>'
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, R, S]
    assert stubs.log == ["C:check", "A:start", "C:check", "A:running", "C:check", "A:halted"]


async def test_reactive_fallback_halts_later_running_child_when_earlier_runs(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "FAILURE", "RUNNING")
    stubs.script("B", "RUNNING")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<ReactiveFallback><StubAction name="A"/><StubAction name="B"/></ReactiveFallback>'
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, R]
    assert stubs.log == ["A:start", "B:start", "A:start", "B:halted"]


async def test_reactive_fallback_all_fail(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "FAILURE")
    stubs.script("B", "FAILURE")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<ReactiveFallback><StubAction name="A"/><StubAction name="B"/></ReactiveFallback>'
        )
    )
    assert await tree.tick_exactly_once() is F
    assert all(node.status is IDLE for node in tree.nodes())


async def test_async_fallback_yields_after_each_instant_failure(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "FAILURE")
    stubs.script("B", "FAILURE")
    tree = bt_factory.create_tree_from_text(tree_xml(f"<AsyncFallback>{THREE}</AsyncFallback>"))
    assert await tick_statuses(tree.tick_exactly_once, 4) == [R, R, S, R]
    assert stubs.log == ["A:start", "B:start", "C:start", "A:start"]
    stubs.clear()
    tree2 = bt_factory.create_tree_from_text(
        tree_xml(f"<AsyncFallback>{THREE}</AsyncFallback>", "Other")
    )
    assert await tree2.tick_once() is S
    assert stubs.log == ["A:start", "B:start", "C:start"]
