"""Precondition: the ``if`` script gates its child; ``else`` when false."""

from __future__ import annotations

import pytest

from aiobt.core.errors import TreeLoadError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tree_xml

S, F, R, K = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED


@pytest.mark.parametrize(
    ("else_attr", "expected"), [("", F), ('else="SUCCESS"', S), ('else="SKIPPED"', K)]
)
async def test_false_returns_else_without_ticking(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, else_attr: str, expected: Status
) -> None:
    tree = bt_factory.create_tree_from_text(
        tree_xml(f'<Precondition if="ok" {else_attr}><StubAction name="A"/></Precondition>')
    )
    tree.root_blackboard.set("ok", False)
    assert await tree.tick_exactly_once() is expected
    assert stubs.ticks("A") == 0


async def test_condition_checked_only_before_the_child_runs(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    stubs.script("A", "R", "R", "S")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Precondition if="ok"><StubAction name="A"/></Precondition>')
    )
    bb = tree.root_blackboard
    bb.set("ok", True)
    assert await tree.tick_exactly_once() is R
    bb.set("ok", False)  # ignored while the child runs
    assert await tree.tick_exactly_once() is R
    assert await tree.tick_exactly_once() is S
    assert await tree.tick_exactly_once() is F  # checked again: false
    assert stubs.events("A") == ["start", "running", "running"]


async def test_halt_rearms_the_condition(bt_factory: BehaviorTreeFactory, stubs: Stubs) -> None:
    stubs.script("A", "R")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Precondition if="ok"><StubAction name="A"/></Precondition>')
    )
    tree.root_blackboard.set("ok", True)
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree("test")
    assert stubs.halts("A") == 1
    tree.root_blackboard.set("ok", False)
    assert await tree.tick_exactly_once() is F


async def test_bad_if_and_else_fail_at_load(bt_factory: BehaviorTreeFactory) -> None:
    with pytest.raises(TreeLoadError, match=r'if="ok &&": column 6'):
        bt_factory.create_tree_from_text(
            tree_xml('<Precondition if="ok &amp;&amp;"><AlwaysSuccess/></Precondition>')
        )
    with pytest.raises(TreeLoadError, match="not a node status"):
        bt_factory.create_tree_from_text(
            tree_xml('<Precondition if="1" else="MAYBE"><AlwaysSuccess/></Precondition>')
        )
