"""Every remote leaf (action, service, cancel) has the ports of Nav2's nav2_tree_nodes.xml."""

from __future__ import annotations

import pytest

from aiobt.core.convert import convert, type_name
from aiobt.core.manifest import NodeManifest
from aiobt.factory import BehaviorTreeFactory
from aiobt.nav import register_nav2_nodes
from aiobt.nav.actions import ACTION_NODES
from aiobt.nav.cancel import CANCEL_NODES
from aiobt.nav.services import SERVICE_NODES
from aiobt.xml.model import read_tree_nodes_model

MANIFEST = {m.id: m for m in read_tree_nodes_model("trees/nav2/nav2_tree_nodes.xml")}
OURS = [cls.__name__ for cls in (*ACTION_NODES, *SERVICE_NODES, *CANCEL_NODES)]
# the catalogue's (jazzy, opennav_coverage), not nav2_tree_nodes.xml's
NOT_IN_MANIFEST = {"IsPathValid", "CancelCoverage", "ComputeCoveragePath"}


def _registered() -> dict[str, NodeManifest]:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory, None, replace=True)
    return factory.manifests


def test_every_remote_node_of_the_manifest_is_ours() -> None:
    remote = {
        node_id
        for node_id, model in MANIFEST.items()
        if {"server_name", "service_name"} & set(model.ports)
    }
    assert remote <= set(OURS), sorted(remote - set(OURS))


@pytest.mark.parametrize("node_id", sorted(set(OURS) - NOT_IN_MANIFEST))
def test_ports_match_the_nav2_manifest(node_id: str) -> None:
    mine, theirs = _registered()[node_id], MANIFEST[node_id]
    assert mine.kind == theirs.kind
    assert set(mine.ports) == set(theirs.ports)
    for name, port in mine.ports.items():
        other = theirs.ports[name]
        assert (type_name(port.type), port.direction) == (type_name(other.type), other.direction), (
            name
        )
        if other.has_default:
            expected = convert(str(other.default).strip('"'), other.type)
            assert port.default == expected, name
        else:
            assert not port.has_default, name
