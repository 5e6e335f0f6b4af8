"""Condition attributes on any node: order, moments, halts, errors (BT.CPP 4.8 rules)."""

from __future__ import annotations

import enum
from pathlib import Path

import pytest

from aiobt.core.blackboard import Blackboard
from aiobt.core.errors import NodeError, TreeLoadError
from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, tree_xml

S, F, R, K, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED, Status.IDLE


async def test_pre_conditions_checked_in_order_failure_success_skip(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    xml = tree_xml('<StubAction name="A" _failureIf="f" _successIf="s" _skipIf="k"/>')
    results = []
    for f, s, k in ((1, 1, 1), (0, 1, 1), (0, 0, 1), (0, 0, 0)):
        bb = Blackboard.create()
        for key, value in (("f", f), ("s", s), ("k", k)):
            bb.set(key, value)
        tree = bt_factory.create_tree_from_text(xml, blackboard=bb)
        results.append(await tree.tick_exactly_once())
    assert results == [F, S, K, S]
    assert stubs.starts("A") == 1  # ticked only when no pre-condition decided


async def test_skip_if_is_not_checked_while_running(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    stubs.script("A", "R", "R", "S")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<StubAction name="A" _skipIf="skip" _failureIf="fail"/>')
    )
    tree.root_blackboard.set("skip", False)
    tree.root_blackboard.set("fail", False)
    assert await tree.tick_exactly_once() is R
    tree.root_blackboard.set("skip", True)
    tree.root_blackboard.set("fail", True)
    assert await tree.tick_exactly_once() is R
    assert await tree.tick_exactly_once() is S
    assert stubs.events("A") == ["start", "running", "running"]
    assert await tree.tick_exactly_once() is F  # IDLE again: _failureIf wins


async def test_while_false_halts_a_running_node_and_skips(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    stubs.script("A", "R")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            """<Sequence>
                 <StubAction name="A" _while="go" _onHalted="halts += 1" _post="post += 1"/>
               </Sequence>"""
        )
    )
    bb = tree.root_blackboard
    bb.set("go", True)
    bb.set("halts", 0)
    bb.set("post", 0)
    assert await tree.tick_exactly_once() is R
    assert await tree.tick_exactly_once() is R
    bb.set("go", False)
    assert await tree.tick_exactly_once() is K
    node = tree.find("A")
    assert node.status is IDLE
    assert stubs.events("A") == ["start", "running", "halted"]
    assert bb["halts"] == 1
    assert bb["post"] == 0  # SKIPPED runs no post-condition
    # while false at IDLE: skipped without a tick
    assert await tree.tick_exactly_once() is K
    assert stubs.starts("A") == 1


async def test_post_conditions_run_on_completion_before_the_status_change(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    stubs.script("A", "R", "S", "F")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<StubAction name="A" _onSuccess="ok += 1" _onFailure="ko += 1" _post="done += 1"/>'
        )
    )
    bb = tree.root_blackboard
    for key in ("ok", "ko", "done"):
        bb.set(key, 0)
    seen: list[tuple[str, int]] = []

    def listener(_stamp: float, node: TreeNode, _prev: Status, status: Status) -> None:
        if node.name == "A" and status.is_completed:
            seen.append((status.name, bb["done"]))

    tree.add_status_listener(listener)
    assert [await tree.tick_exactly_once() for _ in range(3)] == [R, S, F]
    assert (bb["ok"], bb["ko"], bb["done"]) == (1, 1, 2)
    assert seen == [("SUCCESS", 1), ("FAILURE", 2)]


async def test_pre_condition_results_also_run_post_conditions(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<StubAction name="A" _failureIf="1" _onFailure="ko := 1" _onSuccess="ok := 1"'
            ' _post="done := 1"/>'
        )
    )
    assert await tree.tick_exactly_once() is F
    assert tree.root_blackboard.snapshot() == {"ko": 1, "done": 1}
    assert stubs.starts("A") == 0


