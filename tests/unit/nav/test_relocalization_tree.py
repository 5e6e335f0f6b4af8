"""aiobt's relocalizing navigate-to-pose tree (issue 33's kidnapped robot) builds with
the real Nav2 nodes and relocalizes in its recovery round."""

from __future__ import annotations

from pathlib import Path

import pytest

from aiobt.factory import BehaviorTreeFactory
from aiobt.nav import register_nav2_nodes
from aiobt.nav.conditions import AreErrorCodesPresent
from aiobt.xml.model import UnimplementedControl, UnimplementedDecorator, UnimplementedNode

TREE = (Path(__file__).resolve().parents[3] / "trees"
        / "navigate_to_pose_w_relocalization_and_recovery.xml")  # fmt: skip
PLACEHOLDERS = (UnimplementedNode, UnimplementedControl, UnimplementedDecorator)


def test_builds_with_real_nodes_and_relocalizes_turns_in_eighths_then_clears_in_the_round() -> None:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory)
    tree = factory.create_tree_from_file(TREE)
    nodes = list(tree.nodes())
    assert [n.path for n in nodes if isinstance(n, PLACEHOLDERS)] == []
    (round_robin,) = [n for n in nodes if n.config.registration_id == "RoundRobin"]
    (relocalize,) = [n for n in round_robin.children_nodes() if n.name == "Relocalize"]
    steps = relocalize.children_nodes()
    assert [s.config.registration_id for s in steps] == [
        "ReinitializeGlobalLocalization",
        "Repeat",
        "ClearEntireCostmap",
        "ClearEntireCostmap",
    ]
    # a whole turn (every side seen) in eighths, still after each: the filter reads
    # every scan of an eighth while the robot stands
    eighths = steps[1]
    assert eighths.config.inputs["num_cycles"].text == "8"
    (step,) = eighths.children_nodes()
    spin, wait = step.children_nodes()
    assert spin.config.registration_id == "Spin"
    assert wait.config.registration_id == "Wait"
    turned = 8 * float(spin.config.inputs["spin_dist"].text)
    assert turned == pytest.approx(6.28)
    assert float(wait.config.inputs["wait_duration"].text) >= 2.0
    # then the obstacles laid in map from the wrong estimate go, from both costmaps
    assert sorted(s.config.inputs["service_name"].text for s in steps[2:]) == [
        "global_costmap/clear_entirely_global_costmap",
        "local_costmap/clear_entirely_local_costmap",
    ]


def test_the_round_also_runs_on_start_or_goal_occupied() -> None:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory)
    tree = factory.create_tree_from_file(TREE)
    (gate,) = [n for n in tree.nodes() if n.name == "LostRobotPlannerCodes"]
    assert isinstance(gate, AreErrorCodesPresent)
    for code, runs in ((205, True), (206, True), (204, False), (0, False)):
        tree.root_blackboard["compute_path_error_code"] = code
        assert gate.check() is runs, code
