"""Ports: literal conversion to declared types, custom converters, {key} and {=}."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import pytest

from aiobt.core.convert import Milliseconds, convert, register_converter, to_text, type_name
from aiobt.core.errors import NodeError, PortError, TreeLoadError
from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import NO_DEFAULT, PortInfo, blackboard_key, input_port, output_port
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import tree_xml


@dataclass(frozen=True)
class Point:
    x: float
    y: float


def _point(text: str) -> Point:
    x, y = (float(part) for part in text.split(","))
    return Point(x, y)


register_converter(Point, _point, "test::Point")


@dataclass(frozen=True)
class Heading:
    degrees: float

    @classmethod
    def from_bt_string(cls, text: str) -> Heading:
        return cls(float(text.removesuffix("deg")))


class Probe(SyncActionNode):
    """Reads every port into ``seen`` and copies ``number`` to ``out``."""

    seen: ClassVar[dict[str, Any]] = {}
    PORTS = (
        input_port("number", int, 1),
        input_port("ratio", float, 0.5),
        input_port("flag", bool, False),
        input_port("names", list[str], "a;b"),
        input_port("values", list[float], NO_DEFAULT),
        input_port("point", Point),
        input_port("heading", Heading),
        input_port("timeout", Milliseconds, 100),
        input_port("anything"),
        input_port("required", int),
        output_port("out", int),
    )

    def on_tick(self) -> Status:
        for name in ("number", "ratio", "flag", "names", "timeout"):
            Probe.seen[name] = self.get_input(name)
        for name in ("values", "point", "heading", "anything", "required"):
            if self.has_input(name):
                Probe.seen[name] = self.get_input(name)
        self.set_output("out", self.get_input("number"))
        return Status.SUCCESS


@pytest.fixture
def factory() -> BehaviorTreeFactory:
    Probe.seen = {}
    factory = BehaviorTreeFactory()
    factory.register_node_type(Probe)
    return factory


async def _run(factory: BehaviorTreeFactory, attributes: str, **entries: Any) -> dict[str, Any]:
    tree = factory.create_tree_from_text(tree_xml(f"<Probe {attributes}/>"))
    for key, value in entries.items():
        tree.root_blackboard.set(key, value)
    assert await tree.tick_exactly_once() is Status.SUCCESS
    return dict(Probe.seen, bb=tree.root_blackboard.snapshot())


async def test_defaults(factory: BehaviorTreeFactory):
    seen = await _run(factory, "")
    assert seen["number"] == 1
    assert seen["ratio"] == 0.5
    assert seen["flag"] is False
    assert seen["names"] == ["a", "b"]
    assert seen["timeout"] == 100
    assert seen["bb"] == {}  # out is not connected


@pytest.mark.parametrize(
    ("attributes", "port", "expected"),
    [
        ('number="-12"', "number", -12),
        ('number="0x1F"', "number", 31),
        ('ratio="2.5e-1"', "ratio", 0.25),
        ('ratio="3"', "ratio", 3.0),
        ('flag="true"', "flag", True),
        ('flag="1"', "flag", True),
        ('flag="FALSE"', "flag", False),
        ('names="x;y;z"', "names", ["x", "y", "z"]),
        ('values="1;2.5;-3"', "values", [1.0, 2.5, -3.0]),
        ('point="1,2"', "point", Point(1.0, 2.0)),
        ('heading="90deg"', "heading", Heading(90.0)),
        ('anything="as is"', "anything", "as is"),
        ('values="json:[1, 2]"', "values", [1, 2]),
        ('anything="json:{&quot;a&quot;: [1, true]}"', "anything", {"a": [1, True]}),
        ('timeout="250"', "timeout", Milliseconds(250)),
    ],
)
async def test_literal_conversion(
    factory: BehaviorTreeFactory, attributes: str, port: str, expected: Any
):
    seen = await _run(factory, attributes)
    assert seen[port] == expected
    assert type(seen[port]) is type(expected)


@pytest.mark.parametrize(
    ("attributes", "port", "text"),
    [
        ('number="twelve"', "number", "twelve"),
        ('ratio="fast"', "ratio", "fast"),
        ('flag="yes"', "flag", "yes"),
        ('values="1;x"', "values", "1;x"),
        ('point="1"', "point", "1"),
        ('anything="json:{bad"', "anything", "json:{bad"),
    ],
)
def test_unconvertible_literal_is_load_error(
    factory: BehaviorTreeFactory, attributes: str, port: str, text: str
):
    with pytest.raises(TreeLoadError) as info:
        factory.create_tree_from_text(tree_xml(f"<Probe {attributes}/>"), file="probe.xml")
    error = info.value
    assert f"[{port}]" in error.message
    assert repr(text) in error.message or text in error.message
    assert error.file == "probe.xml"
    assert error.line == 1
    assert error.node_path == "MainTree/Probe"


async def test_blackboard_pointer_and_own_name(factory: BehaviorTreeFactory):
    seen = await _run(factory, 'number="{n}" ratio="{=}" out="{result}"', n=4, ratio=0.25)
    assert seen["number"] == 4
    assert seen["ratio"] == 0.25
    assert seen["bb"]["result"] == 4


async def test_blackboard_text_is_converted_on_read(factory: BehaviorTreeFactory):
    seen = await _run(factory, 'number="{n}" names="{list}"', n="9", list="p;q")
    assert seen["number"] == 9
    assert seen["names"] == ["p", "q"]


async def test_port_pointer_declares_entry_type(factory: BehaviorTreeFactory):
    tree = factory.create_tree_from_text(tree_xml('<Probe number="{n}"/>'))
    entry = tree.root_blackboard.entry("n")
    assert entry is not None
    assert entry.type is int
    assert not entry.has_value


async def test_missing_blackboard_value_is_an_error(factory: BehaviorTreeFactory):
    tree = factory.create_tree_from_text(tree_xml('<Probe number="{n}"/>'))
    with pytest.raises(NodeError) as info:
        await tree.tick_exactly_once()
    assert isinstance(info.value.cause, PortError)
    assert "[n]" in str(info.value)
    assert info.value.node_path == "MainTree/Probe"


async def test_required_port_without_value_raises_port_error():
    node = Probe("probe")
    node.config.ports = {p.name: p for p in Probe.PORTS}
    with pytest.raises(PortError, match=r"\[required\]"):
        node.get_input("required")
    with pytest.raises(PortError, match="not declared"):
        node.get_input("nope")
    with pytest.raises(PortError, match="not declared"):
        node.set_output("nope", 1)
    assert node.set_output("out", 1) is False  # declared but not connected


def test_output_port_needs_a_pointer(factory: BehaviorTreeFactory):
    with pytest.raises(TreeLoadError, match=r"output port \[out\]"):
        factory.create_tree_from_text(tree_xml('<Probe out="5"/>'))


def test_conflicting_pointer_types_are_a_load_error(factory: BehaviorTreeFactory):
    with pytest.raises(TreeLoadError, match=r"\[k\]"):
        factory.create_tree_from_text(
            tree_xml('<Sequence><Probe number="{k}"/><Probe names="{k}"/></Sequence>')
        )


def test_blackboard_key_parsing():
    assert blackboard_key("{goal}", "port") == "goal"
    assert blackboard_key(" { goal } ", "port") == "goal"
    assert blackboard_key("{=}", "port") == "port"
    assert blackboard_key("{}", "port") == "port"
    assert blackboard_key("goal", "port") is None
    assert blackboard_key("{a}{b}", "port") is None


def test_convert_helpers():
    assert convert("json:[1,2]", list[int]) == [1, 2]
    assert convert("1,2,3", list[int]) == [1, 2, 3]  # Nav2's comma lists
    assert convert("std::numeric_limits<double>::infinity()", float) == float("inf")
    assert to_text([1, True, "x"]) == "1;true;x"
    assert type_name(list[float]) == "std::vector<double>"
    assert type_name(Point) == "test::Point"
    assert type_name(None) == "AnyTypeAllowed"


def test_port_info_directions():
    port = PortInfo("p", input_port("p").direction)
    assert port.is_input
    assert not port.is_output
    assert not port.has_default
    assert output_port("o").is_output