async def test_completed_node_checks_no_pre_condition(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    tree = bt_factory.create_tree_from_text(tree_xml('<StubAction name="A" _skipIf="skip"/>'))
    tree.root_blackboard.set("skip", False)
    node = tree.root
    assert await node.tick() is S  # ticked directly: nobody resets it
    tree.root_blackboard.set("skip", True)
    assert await node.tick() is S  # still SUCCESS: no pre-condition, no hook
    assert stubs.events("A") == ["start"]


async def test_on_halted_runs_on_every_halt(bt_factory: BehaviorTreeFactory, stubs: Stubs) -> None:
    stubs.script("B", "R")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            """<Sequence>
                 <Script code="h := 0; a := 0"/>
                 <AlwaysSuccess _onHalted="a += 1"/>
                 <StubAction name="B" _onHalted="h += 1"/>
               </Sequence>"""
        )
    )
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree("test")
    # as BT.CPP: halted by its parent and again by halt_tree's sweep
    assert tree.root_blackboard["h"] == 2
    assert tree.root_blackboard["a"] == 1


async def test_condition_attributes_on_control_nodes_and_subtrees(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
) -> None:
    xml = tree_xml(
        """<Sequence>
             <Script code="n := 0"/>
             <Sequence _skipIf="n > 0" _onSuccess="n += 1"><StubAction name="A"/></Sequence>
             <SubTree ID="Sub" _skipIf="n > 1" _onSuccess="n += 10"/>
           </Sequence>""",
        "MainTree",
        '<BehaviorTree ID="Sub"><StubAction name="B"/></BehaviorTree>',
    )
    tree = bt_factory.create_tree_from_text(xml)
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["n"] == 11
    assert stubs.starts("A") == 1
    assert stubs.starts("B") == 1


async def test_syntax_error_is_a_load_error_with_file_line_attribute_column_and_path(
    bt_factory: BehaviorTreeFactory, tmp_path: Path
) -> None:
    path = tmp_path / "tree.xml"
    path.write_text(tree_xml('<Sequence>\n  <AlwaysSuccess name="ok" _skipIf="a b"/>\n</Sequence>'))
    with pytest.raises(TreeLoadError) as info:
        bt_factory.create_tree_from_file(path)
    error = info.value
    assert error.file is not None
    assert error.file.endswith("tree.xml")
    assert error.line == 2
    assert error.node_path == "MainTree/Sequence/AlwaysSuccess[ok]"
    assert '_skipIf="a b"' in error.message
    assert "column 3" in error.message


async def test_script_node_syntax_error_is_a_load_error(bt_factory: BehaviorTreeFactory) -> None:
    with pytest.raises(TreeLoadError, match=r'code="x := 1 \+": column 9.*Script'):
        bt_factory.create_tree_from_text(tree_xml('<Script code="x := 1 +"/>'))


async def test_runtime_error_names_node_attribute_and_script(
    bt_factory: BehaviorTreeFactory,
) -> None:
    tree = bt_factory.create_tree_from_text(tree_xml('<AlwaysSuccess _skipIf="name"/>'))
    tree.root_blackboard.set("name", "text")
    with pytest.raises(NodeError) as info:
        await tree.tick_exactly_once()
    assert info.value.node_path == "MainTree/AlwaysSuccess"
    assert '_skipIf="name"' in str(info.value)
    assert "cannot be used as a bool" in str(info.value)


async def test_empty_condition_attribute_is_a_load_error(bt_factory: BehaviorTreeFactory) -> None:
    with pytest.raises(TreeLoadError, match='_while="": column 1: empty script'):
        bt_factory.create_tree_from_text(tree_xml('<AlwaysSuccess _while=""/>'))


class Color(enum.IntEnum):
    RED = 1
    GREEN = 2


async def test_scripting_enums(bt_factory: BehaviorTreeFactory) -> None:
    bt_factory.register_scripting_enums(Color)
    bt_factory.register_scripting_enum("BLUE", 7)
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            """<Sequence>
                 <Script code="c := GREEN; b := BLUE"/>
                 <AlwaysFailure _skipIf="c == GREEN"/>
               </Sequence>"""
        )
    )
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard.snapshot() == {"c": 2.0, "b": 7.0}
    with pytest.raises(ValueError, match="not an identifier"):
        bt_factory.register_scripting_enum("not valid", 1)
