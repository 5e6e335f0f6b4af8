"""AlwaysSuccess, AlwaysFailure, SetBlackboard, UnsetBlackboard."""

from __future__ import annotations

import pytest

from aiobt.core.errors import BlackboardError, NodeError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import tree_xml

S, F = Status.SUCCESS, Status.FAILURE


@pytest.mark.parametrize(("node", "expected"), [("AlwaysSuccess", S), ("AlwaysFailure", F)])
async def test_always(bt_factory: BehaviorTreeFactory, node: str, expected: Status):
    tree = bt_factory.create_tree_from_text(tree_xml(f"<{node}/>"))
    assert await tree.tick_exactly_once() is expected
    assert tree.root.status is Status.IDLE


async def test_set_blackboard_literal_and_copy(bt_factory: BehaviorTreeFactory):
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Sequence><SetBlackboard value="42" output_key="answer"/>'
            '<SetBlackboard value="{answer}" output_key="copy"/></Sequence>'
        )
    )
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard.get("answer") == "42"
    assert tree.root_blackboard.get("copy") == "42"


async def test_set_blackboard_converts_to_typed_entry(bt_factory: BehaviorTreeFactory):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<SetBlackboard value="2.5" output_key="speed"/>')
    )
    tree.root_blackboard.set("speed", 1.0)
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard.get("speed") == 2.5


async def test_set_blackboard_bad_text_for_typed_entry(bt_factory: BehaviorTreeFactory):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<SetBlackboard value="fast" output_key="speed"/>')
    )
    tree.root_blackboard.set("speed", 1.0)
    with pytest.raises(NodeError) as info:
        await tree.tick_exactly_once()
    assert isinstance(info.value.cause, BlackboardError)
    assert "speed" in str(info.value)


async def test_set_blackboard_copy_keeps_type(bt_factory: BehaviorTreeFactory):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<SetBlackboard value="{src}" output_key="dst"/>')
    )
    tree.root_blackboard.set("src", [1, 2])
    assert await tree.tick_exactly_once() is S
    entry = tree.root_blackboard.entry("dst")
    assert entry is not None
    assert entry.value == [1, 2]
    assert entry.type is list


async def test_set_blackboard_copy_from_empty_entry_fails(bt_factory: BehaviorTreeFactory):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<SetBlackboard value="{src}" output_key="dst"/>')
    )
    tree.root_blackboard.create_entry("src", int)
    assert await tree.tick_exactly_once() is F
    assert "dst" not in tree.root_blackboard


async def test_set_blackboard_into_subtree_remapped_key(bt_factory: BehaviorTreeFactory):
    xml = tree_xml(
        '<SubTree ID="Inner" result="{outer}"/>',
        "MainTree",
        '<BehaviorTree ID="Inner"><SetBlackboard value="done" output_key="result"/></BehaviorTree>',
    )
    tree = bt_factory.create_tree_from_text(xml)
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard.get("outer") == "done"


async def test_unset_blackboard_removes_entry(bt_factory: BehaviorTreeFactory):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Sequence><UnsetBlackboard key="x"/><UnsetBlackboard key="missing"/></Sequence>')
    )
    tree.root_blackboard.set("x", 1)
    assert await tree.tick_exactly_once() is S
    assert "x" not in tree.root_blackboard
    assert tree.root_blackboard.entry("x") is None
