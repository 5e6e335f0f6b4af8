"""Loading trees: compact and explicit syntax, several trees, SubTree, include, v3 files."""

from __future__ import annotations

import logging
from pathlib import Path

import pytest

from aiobt.core.errors import TreeLoadError
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.nodes.control.sequence_with_memory import SequenceWithMemory
from aiobt.nodes.subtree import SubTreeNode
from aiobt.testing.stubs import Stubs, tree_xml


async def test_explicit_and_compact_syntax_build_the_same_tree(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    compact = tree_xml(
        '<Sequence><Inverter><StubCondition name="C" results="F"/></Inverter>'
        '<StubAction name="A"/></Sequence>'
    )
    explicit = tree_xml(
        '<Control ID="Sequence"><Decorator ID="Inverter">'
        '<Condition ID="StubCondition" name="C" results="F"/></Decorator>'
        '<Action ID="StubAction" name="A"/></Control>'
    )
    shapes = []
    for text in (compact, explicit):
        tree = bt_factory.create_tree_from_text(text)
        assert await tree.tick_exactly_once() is Status.SUCCESS
        shapes.append([(type(n).__name__, n.name, n.path) for n in tree.nodes()])
    assert shapes[0] == shapes[1]
    assert stubs.log == ["C:check", "A:start"] * 2


async def test_several_trees_and_main_tree_to_execute(bt_factory: BehaviorTreeFactory):
    text = """
    <root BTCPP_format="4" main_tree_to_execute="Second">
      <BehaviorTree ID="First"><AlwaysFailure/></BehaviorTree>
      <BehaviorTree ID="Second"><SubTree ID="First"/></BehaviorTree>
    </root>"""
    tree = bt_factory.create_tree_from_text(text)
    assert tree.tree_id == "Second"
    assert await tree.tick_exactly_once() is Status.FAILURE
    ids = bt_factory.register_behavior_tree_from_text(text)
    assert ids == ["First", "Second"]
    assert bt_factory.registered_behavior_trees() == ["First", "Second"]
    assert bt_factory.create_tree().tree_id == "Second"
    assert bt_factory.create_tree("First").tree_id == "First"


async def test_create_from_same_text_twice(bt_factory: BehaviorTreeFactory):
    text = tree_xml("<AlwaysSuccess/>")
    first = bt_factory.create_tree_from_text(text)
    second = bt_factory.create_tree_from_text(text)
    assert first.root is not second.root
    assert bt_factory.registered_behavior_trees() == []


async def test_registered_subtree_visible_from_created_text(bt_factory: BehaviorTreeFactory):
    bt_factory.register_behavior_tree_from_text(
        '<root BTCPP_format="4"><BehaviorTree ID="Lib"><AlwaysFailure/></BehaviorTree></root>'
    )
    tree = bt_factory.create_tree_from_text(tree_xml('<Inverter><SubTree ID="Lib"/></Inverter>'))
    assert await tree.tick_exactly_once() is Status.SUCCESS


async def test_subtree_remapping_and_autoremap(bt_factory: BehaviorTreeFactory):
    text = """
    <root BTCPP_format="4" main_tree_to_execute="Main">
      <BehaviorTree ID="Main">
        <Sequence>
          <SubTree ID="Copy" name="explicit" src="{a}" dst="{b}"/>
          <SubTree ID="Copy" name="auto" _autoremap="true"/>
          <SubTree ID="Copy" name="literal" src="5" dst="{c}"/>
        </Sequence>
      </BehaviorTree>
      <BehaviorTree ID="Copy">
        <SetBlackboard value="{src}" output_key="dst"/>
      </BehaviorTree>
    </root>"""
    tree = bt_factory.create_tree_from_text(text)
    bb = tree.root_blackboard
    bb.set("a", "A")
    bb.set("src", "S")
    assert await tree.tick_exactly_once() is Status.SUCCESS
    assert (bb["b"], bb["dst"], bb["c"]) == ("A", "S", "5")
    subtrees = [n for n in tree.nodes() if isinstance(n, SubTreeNode)]
    assert [n.path for n in subtrees] == [
        "Main/Sequence/Copy[explicit]",
        "Main/Sequence/Copy[auto]",
        "Main/Sequence/Copy[literal]",
    ]
    assert tree.find("Main/Sequence/Copy[auto]/SetBlackboard").status is Status.IDLE


async def test_subtree_halt_reaches_inner_nodes(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    text = tree_xml(
        '<SubTree ID="Inner"/>',
        "Main",
        '<BehaviorTree ID="Inner"><StubAction name="A" results="R"/></BehaviorTree>',
    )
    tree = bt_factory.create_tree_from_text(text)
    assert await tree.tick_exactly_once() is Status.RUNNING
    await tree.halt_tree("stop")
    assert stubs.halts("A") == 1


def _write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


async def test_include_paths_are_relative_to_the_including_file(tmp_path: Path):
    _write(
        tmp_path / "common.xml",
        '<root BTCPP_format="4"><BehaviorTree ID="Common"><AlwaysSuccess/></BehaviorTree></root>',
    )
    _write(
        tmp_path / "lib" / "inner.xml",
        '<root BTCPP_format="4"><include path="../common.xml"/>'
        '<BehaviorTree ID="Inner"><SubTree ID="Common"/></BehaviorTree></root>',
    )
    main = _write(
        tmp_path / "main.xml",
        '<root BTCPP_format="4" main_tree_to_execute="Main"><include path="lib/inner.xml"/>'
        '<BehaviorTree ID="Main"><SubTree ID="Inner"/></BehaviorTree></root>',
    )
    tree = BehaviorTreeFactory().create_tree_from_file(main)
    assert await tree.tick_exactly_once() is Status.SUCCESS
    assert tree.source == str(main)


def test_include_cycle_is_a_load_error(tmp_path: Path):
    _write(tmp_path / "a.xml", '<root BTCPP_format="4">\n<include path="b.xml"/>\n</root>')
    _write(
        tmp_path / "b.xml",
        '<root BTCPP_format="4">\n<BehaviorTree ID="B"><AlwaysSuccess/></BehaviorTree>\n'
        '<include path="a.xml"/>\n</root>',
    )
    with pytest.raises(TreeLoadError, match="cycle") as info:
        BehaviorTreeFactory().register_behavior_tree_from_file(tmp_path / "a.xml")
    assert info.value.file == str(tmp_path / "b.xml")
    assert info.value.line == 3
    assert 'path="a.xml"' in info.value.message


def test_missing_include_is_a_load_error(tmp_path: Path):
    main = _write(tmp_path / "m.xml", '<root BTCPP_format="4">\n<include path="gone.xml"/></root>')
    with pytest.raises(TreeLoadError, match=r"gone\.xml") as info:
        BehaviorTreeFactory().register_behavior_tree_from_file(main)
    assert (info.value.file, info.value.line) == (str(main), 2)


async def test_v3_file_is_translated_with_a_warning(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, caplog: pytest.LogCaptureFixture
):
    text = (
        '<root main_tree_to_execute="Main"><BehaviorTree ID="Main">'
        '<SequenceStar><StubAction name="A"/><StubAction name="B"/></SequenceStar>'
        "</BehaviorTree></root>"
    )
    with caplog.at_level(logging.WARNING, logger="aiobt.xml"):
        tree = bt_factory.create_tree_from_text(text, file="old.xml")
    assert any("old.xml" in r.getMessage() and "v3" in r.getMessage() for r in caplog.records)
    assert isinstance(tree.root, SequenceWithMemory)
    assert await tree.tick_once() is Status.SUCCESS
    assert stubs.log == ["A:start", "B:start"]


def test_v4_file_has_no_warning(bt_factory: BehaviorTreeFactory, caplog: pytest.LogCaptureFixture):
    with caplog.at_level(logging.WARNING, logger="aiobt.xml"):
        bt_factory.create_tree_from_text(tree_xml("<AlwaysSuccess/>"))
    assert caplog.records == []


def test_tree_nodes_model_inside_a_tree_file_is_accepted(bt_factory: BehaviorTreeFactory):
    text = (
        '<root BTCPP_format="4"><BehaviorTree ID="Main"><AlwaysSuccess/></BehaviorTree>'
        '<TreeNodesModel><Action ID="Extra"/></TreeNodesModel></root>'
    )
    assert bt_factory.create_tree_from_text(text).tree_id == "Main"


def test_comments_and_names_do_not_matter(bt_factory: BehaviorTreeFactory):
    text = tree_xml(
        '<!-- a comment --><Sequence name="main seq" _description="why">'
        '<AlwaysSuccess name="ok"/></Sequence>'
    )
    tree = bt_factory.create_tree_from_text(text)
    assert [n.path for n in tree.nodes()] == [
        "MainTree/Sequence[main seq]",
        "MainTree/Sequence[main seq]/AlwaysSuccess[ok]",
    ]


def test_reactive_sequence_with_one_async_sequence_loads(bt_factory: BehaviorTreeFactory):
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            "<ReactiveSequence><AsyncSequence><AlwaysSuccess/></AsyncSequence>"
            "<Sequence><AsyncSequence><AlwaysSuccess/></AsyncSequence></Sequence>"
            "<AsyncFallback><AlwaysSuccess/></AsyncFallback></ReactiveSequence>"
        )
    )
    assert type(tree.root).__name__ == "ReactiveSequence"
