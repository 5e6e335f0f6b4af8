"""``<TreeNodesModel>``: read Nav2's manifest, write ours for Groot2."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

from lxml import etree

from aiobt.core.composite import ControlNode, DecoratorNode
from aiobt.core.convert import Milliseconds, to_text, type_name
from aiobt.core.errors import LogicError, TreeLoadError
from aiobt.core.manifest import NodeManifest
from aiobt.core.node import NodeConfig, NodeKind, TreeNode
from aiobt.core.ports import NO_DEFAULT, PortDirection, PortInfo
from aiobt.core.status import Status
from aiobt.xml.document import Element, line_of

_KINDS = {
    "Action": NodeKind.ACTION,
    "Condition": NodeKind.CONDITION,
    "Control": NodeKind.CONTROL,
    "Decorator": NodeKind.DECORATOR,
    "SubTree": NodeKind.SUBTREE,
}

# BT.CPP / ROS type names that map onto Python types with converters.
_TYPES: dict[str, Any] = {
    "double": float,
    "float": float,
    "int": int,
    "unsigned": int,
    "unsigned int": int,
    "uint16": int,
    "uint16_t": int,
    "int32": int,
    "int64": int,
    "uint32": int,
    "size_t": int,
    "bool": bool,
    "string": str,
    "std::string": str,
    "chrono::milliseconds": Milliseconds,
    "std::chrono::milliseconds": Milliseconds,
    "vector<string>": list[str],
    "std::vector<std::string>": list[str],
    "vector<double>": list[float],
    "std::vector<double>": list[float],
    "vector<int>": list[int],
    "std::vector<int>": list[int],
    "std::vector<unsigned short>": list[int],
    "vector<uint16>": list[int],
    "std::vector<uint16_t>": list[int],
    "std::set<unsigned short>": list[int],
}


def python_type(name: str | None) -> Any:
    """The Python type for a manifest type name; unknown names stay as text tags."""
    if not name:
        return None
    return _TYPES.get(name.strip(), name.strip())


def _unimplemented(node: TreeNode) -> LogicError:
    return LogicError(
        f"[{node.config.registration_id}] is declared in a TreeNodesModel "
        "but has no implementation; register one or add a substitution rule"
    )


class UnimplementedNode(TreeNode):
    """Stands in for a leaf known only from a TreeNodesModel; raises when ticked."""

    __slots__ = ()

    def execute_sync(self) -> Status:
        raise _unimplemented(self)


class UnimplementedControl(ControlNode):
    """A control node known only from a TreeNodesModel: keeps its children, raises when ticked."""

    __slots__ = ()

    def execute_sync(self) -> Status:
        raise _unimplemented(self)


class UnimplementedDecorator(DecoratorNode):
    """A decorator known only from a TreeNodesModel: keeps its child, raises when ticked."""

    __slots__ = ()

    def execute_sync(self) -> Status:
        raise _unimplemented(self)


_UNIMPLEMENTED: dict[str, type[TreeNode]] = {
    NodeKind.CONTROL: UnimplementedControl,
    NodeKind.DECORATOR: UnimplementedDecorator,
}


def is_unimplemented(manifest: NodeManifest) -> bool:
    """Whether ``manifest`` comes from a TreeNodesModel alone (no implementation)."""
    return manifest.node_class in (UnimplementedNode, UnimplementedControl, UnimplementedDecorator)


def read_tree_nodes_model(
    source: str | Path, builder: Callable[[str, NodeConfig], TreeNode] | None = None
) -> list[NodeManifest]:
    if isinstance(source, Path) or (
        isinstance(source, str) and not source.lstrip().startswith("<")
    ):
        file: str | None = str(source)
        text = Path(source).read_text(encoding="utf-8")
    else:
        file, text = None, str(source)
    try:
        root = etree.fromstring(text.encode("utf-8"))
    except etree.XMLSyntaxError as exc:
        raise TreeLoadError(f"malformed XML: {exc.msg}", file=file, line=exc.lineno) from exc
    models = root.iter("TreeNodesModel")
    return [
        _manifest(e, builder, file) for model in models for e in model if isinstance(e.tag, str)
    ]


def _manifest(
    element: Element, builder: Callable[[str, NodeConfig], TreeNode] | None, file: str | None
) -> NodeManifest:
    kind = _KINDS.get(str(element.tag))
    node_id = element.get("ID")
    if kind is None or not node_id:
        raise TreeLoadError(
            f"unexpected <{element.tag}> in TreeNodesModel", file=file, line=line_of(element)
        )
    ports = {}
    for port_element in element:
        if not isinstance(port_element.tag, str):
            continue
        direction = _DIRECTIONS.get(str(port_element.tag))
        name = port_element.get("name") or ""
        if direction is None or not name:
            raise TreeLoadError(
                f"[{node_id}]: expected <input_port|output_port|inout_port name=...>, "
                f"got <{port_element.tag}> with name {name!r}",
                file=file,
                line=line_of(port_element),
            )
        default = port_element.get("default", NO_DEFAULT)
        if default == '""':
            default = ""
        ports[name] = PortInfo(
            name,
            direction,
            python_type(port_element.get("type")),
            default,
            (port_element.text or "").strip(),
        )
    fallback = _UNIMPLEMENTED.get(kind, UnimplementedNode)
    return NodeManifest(
        node_id, kind, ports, builder or fallback, node_class=None if builder else fallback
    )


# BT.CPP writes inout_port; Nav2's manifests say bidirectional_port
_DIRECTIONS = {
    "input_port": PortDirection.INPUT,
    "output_port": PortDirection.OUTPUT,
    "inout_port": PortDirection.INOUT,
    "bidirectional_port": PortDirection.INOUT,
}


def add_node_model(
    model: etree._Element, kind: str, node_id: str, ports: Iterable[PortInfo]
) -> None:
    """Append ``<kind ID=node_id>`` with its ports to a ``<TreeNodesModel>``."""
    element = etree.SubElement(model, kind, ID=node_id)
    for port in ports:
        attributes = {"name": port.name, "type": type_name(port.type)}
        if port.has_default:
            attributes["default"] = to_text(port.default)
        port_element = etree.SubElement(element, port.direction.value, attributes)
        if port.description:
            port_element.text = port.description


def write_tree_nodes_model(manifests: Iterable[NodeManifest]) -> str:
    root = etree.Element("root", BTCPP_format="4")
    model = etree.SubElement(root, "TreeNodesModel")
    for manifest in sorted(manifests, key=lambda m: m.id):
        add_node_model(model, manifest.kind, manifest.id, manifest.ports.values())
    return etree.tostring(root, pretty_print=True, encoding="unicode")
