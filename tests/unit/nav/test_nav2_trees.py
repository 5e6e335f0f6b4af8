"""Nav2's own trees load with the real Nav2 nodes: no stubs, no TreeNodesModel."""

from __future__ import annotations

from pathlib import Path

import pytest

from aiobt.factory import BehaviorTreeFactory
from aiobt.nav import register_nav2_nodes
from aiobt.transport import Bus
from aiobt.xml.model import UnimplementedControl, UnimplementedDecorator, UnimplementedNode

NAV2 = Path(__file__).resolve().parents[3] / "trees" / "nav2"
TREES = sorted(p for p in NAV2.rglob("*.xml") if p.name != "nav2_tree_nodes.xml")
PLACEHOLDERS = (UnimplementedNode, UnimplementedControl, UnimplementedDecorator)


def test_every_tree_of_main_kilted_and_jazzy_is_there() -> None:
    # main's 15 (its through-poses tree in main/), the navigator's own through-poses tree,
    # kilted's 14 (kilted/) and jazzy's 12 (jazzy/), each differing from main's
    assert len(TREES) == 15 + 1 + 14 + 12


@pytest.mark.parametrize("path", TREES, ids=lambda p: str(p.relative_to(NAV2).with_suffix("")))
def test_builds_with_real_nodes_only(path: Path) -> None:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory)  # no bus: builds (as `aiobt validate` does), ticks nothing
    tree = factory.create_tree_from_file(path)
    nodes = list(tree.nodes())
    assert len(nodes) >= 5  # navigate_to_pose_w_bounds_check's five
    assert [n.path for n in nodes if isinstance(n, PLACEHOLDERS)] == []


@pytest.mark.timeout(60)
@pytest.mark.parametrize("path", TREES, ids=lambda p: str(p.relative_to(NAV2).with_suffix("")))
async def test_builds_on_a_bus(path: Path, local_bus: Bus) -> None:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory, local_bus)
    tree = factory.create_tree_from_file(path)
    assert tree.root is not None
