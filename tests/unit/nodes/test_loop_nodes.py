"""LoopInt/LoopDouble/LoopString/LoopBool: one child run per queue item."""

from __future__ import annotations

from collections import deque

import pytest

from aiobt.core.errors import NodeError, TreeLoadError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tree_xml

S, F, R, K = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED

SUM = '<Loop{kind} queue="{queue}" value="{{v}}"{extra}><Script code="acc += v"/></Loop{kind}>'


async def run_loop(
    factory: BehaviorTreeFactory, kind: str, queue: str, extra: str = "", **entries: object
) -> tuple[list[Status], dict[str, object]]:
    tree = factory.create_tree_from_text(tree_xml(SUM.format(kind=kind, queue=queue, extra=extra)))
    bb = tree.root_blackboard
    bb.set("acc", entries.pop("acc", 0))
    for key, value in entries.items():
        bb.set(key, value)
    statuses = [await tree.tick_exactly_once() for _ in range(4)]
    return statuses, bb.snapshot()


async def test_loop_int_literal_queue(bt_factory: BehaviorTreeFactory) -> None:
    statuses, bb = await run_loop(bt_factory, "Int", "1;2;3")
    assert statuses == [R, R, R, S]
    assert bb["acc"] == 6
    assert bb["v"] == 3
    assert type(bb["v"]) is int


async def test_literal_queue_restarts_on_every_run(bt_factory: BehaviorTreeFactory) -> None:
    tree = bt_factory.create_tree_from_text(tree_xml(SUM.format(kind="Int", queue="5", extra="")))
    tree.root_blackboard.set("acc", 0)
    assert [await tree.tick_exactly_once() for _ in range(4)] == [R, S, R, S]
    assert tree.root_blackboard["acc"] == 10


async def test_loop_double_and_string_and_bool(bt_factory: BehaviorTreeFactory) -> None:
    _, bb = await run_loop(bt_factory, "Double", "0.5;1.25;0.25", acc=0.0)
    assert bb["acc"] == 2.0
    _, bb = await run_loop(bt_factory, "String", "a;b;c", acc="")
    assert bb["acc"] == "abc"
    _, bb = await run_loop(bt_factory, "Bool", "true;false;1", acc=0)
    assert bb["acc"] == 2
    assert bb["v"] is True


async def test_deque_on_the_blackboard_is_consumed_in_place(
    bt_factory: BehaviorTreeFactory,
) -> None:
    queue = deque([4, 5])
    statuses, bb = await run_loop(bt_factory, "Int", "{q}", q=queue)
    assert statuses == [R, R, S, S]
    assert bb["acc"] == 9
    assert not queue  # shared: others see it emptied


async def test_list_and_string_on_the_blackboard_are_copied(
    bt_factory: BehaviorTreeFactory,
) -> None:
    waypoints = [1, 2]
    statuses, bb = await run_loop(bt_factory, "Int", "{q}", q=waypoints)
    assert statuses == [R, R, S, R]  # a new run reads the list again
    assert bb["acc"] == 4
    assert waypoints == [1, 2]
    _, bb = await run_loop(bt_factory, "Int", "{q}", q="7;8")
    assert bb["acc"] == 15 + 7


@pytest.mark.parametrize(("if_empty", "expected"), [("", S), ("FAILURE", F), ("SKIPPED", K)])
async def test_empty_queue_returns_if_empty(
    bt_factory: BehaviorTreeFactory, if_empty: str, expected: Status
) -> None:
    extra = f' if_empty="{if_empty}"' if if_empty else ""
    statuses, bb = await run_loop(bt_factory, "Int", "{q}", extra, q=[])
    assert statuses[0] is expected
    assert bb["acc"] == 0


async def test_child_failure_fails_and_running_child_keeps_its_item(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    stubs.script("Visit", "R", "S", "F")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<LoopInt queue="1;2;3" value="{v}"><StubAction name="Visit"/></LoopInt>')
    )
    bb = tree.root_blackboard
    assert await tree.tick_exactly_once() is R
    assert bb["v"] == 1
    assert await tree.tick_exactly_once() is R  # item 1 finished
    assert bb["v"] == 1
    assert await tree.tick_exactly_once() is F  # item 2 failed
    assert bb["v"] == 2


async def test_halt_stops_the_child(bt_factory: BehaviorTreeFactory, stubs: Stubs) -> None:
    stubs.script("Visit", "R")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<LoopInt queue="1;2" value="{v}"><StubAction name="Visit"/></LoopInt>')
    )
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree("test")
    assert stubs.halts("Visit") == 1
    assert await tree.tick_exactly_once() is R
    assert tree.root_blackboard["v"] == 1  # a fresh run starts from the first item


async def test_bad_items_and_queue_types(bt_factory: BehaviorTreeFactory) -> None:
    with pytest.raises(TreeLoadError, match="cannot create"):
        bt_factory.create_tree_from_text(tree_xml(SUM.format(kind="Int", queue="1;x", extra="")))
    tree = bt_factory.create_tree_from_text(tree_xml(SUM.format(kind="Int", queue="{q}", extra="")))
    tree.root_blackboard.set("q", 3.5)
    with pytest.raises(NodeError, match=r"port \[queue\] must hold"):
        await tree.tick_exactly_once()
