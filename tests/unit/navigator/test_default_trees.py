"""The navigator's default trees and Nav2's trees load with the real Nav2 node set."""

from __future__ import annotations

import pytest

from aiobt.core.blackboard import Blackboard
from aiobt.core.clock import ManualClock
from aiobt.factory import BehaviorTreeFactory
from aiobt.nav import register_nav2_nodes
from aiobt_services.navigator.trees import (
    DEFAULT_THROUGH_POSES_TREE,
    DEFAULT_TO_POSE_TREE,
    TREES_DIR,
    TreeLibrary,
)

TREE_IDS = [
    "NavigateToPoseWReplanningAndRecovery",
    "NavigateThroughPosesWReplanningAndRecovery",
    "NavigateToPoseWReplanningGoalPatienceAndRecovery",
    "NavToPoseWithConsistentReplanningAndIfPathBecomesInvalid",
    "FollowPoint",
]


@pytest.fixture(scope="module")
def library() -> TreeLibrary:
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory)  # no bus: trees build, nothing ticks
    return TreeLibrary(factory, [TREES_DIR])


@pytest.mark.parametrize("tree_id", TREE_IDS)
def test_registered_by_id(library: TreeLibrary, tree_id: str) -> None:
    tree = library.load(tree_id, Blackboard.create(), ManualClock())
    assert tree.tree_id == tree_id


def test_the_through_poses_tree_replans_through_the_remaining_goals(library: TreeLibrary) -> None:
    tree = library.load(str(DEFAULT_THROUGH_POSES_TREE), Blackboard.create(), ManualClock())
    ids = [node.config.registration_id for node in tree.nodes()]
    for needed in ("RemovePassedGoals", "ComputePathThroughPoses", "FollowPath", "GoalUpdated"):
        assert needed in ids
    recoveries = tree.find("RecoveryActions")
    assert [c.name for c in recoveries.children_nodes()] == [
        "ClearingActions",
        "SpinRecovery",
        "WaitRecovery",
        "BackUpRecovery",
    ]
    assert library.load(str(DEFAULT_TO_POSE_TREE), Blackboard.create(), ManualClock())
