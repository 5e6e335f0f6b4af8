"""Nav2's own replanning trees (trees/nav2/) navigate to SUCCESS with the real services.

Issue 13: the goal-patience tree and the consistent-replanning / invalid-path tree had
no run against the planner, controller and behaviors processes on the simulated robot.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from aiobt.msgs import GoalState
from aiobt.testing.navwatch import ServerGoals

from .world import World

pytestmark = [pytest.mark.e2e, pytest.mark.integration]

NAV2_TREES = Path(__file__).resolve().parents[2] / "trees" / "nav2"
THROUGH_A_DOOR = (10.0, 6.0, 0.0)  # the south middle room, through its door off the corridor


@pytest.mark.timeout(150)
@pytest.mark.parametrize(
    "tree",
    [
        "navigate_to_pose_w_replanning_goal_patience_and_recovery.xml",
        "nav_to_pose_with_consistent_replanning_and_if_path_becomes_invalid.xml",
    ],
)
async def test_nav2_replanning_tree_reaches_the_goal(world: World, goals: ServerGoals, tree: str):
    path = NAV2_TREES / tree
    assert path.is_file(), path

    done = await world.navigate(*THROUGH_A_DOOR, tree=str(path), timeout=120.0)

    assert done.state is GoalState.SUCCEEDED, done.result
    assert done.result.error_code == 0, done.result
    world.assert_at(*THROUGH_A_DOOR)
    assert world.track.driven > math.dist(THROUGH_A_DOOR[:2], (2.0, 9.75))
    assert goals.ended("compute_path_to_pose", GoalState.SUCCEEDED) >= 1
    assert await goals.wait_idle(5.0), goals.active()
