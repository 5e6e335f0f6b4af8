"""Script, ScriptCondition and the entry-updated nodes, scenario by scenario."""

from __future__ import annotations

import pytest

from aiobt.core.errors import NodeError, TreeLoadError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tree_xml

S, F, R, K, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED, Status.IDLE


async def test_script_writes_the_blackboard_and_succeeds(bt_factory: BehaviorTreeFactory) -> None:
    tree = bt_factory.create_tree_from_text(
        tree_xml("<Script code=\"n := 2; msg := 'n=' .. n; @top := n * 1.5\"/>")
    )
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard.snapshot() == {"n": 2, "msg": "n=2", "top": 3.0}


async def test_empty_script_does_nothing(bt_factory: BehaviorTreeFactory) -> None:
    tree = bt_factory.create_tree_from_text(tree_xml('<Script code=""/>'))
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard.snapshot() == {}


async def test_script_code_from_the_blackboard_is_recompiled_when_it_changes(
    bt_factory: BehaviorTreeFactory,
) -> None:
    tree = bt_factory.create_tree_from_text(tree_xml('<Script code="{program}"/>'))
    bb = tree.root_blackboard
    bb.set("program", "x := 1")
    assert await tree.tick_exactly_once() is S
    bb.set("program", "x += 41")
    assert await tree.tick_exactly_once() is S
    assert bb["x"] == 42
    bb.set("program", "x +")
    with pytest.raises(NodeError, match=r'code="x \+": column 4'):
        await tree.tick_exactly_once()


async def test_script_runtime_error_names_the_node(bt_factory: BehaviorTreeFactory) -> None:
    tree = bt_factory.create_tree_from_text(tree_xml('<Script name="init" code="a = 1"/>'))
    with pytest.raises(NodeError) as info:
        await tree.tick_exactly_once()
    assert info.value.node_path == "MainTree/Script[init]"
    assert "[a] does not exist yet" in str(info.value)


@pytest.mark.parametrize(
    ("code", "expected"),
    [("x == 3", S), ("x == 4", F), ("x > 1 &amp;&amp; x &lt; 5", S), ("0.5", S), ("false", F)],
)
async def test_script_condition(
    bt_factory: BehaviorTreeFactory, code: str, expected: Status
) -> None:
    tree = bt_factory.create_tree_from_text(
        tree_xml(f'<Sequence><Script code="x := 3"/><ScriptCondition code="{code}"/></Sequence>')
    )
    assert await tree.tick_exactly_once() is expected


@pytest.mark.parametrize("code", ["'text'", "2", "x"])
async def test_script_condition_rejects_non_bools(
    bt_factory: BehaviorTreeFactory, code: str
) -> None:
    tree = bt_factory.create_tree_from_text(
        tree_xml(f'<Sequence><Script code="x := 3"/><ScriptCondition code="{code}"/></Sequence>')
    )
    with pytest.raises(NodeError, match="bool"):
        await tree.tick_exactly_once()


async def test_script_condition_needs_code(bt_factory: BehaviorTreeFactory) -> None:
    with pytest.raises(TreeLoadError, match="empty script"):
        bt_factory.create_tree_from_text(tree_xml('<ScriptCondition code=""/>'))


async def test_was_entry_updated(bt_factory: BehaviorTreeFactory) -> None:
    tree = bt_factory.create_tree_from_text(tree_xml('<WasEntryUpdated entry="{goal}"/>'))
    bb = tree.root_blackboard
    assert await tree.tick_exactly_once() is F  # no such entry
    bb.set("goal", 1)
    assert await tree.tick_exactly_once() is S
    assert await tree.tick_exactly_once() is F
    bb.set("goal", 1)  # same value, written again: updated
    assert await tree.tick_exactly_once() is S


async def test_skip_unless_updated(bt_factory: BehaviorTreeFactory, stubs: Stubs) -> None:
    stubs.script("Plan", "R", "S")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<SkipUnlessUpdated entry="goal"><StubAction name="Plan"/></SkipUnlessUpdated>')
    )
    bb = tree.root_blackboard
    assert await tree.tick_exactly_once() is K
    bb.set("goal", "A")
    assert await tree.tick_exactly_once() is R
    # a RUNNING child goes on without a new write
    assert await tree.tick_exactly_once() is S
    assert await tree.tick_exactly_once() is K
    assert stubs.starts("Plan") == 1


async def test_wait_value_update(bt_factory: BehaviorTreeFactory) -> None:
    tree = bt_factory.create_tree_from_text(
        tree_xml('<WaitValueUpdate entry="{goal}"><Script code="n += 1"/></WaitValueUpdate>')
    )
    bb = tree.root_blackboard
    bb.set("n", 0)
    bb.set("goal", 1)
    assert await tree.tick_exactly_once() is S  # written before the first look
    assert await tree.tick_exactly_once() is R
    assert await tree.tick_exactly_once() is R
    bb.set("goal", 2)
    assert await tree.tick_exactly_once() is S
    assert bb["n"] == 2


async def test_entry_port_is_required(bt_factory: BehaviorTreeFactory) -> None:
    with pytest.raises(TreeLoadError, match=r"port \[entry\]"):
        bt_factory.create_tree_from_text(tree_xml("<WasEntryUpdated/>"))
