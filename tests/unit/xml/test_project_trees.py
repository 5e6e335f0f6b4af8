"""Every XML under trees/ parses; Nav2's trees load against Nav2's node manifest."""

from __future__ import annotations

from pathlib import Path

import pytest

from aiobt.core.errors import TreeLoadError
from aiobt.core.manifest import TestNodeConfig
from aiobt.core.node import NodeKind
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.xml.document import parse_file

REPO = Path(__file__).resolve().parents[3]
TREES = REPO / "trees"
NAV2 = TREES / "nav2"
NAV2_MODEL = NAV2 / "nav2_tree_nodes.xml"
NAV2_TREES = sorted(p for p in NAV2.rglob("*.xml") if p != NAV2_MODEL)  # with branch folders
# main's manifest declares main's nodes: kilted's and jazzy's trees use IsPathValid (main's
# ValidatePath); they build with aiobt's real nodes (tests/unit/nav/test_nav2_trees.py)
MAIN_TREES = [p for p in NAV2_TREES if p.parent.name in ("nav2", "main")]
ALL_XML = sorted(TREES.rglob("*.xml"))


def test_the_tree_folders_are_where_expected():
    assert NAV2_MODEL.is_file()
    # main's 15 (main/ holds its through-poses tree), the navigator's own through-poses
    # tree, kilted's 14 and jazzy's 12 (each differs from main's of the same name)
    assert len(NAV2_TREES) == 15 + 1 + 14 + 12
    assert {p.parent.name for p in NAV2_TREES} == {"nav2", "main", "kilted", "jazzy"}
    assert (NAV2 / "NOTICE.md").is_file()  # Nav2's license attribution travels with them


@pytest.mark.parametrize("path", ALL_XML, ids=lambda p: str(p.relative_to(TREES)))
def test_every_xml_under_trees_parses(path: Path):
    document = parse_file(path)
    assert document.trees or document.models


def _nav2_factory() -> BehaviorTreeFactory:
    factory = BehaviorTreeFactory()
    factory.register_tree_nodes_model(NAV2_MODEL)
    factory.add_substitution_rule("*", TestNodeConfig(Status.SUCCESS))  # leaves only
    return factory


def test_nav2_manifest_declares_typed_ports():
    factory = BehaviorTreeFactory()
    added = factory.register_tree_nodes_model(str(NAV2_MODEL))
    assert {"ComputePathToPose", "FollowPath", "Spin", "BackUp"} <= set(added)
    assert "GoalUpdated" in factory.manifests  # from the manifest, or already built in
    assert factory.manifests["Spin"].kind == NodeKind.ACTION
    spin = factory.manifests["Spin"].ports
    assert spin["spin_dist"].type is float
    assert spin["spin_dist"].default == "1.57"
    assert spin["error_code_id"].is_output


@pytest.mark.parametrize("path", MAIN_TREES, ids=lambda p: str(p.relative_to(NAV2)))
def test_nav2_tree_loads_with_stub_substitutions(path: Path):
    tree = _nav2_factory().create_tree_from_file(path)
    nodes = list(tree.nodes())
    assert len(nodes) >= 5  # navigate_to_pose_w_bounds_check's five
    leaves = [n for n in nodes if not n.children_nodes()]
    assert leaves
    assert {type(n).__name__ for n in leaves} == {"TestNode"}
    assert all(n.children_nodes() for n in nodes if n.config.registration_id == "RecoveryNode")
    assert tree.source == str(path)


def _misspelt_copy(tmp_path: Path, good: str, bad: str) -> tuple[Path, int]:
    source = NAV2 / "navigate_to_pose_w_replanning_and_recovery.xml"
    text = source.read_text(encoding="utf-8")
    assert f'{good}="' in text
    line = text[: text.index(f'{good}="')].count("\n") + 1
    copy = tmp_path / source.name
    copy.write_text(text.replace(f'{good}="', f'{bad}="', 1), encoding="utf-8")
    return copy, line


@pytest.mark.parametrize(
    ("good", "bad"), [("spin_dist", "spin_dst"), ("proximity_threshold", "proximity_treshold")]
)
def test_misspelt_port_in_a_nav2_tree_is_a_load_error(tmp_path: Path, good: str, bad: str):
    copy, line = _misspelt_copy(tmp_path, good, bad)
    with pytest.raises(TreeLoadError) as info:
        _nav2_factory().create_tree_from_file(copy)
    error = info.value
    assert error.file == str(copy)
    assert error.line == line
    assert f"attribute [{bad}]" in error.message
    assert f"did you mean [{good}]" in error.message
    assert error.node_path is not None
    assert error.node_path.startswith("NavigateToPoseWReplanningAndRecovery/RecoveryNode")


def test_unconvertible_literal_in_a_nav2_tree_is_a_load_error(tmp_path: Path):
    source = NAV2 / "navigate_to_pose_w_replanning_and_recovery.xml"
    copy = tmp_path / "bad.xml"
    copy.write_text(
        source.read_text(encoding="utf-8").replace('spin_dist="1.57"', 'spin_dist="a lot"'),
        encoding="utf-8",
    )
    with pytest.raises(TreeLoadError, match=r"\[spin_dist\].*'a lot'.*double"):
        _nav2_factory().create_tree_from_file(copy)
