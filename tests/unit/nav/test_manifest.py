"""The exported TreeNodesModel against Nav2's nav2_tree_nodes.xml, node by node."""

from __future__ import annotations

from typing import Any

import pytest

from aiobt.core.convert import convert, type_name
from aiobt.core.manifest import NodeManifest
from aiobt.core.ports import PortInfo
from aiobt.factory import BehaviorTreeFactory
from aiobt.nav import register_nav2_nodes
from aiobt.xml.model import read_tree_nodes_model

NAV2_MANIFEST = "trees/nav2/nav2_tree_nodes.xml"
NAV2 = {m.id: m for m in read_tree_nodes_model(NAV2_MANIFEST)}


def exported() -> dict[str, NodeManifest]:
    """What ``aiobt nodes`` would print, read back as a TreeNodesModel."""
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory)
    text = factory.tree_nodes_model_xml(include_builtins=True)
    return {m.id: m for m in read_tree_nodes_model(text)}


def _type(port: PortInfo) -> str:
    """The BT.CPP type name without ``std::`` (Nav2 writes ``string``, BT.CPP ``std::string``)."""
    return type_name(port.type).replace("std::", "")


def _default(port: PortInfo) -> Any:
    if not port.has_default:
        return None
    text = port.default
    if isinstance(text, str) and len(text) >= 2 and text[0] == text[-1] == '"':
        text = text[1:-1]  # Nav2's manifest quotes string defaults: "&quot;name&quot;"
    return convert(text, port.type) if isinstance(text, str) else text


def differences(node_id: str, ours: NodeManifest, theirs: NodeManifest) -> list[str]:
    found = []
    if ours.kind != theirs.kind:
        found.append(f"{node_id}: kind {ours.kind} != Nav2's {theirs.kind}")
    if set(ours.ports) != set(theirs.ports):
        found.append(f"{node_id}: ports {sorted(ours.ports)} != Nav2's {sorted(theirs.ports)}")
    for name in set(ours.ports) & set(theirs.ports):
        mine, nav2 = ours.ports[name], theirs.ports[name]
        for what, a, b in (
            ("direction", mine.direction, nav2.direction),
            ("type", _type(mine), _type(nav2)),
            ("default", _default(mine), _default(nav2)),
        ):
            if a != b:
                found.append(f"{node_id}.{name}: {what} {a!r} != Nav2's {b!r}")
    return found


@pytest.fixture(scope="module")
def ours() -> dict[str, NodeManifest]:
    return exported()


@pytest.mark.parametrize("node_id", sorted(NAV2))
def test_every_nav2_node_is_exported_with_nav2_ports(
    node_id: str, ours: dict[str, NodeManifest]
) -> None:
    if node_id not in ours:
        pytest.fail(f"{node_id} (in {NAV2_MANIFEST}) is not registered by register_nav2_nodes")
    assert differences(node_id, ours[node_id], NAV2[node_id]) == []
