"""<TreeNodesModel>: export for Groot2 and import (ports with types and defaults)."""

from __future__ import annotations

from lxml import etree

from aiobt.core.convert import Milliseconds
from aiobt.core.leaves import SyncActionNode
from aiobt.core.node import NodeKind
from aiobt.core.ports import inout_port, input_port, output_port
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory


class Drive(SyncActionNode):
    """Drives somewhere."""

    __slots__ = ()
    PORTS = (
        input_port("speed", float, 0.5, "m/s"),
        input_port("waypoints", list[float], description="x;y pairs"),
        input_port("timeout", Milliseconds, 1000),
        input_port("reverse", bool, False),
        output_port("distance", float, description="driven"),
        inout_port("goal", str),
    )

    def on_tick(self) -> Status:
        return Status.SUCCESS


def _factory() -> BehaviorTreeFactory:
    factory = BehaviorTreeFactory()
    factory.register_node_type(Drive)
    factory.register_simple_condition("IsReady", lambda node: True, [input_port("level", int, 3)])
    return factory


def test_export_lists_custom_nodes_with_typed_ports():
    root = etree.fromstring(_factory().tree_nodes_model_xml().encode())
    assert root.tag == "root"
    assert root.get("BTCPP_format") == "4"
    model = root.find("TreeNodesModel")
    assert model is not None
    assert [(e.tag, e.get("ID")) for e in model] == [("Action", "Drive"), ("Condition", "IsReady")]
    drive = model.find("Action[@ID='Drive']")
    assert drive is not None
    ports = {p.get("name"): p for p in drive}
    assert ports["speed"].tag == "input_port"
    assert (ports["speed"].get("type"), ports["speed"].get("default")) == ("double", "0.5")
    assert ports["speed"].text == "m/s"
    assert ports["waypoints"].get("type") == "std::vector<double>"
    assert ports["waypoints"].get("default") is None
    assert ports["timeout"].get("type") == "std::chrono::milliseconds"
    assert ports["reverse"].get("default") == "false"
    assert ports["distance"].tag == "output_port"
    assert ports["goal"].tag == "inout_port"
    assert ports["goal"].get("type") == "std::string"


def test_export_with_builtins():
    root = etree.fromstring(_factory().tree_nodes_model_xml(include_builtins=True).encode())
    ids = {e.get("ID"): e.tag for e in root.iter() if e.get("ID")}
    assert ids["Sequence"] == "Control"
    assert ids["Inverter"] == "Decorator"
    assert ids["Sleep"] == "Action"
    assert ids["Drive"] == "Action"


def test_export_parses_back_into_a_factory():
    exported = _factory().tree_nodes_model_xml()
    other = BehaviorTreeFactory()
    assert sorted(other.register_tree_nodes_model(exported)) == ["Drive", "IsReady"]
    drive = other.manifests["Drive"]
    assert drive.kind == NodeKind.ACTION
    assert other.manifests["IsReady"].kind == NodeKind.CONDITION
    original = Drive.provided_ports()
    assert list(drive.ports) == [p.name for p in original]
    for port in original:
        imported = drive.ports[port.name]
        assert imported.direction is port.direction
        assert imported.type == port.type
        assert imported.description == port.description
    assert drive.ports["speed"].default == "0.5"  # defaults come back as text
    assert not drive.ports["waypoints"].has_default


def test_imported_model_validates_attributes_and_converts_defaults():
    factory = BehaviorTreeFactory()
    factory.register_tree_nodes_model(_factory().tree_nodes_model_xml())
    tree = factory.create_tree_from_text(
        '<root BTCPP_format="4"><BehaviorTree ID="M"><Drive waypoints="1;2"/></BehaviorTree></root>'
    )
    node = tree.root
    assert node.get_input("speed") == 0.5
    assert node.get_input("waypoints") == [1.0, 2.0]
    assert node.get_input("reverse") is False


def test_import_keeps_registered_nodes():
    factory = _factory()
    model = (
        '<root BTCPP_format="4"><TreeNodesModel>'
        '<Action ID="Drive"><input_port name="other"/></Action>'
        '<Action ID="Lift"><input_port name="height" type="double" default="0.1"/></Action>'
        "</TreeNodesModel></root>"
    )
    assert factory.register_tree_nodes_model(model) == ["Lift"]
    assert "speed" in factory.manifests["Drive"].ports
    assert factory.manifests["Lift"].ports["height"].type is float
