"""Bad input: each is one TreeLoadError naming file, line, node path and the offending text."""

from __future__ import annotations

from pathlib import Path

import pytest

from aiobt.core.errors import TreeLoadError
from aiobt.factory import BehaviorTreeFactory

HEAD = '<root BTCPP_format="4" main_tree_to_execute="Main">\n'


def _doc(*lines: str) -> str:
    return HEAD + "\n".join(lines) + "\n</root>"


# (case, xml, expected message fragments, line, node path)
CASES = [
    (
        "malformed",
        _doc('<BehaviorTree ID="Main">', "  <Sequence>", "</BehaviorTree>"),
        ["malformed XML", "Sequence"],
        4,
        None,
    ),
    (
        "unknown_id",
        _doc('<BehaviorTree ID="Main">', "  <Sequence>", "    <Fallbak/>", "  </Sequence>",
             "</BehaviorTree>"),
        ["unknown node ID [Fallbak]", "did you mean [Fallback]"],
        4,
        "Main/Sequence/Fallbak",
    ),
    (
        "unknown_port",
        _doc('<BehaviorTree ID="Main">', '  <Sleep msec="1" msce="2"/>', "</BehaviorTree>"),
        ["attribute [msce]", "not a port of [Sleep]", "did you mean [msec]"],
        3,
        "Main/Sleep",
    ),
    (
        "missing_port",
        _doc('<BehaviorTree ID="Main">', '  <Timeout name="guard"><AlwaysSuccess/></Timeout>',
             "</BehaviorTree>"),
        ["missing its required port [msec]"],
        3,
        "Main/Timeout[guard]",
    ),
    (
        "unconvertible",
        _doc('<BehaviorTree ID="Main">', "  <Sequence>", '    <Repeat num_cycles="twice">',
             "      <AlwaysSuccess/>", "    </Repeat>", "  </Sequence>", "</BehaviorTree>"),
        ["[num_cycles]", "'twice'", "int"],
        4,
        "Main/Sequence/Repeat",
    ),
    (
        "duplicate_tree",
        _doc('<BehaviorTree ID="Main"><AlwaysSuccess/></BehaviorTree>',
             '<BehaviorTree ID="Main"><AlwaysFailure/></BehaviorTree>'),
        ["duplicate BehaviorTree ID [Main]", "first defined at bad.xml:2"],
        3,
        None,
    ),
    (
        "recursive",
        _doc('<BehaviorTree ID="Main"><SubTree ID="Loop"/></BehaviorTree>',
             '<BehaviorTree ID="Loop">', "  <Sequence>", '    <SubTree ID="Main"/>',
             "  </Sequence>", "</BehaviorTree>"),
        ["recursive SubTree: Main -> Loop -> Main"],
        5,
        "Main/Loop/Sequence/Main",
    ),
    (
        "unknown_subtree",
        _doc('<BehaviorTree ID="Main">', '  <SubTree ID="Docking"/>', "</BehaviorTree>",
             '<BehaviorTree ID="Docker"><AlwaysSuccess/></BehaviorTree>'),
        ["no BehaviorTree with ID [Docking]", "did you mean [Docker]"],
        3,
        "Main/Docking",
    ),
    (
        "main_missing",
        '<root BTCPP_format="4" main_tree_to_execute="Mian">\n'
        '<BehaviorTree ID="Main"><AlwaysSuccess/></BehaviorTree>\n</root>',
        ['main_tree_to_execute="Mian"', "did you mean [Main]"],
        1,
        None,
    ),
    (
        "too_many_children",
        _doc('<BehaviorTree ID="Main">', "  <Inverter><AlwaysSuccess/><AlwaysFailure/></Inverter>",
             "</BehaviorTree>"),
        ["[Inverter] must have exactly 1 child, it has 2"],
        3,
        "Main/Inverter",
    ),
    (
        "leaf_with_child",
        _doc('<BehaviorTree ID="Main">', "  <AlwaysSuccess><AlwaysFailure/></AlwaysSuccess>",
             "</BehaviorTree>"),
        ["[AlwaysSuccess] must have no children"],
        3,
        "Main/AlwaysSuccess",
    ),
    (
        "explicit_without_id",
        _doc('<BehaviorTree ID="Main">', '  <Action name="x"/>', "</BehaviorTree>"),
        ["<Action> needs an ID attribute"],
        3,
        "Main/Action",
    ),
    (
        "behavior_tree_with_two_children",
        _doc('<BehaviorTree ID="Main">', '  <SetBlackboard value="1" output_key="k"/>',
             '  <Sequence/>', "</BehaviorTree>"),
        ["must have exactly one child, it has 2"],
        2,
        None,
    ),
    (
        "bad_autoremap",
        _doc('<BehaviorTree ID="Main"><SubTree ID="Inner" _autoremap="maybe"/></BehaviorTree>',
             '<BehaviorTree ID="Inner"><AlwaysSuccess/></BehaviorTree>'),
        ["_autoremap must be true or false", "'maybe'"],
        2,
        "Main/Inner",
    ),
    (
        "reactive_two_async",
        _doc('<BehaviorTree ID="Main">', "  <ReactiveSequence>",
             "    <AsyncSequence><AlwaysSuccess/></AsyncSequence>",
             '    <Control ID="AsyncSequence"><AlwaysSuccess/></Control>',
             "  </ReactiveSequence>", "</BehaviorTree>"),
        ["ReactiveSequence cannot have more than one async child"],
        3,
        "Main/ReactiveSequence",
    ),
    (
        "unexpected_top_element",
        _doc("<Behaviourtree/>"),
        ["unexpected <Behaviourtree> under <root>"],
        2,
        None,
    ),
    (
        "bad_format_version",
        '<root BTCPP_format="5"><BehaviorTree ID="Main"><AlwaysSuccess/></BehaviorTree></root>',
        ["unsupported BTCPP_format='5'"],
        1,
        None,
    ),
]  # fmt: skip


