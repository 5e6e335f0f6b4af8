"""Blackboard: typed entries, sequence id and stamp, SubTree scoping, remapping."""

from __future__ import annotations

import pytest

from aiobt.core.blackboard import Blackboard
from aiobt.core.clock import ManualClock
from aiobt.core.errors import BlackboardError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import tree_xml


def test_entry_type_is_fixed_by_first_write():
    bb = Blackboard.create()
    bb.set("count", 3)
    bb.set("count", "7")  # text converts to the entry's type
    assert bb["count"] == 7
    bb.set("count", 8.0)  # an integral float fits an int entry
    assert bb.get("count") == 8
    assert isinstance(bb.get("count"), int)
    with pytest.raises(BlackboardError) as info:
        bb.set("count", "seven")
    assert "[count]" in str(info.value)
    assert "int" in str(info.value)


def test_type_error_names_key_and_both_types():
    bb = Blackboard.create()
    bb.set("pose", [1.0, 2.0])
    with pytest.raises(BlackboardError) as info:
        bb.set("pose", {"x": 1})
    message = str(info.value)
    assert "[pose]" in message
    assert "list" in message
    assert "dict" in message


def test_int_goes_into_float_entry():
    bb = Blackboard.create()
    bb.set("speed", 0.5)
    bb.set("speed", 2)
    assert bb["speed"] == 2.0
    assert isinstance(bb["speed"], float)


def test_declared_entry_without_value():
    bb = Blackboard.create()
    entry = bb.create_entry("goal", float)
    assert not entry.has_value
    assert "goal" not in bb
    assert bb.get("goal", "none") == "none"
    with pytest.raises(BlackboardError, match=r"\[goal\]"):
        _ = bb["goal"]
    bb.set("goal", "1.5")
    assert bb["goal"] == 1.5


def test_string_entry_stays_untyped_until_typed_write():
    bb = Blackboard.create()
    bb.set("v", "42")
    bb.set("v", 42)  # an untyped entry written with text accepts any type afterwards
    assert bb["v"] == 42


def test_sequence_id_and_stamp_follow_the_clock():
    clock = ManualClock(100.0)
    bb = Blackboard.create()
    bb.now = clock.now
    bb.set("x", 1)
    entry = bb.entry("x")
    assert entry is not None
    assert (entry.sequence_id, entry.stamp) == (1, 100.0)
    clock.advance(2.5)
    bb.set("x", 2)
    assert (entry.sequence_id, entry.stamp) == (2, 102.5)


def test_child_scope_remapping_autoremap_private_and_root():
    root = Blackboard.create()
    child = Blackboard.create(root)
    child.add_remapping("target", "goal")
    child.set("target", 5)
    child.set("local", 1)
    assert root["goal"] == 5
    assert "local" not in root
    assert "goal" not in child  # not remapped: invisible

    auto = Blackboard.create(root, autoremap=True)
    auto.set("shared", "yes")
    auto.set("_private", "mine")
    assert root["shared"] == "yes"
    assert "_private" not in root
    assert auto["goal"] == 5

    grandchild = Blackboard.create(child)
    grandchild.set("@top", 1)
    assert root["top"] == 1
    assert grandchild["@goal"] == 5
    grandchild.unset("@top")
    assert "top" not in root


def test_unset_and_snapshot():
    bb = Blackboard.create()
    bb["a"] = 1
    bb["b"] = "two"
    assert bb.snapshot() == {"a": 1, "b": "two"}
    assert sorted(bb.keys()) == ["a", "b"]
    bb.unset("a")
    bb.unset("never")
    assert bb.snapshot() == {"b": "two"}


SUBTREE = """
<BehaviorTree ID="Inner">
  <Sequence>
    <SetBlackboard value="inner" output_key="local"/>
    <SetBlackboard value="{param}" output_key="echo"/>
    <SetBlackboard value="to-root" output_key="@root_key"/>
    <SetBlackboard value="hidden" output_key="_private"/>
  </Sequence>
</BehaviorTree>
"""


async def test_subtree_scoping_with_explicit_remapping(manual_clock: ManualClock):
    factory = BehaviorTreeFactory()
    tree = factory.create_tree_from_text(
        tree_xml('<SubTree ID="Inner" param="7" echo="{out}"/>', "Main", SUBTREE),
        clock=manual_clock,
    )
    assert await tree.tick_exactly_once() is Status.SUCCESS
    root = tree.root_blackboard
    assert root["out"] == "7"  # literal remap seeds the subtree entry; echo is remapped
    assert root["root_key"] == "to-root"
    assert "local" not in root
    assert "_private" not in root
    assert "param" not in root


async def test_subtree_autoremap_shares_all_but_private():
    factory = BehaviorTreeFactory()
    tree = factory.create_tree_from_text(
        tree_xml('<SubTree ID="Inner" _autoremap="true"/>', "Main", SUBTREE)
    )
    tree.root_blackboard.set("param", "from-parent")
    assert await tree.tick_exactly_once() is Status.SUCCESS
    root = tree.root_blackboard
    assert root["local"] == "inner"
    assert root["echo"] == "from-parent"
    assert "_private" not in root


async def test_subtree_remapped_output_keeps_parent_type():
    factory = BehaviorTreeFactory()
    tree = factory.create_tree_from_text(
        tree_xml(
            '<SubTree ID="Inner" value="{speed}"/>',
            "Main",
            '<BehaviorTree ID="Inner"><SetBlackboard value="3" output_key="value"/></BehaviorTree>',
        )
    )
    tree.root_blackboard.set("speed", 1.5)
    assert await tree.tick_exactly_once() is Status.SUCCESS
    assert tree.root_blackboard["speed"] == 3.0
