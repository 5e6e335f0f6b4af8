"""Substitution rules: swap nodes by name, ID or path wildcard for stubs or test nodes."""

from __future__ import annotations

import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.errors import TreeLoadError
from aiobt.core.manifest import TestNodeConfig
from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, settle, tree_xml

MISSION = tree_xml(
    '<Sequence name="main">'
    '<Sleep name="wait_dock" msec="100000"/>'
    '<AlwaysFailure name="undock"/>'
    '<Fallback name="nav"><AlwaysFailure name="move_fast"/><AlwaysFailure name="move_slow"/>'
    "</Fallback></Sequence>"
)


async def test_substitute_by_id_with_stub(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    bt_factory.add_substitution_rule("AlwaysFailure", "StubAction")
    bt_factory.add_substitution_rule("Sleep", "AlwaysSuccess")
    tree = bt_factory.create_tree_from_text(MISSION)
    assert await tree.tick_exactly_once() is Status.SUCCESS
    assert stubs.log == ["undock:start", "move_fast:start"]


async def test_substitute_by_name_wildcard(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    bt_factory.add_substitution_rule("move_*", "StubAction")
    bt_factory.add_substitution_rule("wait_dock", "AlwaysSuccess")
    bt_factory.add_substitution_rule("undock", "AlwaysSuccess")
    stubs.script("move_fast", "FAILURE")
    tree = bt_factory.create_tree_from_text(MISSION)
    assert await tree.tick_exactly_once() is Status.SUCCESS
    assert stubs.log == ["move_fast:start", "move_slow:start"]


async def test_substitute_by_path_with_test_node_config(manual_clock: ManualClock):
    done: list[str] = []

    def completed(node: TreeNode) -> None:
        done.append(node.name)

    factory = BehaviorTreeFactory()
    # the first matching rule wins; brackets in paths are literal, not glob classes
    factory.add_substitution_rule(
        "MainTree/Sequence[main]/Fallback[nav]/*",
        TestNodeConfig(Status.SUCCESS, delay=2.0, on_complete=completed),
    )
    factory.add_substitution_rule("MainTree/Sequence[main]/*", TestNodeConfig(Status.SUCCESS))
    tree = factory.create_tree_from_text(MISSION, clock=manual_clock)
    assert await tree.tick_exactly_once() is Status.RUNNING  # move_fast: 2 s of clock time
    await settle()
    await manual_clock.forward(2.0, step=0.5)
    assert await tree.tick_exactly_once() is Status.SUCCESS
    assert done == ["move_fast"]
    assert manual_clock.now() == 2.0


async def test_test_node_config_keeps_control_nodes(bt_factory: BehaviorTreeFactory):
    bt_factory.add_substitution_rule("*", TestNodeConfig(Status.FAILURE))
    tree = bt_factory.create_tree_from_text(MISSION)
    assert type(tree.root).__name__ == "Sequence"
    assert await tree.tick_exactly_once() is Status.FAILURE
    assert tree.find("wait_dock").status is Status.IDLE


def test_substitution_keeps_port_validation(bt_factory: BehaviorTreeFactory):
    bt_factory.add_substitution_rule("Sleep", TestNodeConfig())
    with pytest.raises(TreeLoadError, match=r"\[mesc\]"):
        bt_factory.create_tree_from_text(tree_xml('<Sleep mesc="1"/>'))


def test_substitution_by_unknown_id_is_an_error(bt_factory: BehaviorTreeFactory):
    bt_factory.add_substitution_rule("Sleep", "Slep")
    with pytest.raises(TreeLoadError, match=r"unknown node ID \[Slep\]"):
        bt_factory.create_tree_from_text(tree_xml('<Sleep msec="1"/>'))


def test_leaf_cannot_be_replaced_by_control(bt_factory: BehaviorTreeFactory):
    bt_factory.add_substitution_rule("AlwaysSuccess", "Sequence")
    with pytest.raises(TreeLoadError, match="cannot replace"):
        bt_factory.create_tree_from_text(tree_xml("<AlwaysSuccess/>"))


def test_wildcards_are_star_and_question_mark_only(bt_factory: BehaviorTreeFactory):
    bt_factory.add_substitution_rule("Always?ailure", "AlwaysSuccess")
    bt_factory.add_substitution_rule("[A]*", "AlwaysFailure")  # no glob classes
    tree = bt_factory.create_tree_from_text(tree_xml("<AlwaysFailure/>"))
    assert type(tree.root).__name__ == "AlwaysSuccess"


def test_test_node_config_is_not_collected():
    assert TestNodeConfig.__test__ is False