@pytest.mark.parametrize(
    ("xml", "fragments", "line", "node_path"),
    [case[1:] for case in CASES],
    ids=[case[0] for case in CASES],
)
def test_bad_input_is_one_clear_error(
    xml: str, fragments: list[str], line: int, node_path: str | None
):
    factory = BehaviorTreeFactory()
    with pytest.raises(TreeLoadError) as info:
        factory.create_tree_from_text(xml, file="bad.xml")
    error = info.value
    for fragment in fragments:
        assert fragment in error.message
    assert error.file == "bad.xml"
    assert error.line == line
    assert error.node_path == node_path
    assert str(error).startswith(f"bad.xml:{line}: ")


def test_unreadable_file_names_it(tmp_path: Path):
    missing = tmp_path / "nope.xml"
    with pytest.raises(TreeLoadError, match="cannot read tree file") as info:
        BehaviorTreeFactory().create_tree_from_file(missing)
    assert info.value.file == str(missing)


def test_register_twice_with_same_id_is_duplicate():
    factory = BehaviorTreeFactory()
    text = '<root BTCPP_format="4"><BehaviorTree ID="A"><AlwaysSuccess/></BehaviorTree></root>'
    factory.register_behavior_tree_from_text(text, file="one.xml")
    with pytest.raises(TreeLoadError, match=r"duplicate BehaviorTree ID \[A\]") as info:
        factory.register_behavior_tree_from_text(text, file="two.xml")
    assert info.value.file == "two.xml"
    assert "one.xml:1" in info.value.message


def test_create_tree_unknown_id_suggests():
    factory = BehaviorTreeFactory()
    factory.register_behavior_tree_from_text(
        '<root BTCPP_format="4"><BehaviorTree ID="Patrol"><AlwaysSuccess/></BehaviorTree></root>'
    )
    with pytest.raises(TreeLoadError, match=r"\[Patrl\].*did you mean \[Patrol\]"):
        factory.create_tree("Patrl")


def test_several_trees_without_main_is_an_error():
    text = (
        '<root BTCPP_format="4"><BehaviorTree ID="A"><AlwaysSuccess/></BehaviorTree>'
        '<BehaviorTree ID="B"><AlwaysSuccess/></BehaviorTree></root>'
    )
    with pytest.raises(TreeLoadError, match="found: A, B"):
        BehaviorTreeFactory().create_tree_from_text(text, file="two.xml")
