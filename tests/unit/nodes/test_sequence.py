"""Sequence, SequenceWithMemory, ReactiveSequence, AsyncSequence: scenarios with stub leaves."""

from __future__ import annotations

import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.errors import NodeError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tick_statuses, tree_xml

S, F, R, K, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED, Status.IDLE

# The tutorial tree of nav2_bt_nodes.md: BatteryOK, then "mission started",
# MoveBase (RUNNING twice, then SUCCESS), "mission completed".
MISSION = """
    <{control}>
      <StubCondition name="BatteryOK"/>
      <Sequence>
        <StubAction name="SayStarted"/>
        <StubAction name="MoveBase"/>
        <StubAction name="SayCompleted"/>
      </Sequence>
    </{control}>
"""


async def _mission(bt_factory: BehaviorTreeFactory, stubs: Stubs, control: str) -> list[Status]:
    stubs.script("MoveBase", "RUNNING", "RUNNING", "SUCCESS")
    tree = bt_factory.create_tree_from_text(tree_xml(MISSION.format(control=control)))
    statuses = []
    for _ in range(3):
        statuses.append(await tree.tick_exactly_once())
        stubs.log.append("--")
    return statuses


async def test_sequence_trace_checks_battery_once(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    assert await _mission(bt_factory, stubs, "Sequence") == [R, R, S]
    assert stubs.log == [
        "BatteryOK:check",
        "SayStarted:start",
        "MoveBase:start",
        "--",
        "MoveBase:running",
        "--",
        "MoveBase:running",
        "SayCompleted:start",
        "--",
    ]
    assert stubs.ticks("BatteryOK") == 1


async def test_reactive_sequence_trace_rechecks_battery(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    assert await _mission(bt_factory, stubs, "ReactiveSequence") == [R, R, S]
    assert stubs.log == [
        "BatteryOK:check",
        "SayStarted:start",
        "MoveBase:start",
        "--",
        "BatteryOK:check",
        "MoveBase:running",
        "--",
        "BatteryOK:check",
        "MoveBase:running",
        "SayCompleted:start",
        "--",
    ]
    assert stubs.ticks("BatteryOK") == 3
    assert stubs.halts("MoveBase") == 0


async def test_reactive_sequence_condition_failure_halts_running_action(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("BatteryOK", "SUCCESS", "FAILURE")
    stubs.script("MoveBase", "RUNNING")
    tree = bt_factory.create_tree_from_text(tree_xml(MISSION.format(control="ReactiveSequence")))
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, F]
    assert stubs.halts("MoveBase") == 1
    assert all(node.status is IDLE for node in tree.nodes())


async def test_sequence_failure_resets_and_restarts_from_first(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("B", "FAILURE", "SUCCESS")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Sequence><StubAction name="A"/><StubAction name="B"/></Sequence>')
    )
    assert await tree.tick_exactly_once() is F
    assert await tree.tick_exactly_once() is S
    assert stubs.starts("A") == 2
    assert stubs.starts("B") == 2


async def test_sequence_keeps_running_child_and_halt_resets(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("B", "RUNNING")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Sequence><StubAction name="A"/><StubAction name="B"/></Sequence>')
    )
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, R, R]
    assert stubs.ticks("A") == 1
    assert stubs.events("B") == ["start", "running", "running"]
    await tree.halt_tree("test")
    assert stubs.halts("B") == 1
    assert stubs.halts("A") == 0  # A was SUCCESS, not RUNNING: reset, not halted
    assert await tree.tick_exactly_once() is R
    assert stubs.starts("A") == 2  # Sequence started over after the halt


async def test_sequence_all_skipped_is_skipped_and_mixed_is_success(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Sequence><Sequence><StubAction name="A" results="K"/>'
            '<StubAction name="B" results="K"/></Sequence></Sequence>'
        )
    )
    inner = tree.root.children_nodes()[0]
    assert await tree.tick_exactly_once() is K
    assert tree.root.status is R  # a SKIPPED root keeps the RUNNING it set (BT.CPP)
    assert inner.status is IDLE
    stubs.script("B", "SUCCESS")
    assert await tree.tick_exactly_once() is S


async def test_sequence_with_memory_yields_between_instant_children(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    xml = tree_xml(
        '<SequenceWithMemory><StubAction name="A"/><StubAction name="B"/>'
        '<StubAction name="C"/></SequenceWithMemory>'
    )
    tree = bt_factory.create_tree_from_text(xml)
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, R, S]
    assert stubs.log == ["A:start", "B:start", "C:start"]
    stubs.clear()
    assert await tree.tick_once() is S  # one tick_once re-ticks on the wake-up
    assert stubs.log == ["A:start", "B:start", "C:start"]


async def test_sequence_with_memory_resumes_at_failed_child(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("B", "RUNNING", "FAILURE", "SUCCESS")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<SequenceWithMemory><StubAction name="A"/><StubAction name="B"/></SequenceWithMemory>'
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, R, F]
    assert await tree.tick_exactly_once() is S
    assert stubs.starts("A") == 1  # not restarted after B failed
    assert stubs.starts("B") == 2


async def test_sequence_with_memory_keeps_index_across_halt_tree(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("B", "RUNNING", "RUNNING", "SUCCESS")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<SequenceWithMemory><StubAction name="A"/><StubAction name="B"/></SequenceWithMemory>'
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, R]
    await tree.halt_tree("interrupted")
    assert stubs.halts("B") == 1
    assert await tree.tick_exactly_once() is R  # B starts again, A is not re-run
    assert stubs.starts("A") == 1
    assert await tree.tick_exactly_once() is S


async def test_async_sequence_yields_after_each_instant_child(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<AsyncSequence><StubAction name="A"/><StubAction name="B"/></AsyncSequence>')
    )
    assert await tree.tick_exactly_once() is R
    assert stubs.log == ["A:start"]
    assert await tree.tick_exactly_once() is S
    assert await tree.tick_once() is S
    assert stubs.starts("A") == 2


async def test_reactive_sequence_halts_later_running_child(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    # A RUNNING, then B RUNNING; then A RUNNING again: B (later, RUNNING) is halted.
    stubs.script("A", "RUNNING", "SUCCESS", "RUNNING")
    stubs.script("B", "RUNNING")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<ReactiveSequence><StubAction name="A"/><StubAction name="B"/></ReactiveSequence>'
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, R]
    assert stubs.log == ["A:start", "A:running", "B:start"]
    # A succeeded and was reset when B ran: next tick starts A again
    assert await tree.tick_exactly_once() is R
    assert stubs.log[3:] == ["A:start", "B:halted"]
    assert stubs.halts("B") == 1


async def test_sequence_child_returning_idle_is_a_logic_error(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "IDLE")
    tree = bt_factory.create_tree_from_text(tree_xml('<Sequence><StubAction name="A"/></Sequence>'))
    with pytest.raises(NodeError) as info:
        await tree.tick_exactly_once()
    assert "A" in info.value.node_path


async def test_reactive_sequence_with_async_leaf(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, manual_clock: ManualClock
):
    stubs.script("C", "SUCCESS", "SUCCESS", "FAILURE")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<ReactiveSequence><StubCondition name="C"/>'
            '<StubAsyncAction name="W" msec="1000"/></ReactiveSequence>'
        ),
        clock=manual_clock,
    )
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, R]
    assert await tree.tick_exactly_once() is F
    assert stubs.events("W") == ["run", "cancelled"]
    assert stubs.halts("W") == 1
