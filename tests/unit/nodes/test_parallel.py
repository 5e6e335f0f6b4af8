"""Parallel and ParallelAll: thresholds, negative counts, halting, errors."""

from __future__ import annotations

import pytest

from aiobt.core.errors import NodeError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tick_statuses, tree_xml

S, F, R, K, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED, Status.IDLE

THREE = '<StubAction name="A"/><StubAction name="B"/><StubAction name="C"/>'


def _parallel(factory: BehaviorTreeFactory, attributes: str, body: str = THREE):
    return factory.create_tree_from_text(tree_xml(f"<Parallel {attributes}>{body}</Parallel>"))


async def test_parallel_success_count_halts_the_rest(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "RUNNING", "SUCCESS")
    stubs.script("B", "RUNNING", "RUNNING", "SUCCESS")
    stubs.script("C", "RUNNING")
    tree = _parallel(bt_factory, 'success_count="2" failure_count="2"')
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, R, S]
    assert stubs.log == [
        "A:start", "B:start", "C:start",
        "A:running", "B:running", "C:running",
        "B:running", "C:halted",
    ]  # fmt: skip
    assert all(node.status is IDLE for node in tree.nodes())


async def test_parallel_default_fails_on_first_failure(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "RUNNING")
    stubs.script("B", "FAILURE")
    stubs.script("C", "RUNNING")
    tree = _parallel(bt_factory, "")
    assert await tick_statuses(tree.tick_exactly_once, 2) == [F, F]
    # thresholds are checked after each child: C is never ticked
    assert stubs.log == ["A:start", "B:start", "A:halted"] * 2


async def test_parallel_success_count_zero_succeeds_after_first_child(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "RUNNING", "FAILURE")
    stubs.script("B", "RUNNING")
    tree = _parallel(
        bt_factory,
        'success_count="0" failure_count="1"',
        '<StubAction name="A"/><StubAction name="B"/>',
    )
    assert await tick_statuses(tree.tick_exactly_once, 2) == [S, S]
    assert stubs.log == ["A:start", "A:halted", "A:start"]


async def test_parallel_negative_counts(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "FAILURE")
    stubs.script("C", "RUNNING", "SUCCESS")
    tree = _parallel(bt_factory, 'success_count="-2" failure_count="-1"')
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, S]
    assert stubs.log == ["A:start", "B:start", "C:start", "C:running"]


async def test_parallel_fails_when_success_becomes_impossible(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "FAILURE")
    stubs.script("B", "RUNNING")
    tree = _parallel(bt_factory, 'success_count="3" failure_count="2"')
    assert await tick_statuses(tree.tick_exactly_once, 2) == [F, F]
    assert stubs.log == ["A:start", "A:start"]


async def test_parallel_failure_count_reached_exactly(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "FAILURE")
    stubs.script("B", "RUNNING", "FAILURE")
    stubs.script("C", "RUNNING")
    tree = _parallel(bt_factory, 'success_count="1" failure_count="2"')
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, F]
    assert stubs.halts("C") == 1


@pytest.mark.parametrize("attributes", ['success_count="4"', 'failure_count="4"'])
async def test_parallel_threshold_above_children_throws(
    bt_factory: BehaviorTreeFactory, attributes: str
):
    tree = _parallel(bt_factory, attributes)
    with pytest.raises(NodeError, match="number of children"):
        await tree.tick_exactly_once()


async def test_parallel_halt_tree_halts_running_children(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    for name in "ABC":
        stubs.script(name, "RUNNING")
    tree = _parallel(bt_factory, "")
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree("stop")
    assert [stubs.halts(n) for n in "ABC"] == [1, 1, 1]
    assert await tree.tick_exactly_once() is R
    assert [stubs.starts(n) for n in "ABC"] == [2, 2, 2]


async def test_parallel_all_waits_for_every_child(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "FAILURE")
    stubs.script("B", "RUNNING", "SUCCESS")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<ParallelAll max_failures="1"><StubAction name="A"/><StubAction name="B"/>'
            "</ParallelAll>"
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, F]
    assert stubs.log == ["A:start", "B:start", "B:running"]  # A not re-ticked


async def test_parallel_all_max_failures_zero_always_fails(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<ParallelAll max_failures="0"><StubAction name="A"/><StubAction name="B"/>'
            "</ParallelAll>"
        )
    )
    assert await tree.tick_exactly_once() is F


async def test_parallel_all_below_max_failures_succeeds(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("A", "FAILURE")
    tree = bt_factory.create_tree_from_text(
        tree_xml(f'<ParallelAll max_failures="2">{THREE}</ParallelAll>')
    )
    assert await tree.tick_exactly_once() is S


async def test_parallel_all_max_failures_above_children_throws(bt_factory: BehaviorTreeFactory):
    tree = bt_factory.create_tree_from_text(
        tree_xml(f'<ParallelAll max_failures="4">{THREE}</ParallelAll>')
    )
    with pytest.raises(NodeError):
        await tree.tick_exactly_once()
