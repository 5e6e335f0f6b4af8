"""IfThenElse and WhileDoElse: branch choice, re-checking, halts, errors."""

from __future__ import annotations

import pytest

from aiobt.core.errors import NodeError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tick_statuses, tree_xml

S, F, R, K, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED, Status.IDLE

ITE3 = (
    '<IfThenElse><StubCondition name="C"/><StubAction name="T"/><StubAction name="E"/></IfThenElse>'
)
WDE3 = (
    '<WhileDoElse><StubCondition name="C"/><StubAction name="D"/>'
    '<StubAction name="E"/></WhileDoElse>'
)


async def test_if_then_else_does_not_recheck_condition_while_branch_runs(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("C", "SUCCESS", "FAILURE")
    stubs.script("T", "RUNNING", "RUNNING", "SUCCESS")
    tree = bt_factory.create_tree_from_text(tree_xml(ITE3))
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, R, S]
    assert stubs.log == ["C:check", "T:start", "T:running", "T:running"]


async def test_if_then_else_else_branch_then_then_branch(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("C", "FAILURE", "SUCCESS")
    stubs.script("E", "RUNNING", "SUCCESS")
    tree = bt_factory.create_tree_from_text(tree_xml(ITE3))
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, S, S]
    assert stubs.log == ["C:check", "E:start", "E:running", "C:check", "T:start"]


async def test_if_then_else_branch_result_passes_through(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("E", "FAILURE")
    stubs.script("C", "FAILURE")
    tree = bt_factory.create_tree_from_text(tree_xml(ITE3))
    assert await tree.tick_exactly_once() is F
    assert all(node.status is IDLE for node in tree.nodes())


async def test_if_then_else_running_condition(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("C", "RUNNING", "FAILURE")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<IfThenElse><StubAction name="C"/><StubAction name="T"/>'
            '<StubAction name="E"/></IfThenElse>'
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, S]
    assert stubs.log == ["C:start", "C:running", "E:start"]


async def test_two_child_if_then_else_keeps_failed_condition_status(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    # BT.CPP: the failed stateful condition is not reset, so it is not called again
    stubs.script("C", "FAILURE", "SUCCESS")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Sequence><IfThenElse><StubAction name="C"/><StubAction name="T"/>'
            "</IfThenElse></Sequence>"
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 3) == [F, F, F]
    assert stubs.log == ["C:start"]
    assert stubs.ticks("C") == 3


async def test_if_then_else_skipped_condition_throws(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("C", "SKIPPED")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<IfThenElse><StubAction name="C"/><StubAction name="T"/></IfThenElse>')
    )
    with pytest.raises(NodeError, match="IfThenElse"):
        await tree.tick_exactly_once()


@pytest.mark.parametrize("control", ["IfThenElse", "WhileDoElse"])
@pytest.mark.parametrize("count", [1, 4])
async def test_wrong_child_count_loads_and_throws_at_tick(
    bt_factory: BehaviorTreeFactory, control: str, count: int
):
    children = "".join(f'<StubAction name="N{i}"/>' for i in range(count))
    tree = bt_factory.create_tree_from_text(tree_xml(f"<{control}>{children}</{control}>"))
    with pytest.raises(NodeError, match="2 or 3 children") as info:
        await tree.tick_exactly_once()
    assert control in info.value.node_path


async def test_while_do_else_rechecks_and_switches_branch(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("C", "SUCCESS", "FAILURE", "SUCCESS")
    stubs.script("D", "RUNNING")
    stubs.script("E", "RUNNING")
    tree = bt_factory.create_tree_from_text(tree_xml(WDE3))
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, R, R]
    assert stubs.log == [
        "C:check", "D:start",
        "C:check", "D:halted", "E:start",
        "C:check", "E:halted", "D:start",
    ]  # fmt: skip


async def test_while_do_else_two_children_fails_and_halts_do(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("C", "SUCCESS", "FAILURE")
    stubs.script("D", "RUNNING")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<WhileDoElse><StubCondition name="C"/><StubAction name="D"/></WhileDoElse>')
    )
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, F]
    assert stubs.log == ["C:check", "D:start", "C:check", "D:halted"]


async def test_while_do_else_stateful_first_child_keeps_success(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    # BT.CPP: the first child stays SUCCESS while the branch runs, so a stateful
    # action there is not called again
    stubs.script("D", "RUNNING")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<WhileDoElse><StubAction name="C"/><StubAction name="D"/>'
            '<StubAction name="E"/></WhileDoElse>'
        )
    )
    assert await tick_statuses(tree.tick_exactly_once, 3) == [R, R, R]
    assert stubs.log == ["C:start", "D:start", "D:running", "D:running"]
    assert stubs.ticks("C") == 3


async def test_while_do_else_skipped_condition_throws(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("C", "SKIPPED")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<WhileDoElse><StubAction name="C"/><StubAction name="D"/></WhileDoElse>')
    )
    with pytest.raises(NodeError):
        await tree.tick_exactly_once()


async def test_while_do_else_finished_branch_resets_all(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("D", "RUNNING", "SUCCESS")
    tree = bt_factory.create_tree_from_text(tree_xml(WDE3))
    assert await tick_statuses(tree.tick_exactly_once, 2) == [R, S]
    assert all(node.status is IDLE for node in tree.nodes())
