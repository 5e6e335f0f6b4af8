"""Nav2's own trees load with the real Nav2 nodes: no stubs, no TreeNodesModel."""

from __future__ import annotations

from pathlib import Path

import pytest

from aiobt.factory import BehaviorTreeFactory
from aiobt.nav import register_nav2_nodes
from aiobt.transport import Bus
from aiobt.xml.model import UnimplementedControl, UnimplementedDecorator, UnimplementedNode

NAV2 = Path(__file__).resolve().parents[3] / "trees" / "nav2"
TREES = sorted(p for p in NAV2.glob("*.xml") if p.name != "nav2_tree_nodes.xml")
PLACEHOLDERS = (UnimplementedNode, UnimplementedControl, UnimplementedDecorator)


def test_the_four_trees_are_there() -> None:
    # Nav2's six (two of them route trees), and the navigator's own navigate_through_poses tree
    assert len(TREES) == 7


@pytest.mark.parametrize("path", TREES, ids=lambda p: p.stem)
def test_builds_with_real_nodes_only(path: Path) -> None:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory)  # no bus: builds (as `aiobt validate` does), ticks nothing
    tree = factory.create_tree_from_file(path)
    nodes = list(tree.nodes())
    assert len(nodes) >= 8
    assert [n.path for n in nodes if isinstance(n, PLACEHOLDERS)] == []


@pytest.mark.timeout(60)
@pytest.mark.parametrize("path", TREES, ids=lambda p: p.stem)
async def test_builds_on_a_bus(path: Path, local_bus: Bus) -> None:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory, local_bus)
    tree = factory.create_tree_from_file(path)
    assert tree.root is not None
