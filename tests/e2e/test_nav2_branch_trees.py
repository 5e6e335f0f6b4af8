"""Every Nav2 tree shipped in trees/nav2 runs to its end against the services (issue 36).

Each tree file under ``trees/nav2`` (main's at the top, kilted's and jazzy's where they
differ from main in ``kilted/`` and ``jazzy/``, and any file a user drops in) is sent
as a user sends it: NavigateToPose or NavigateThroughPoses naming the file. The trees
other e2e files run (the navigator's defaults in test_navigate, two replanning trees
in test_nav2_trees, the two routing trees in test_route) are left out. The module's
stack adds the route server, for kilted's routing trees.

- a navigation tree: SUCCEEDED at a goal 3 m along the corridor (through poses: two);
- ``follow_point`` never ends by design: it follows until cancelled, then CANCELED
  with the robot standing still;
- ``odometry_calibration`` drives its 2 m square three times, in the open plan room,
  and ends SUCCEEDED about where it began. Its kilted and jazzy copies (40 s each;
  they differ from main's only in the tree's ID and the error ports) run with
  ``AIOBT_E2E_FULL=1`` (the issue's must-hold is measured so); CI runs main's.

A user's own trees run the same way: ``AIOBT_E2E_TREES=mine.xml:their_folder pytest
tests/e2e/test_nav2_branch_trees.py`` (docs/navigator.md).
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import pytest

from aiobt.msgs import GoalState, NavigateThroughPoses, PoseStamped
from aiobt.testing.navwatch import ServerGoals

from .conftest import FULL
from .routed import _module_stack, route_goals  # noqa: F401  (the route server's stack)
from .world import World

pytestmark = [pytest.mark.e2e, pytest.mark.integration]

NAV2_TREES = Path(__file__).resolve().parents[2] / "trees" / "nav2"
RUN_ELSEWHERE = {  # top-level file names other e2e files send
    "navigate_to_pose_w_replanning_and_recovery.xml",  # test_navigate (the default)
    "navigate_through_poses_w_replanning_and_recovery.xml",  # test_navigate (aiobt's own)
    "navigate_to_pose_w_replanning_goal_patience_and_recovery.xml",  # test_nav2_trees
    "nav_to_pose_with_consistent_replanning_and_if_path_becomes_invalid.xml",  # test_nav2_trees
    "navigate_on_route_graph_w_recovery.xml",  # test_route
    "navigate_w_routing_global_planning_and_control_w_recovery.xml",  # test_route
}
GOAL = (5.0, 9.75, 0.0)  # along the corridor, 1 m past route node 3
WAYPOINTS = ((3.5, 9.75, 0.0), GOAL)
SQUARE_START = (2.0, 12.5, 0.0)  # the open plan room: a 2 m square to the left is free
SQUARE_CLOSES = 1.0  # m: where odometry_calibration ends from where it began (24 m driven)
CORNER = 0.5  # m: how near the first square passes its corners
FOLLOW_CLOSE = 1.5  # m: follow_point stops 1 m (TruncatePath) short of the goal


BROUGHT = os.environ.get("AIOBT_E2E_TREES", "")  # a user's tree files or folders, os.pathsep


def tree_files(folder: Path) -> list[Path]:
    return sorted(f for f in folder.rglob("*.xml") if f.name != "nav2_tree_nodes.xml")


def trees_to_run() -> list[Path]:
    """Every tree file in trees/nav2 and its branch folders, less those run elsewhere,
    and every file (or file in a folder) AIOBT_E2E_TREES names."""
    shipped = [
        f
        for f in tree_files(NAV2_TREES)
        if not (f.parent == NAV2_TREES and f.name in RUN_ELSEWHERE)
        and (FULL or f.parent == NAV2_TREES or f.stem != "odometry_calibration")
    ]
    brought = [Path(p).resolve() for p in BROUGHT.split(os.pathsep) if p]
    return shipped + [f for p in brought for f in (tree_files(p) if p.is_dir() else [p])]


def tree_id(tree: Path) -> str:
    inside = tree.is_relative_to(NAV2_TREES)
    return str(tree.relative_to(NAV2_TREES).with_suffix("")) if inside else str(tree)


def kind(tree: Path) -> str:
    """How a user runs ``tree``: through poses, follow (never ends), calibrate, to a pose."""
    if tree.stem == "follow_point":
        return "follow"
    if tree.stem == "odometry_calibration":
        return "calibrate"
    text = tree.read_text(encoding="utf-8")  # the navigators' keys: goal, or goals
    if '"{goals}"' in text and '"{goal}"' not in text:
        return "through"
    return "to_pose"


async def through_poses(world: World, tree: Path) -> None:
    poses = [PoseStamped.from_xy_yaw(*pose) for pose in WAYPOINTS]
    goal = NavigateThroughPoses.Goal(poses=poses, behavior_tree=str(tree))
    sent = await world.through.send_goal(goal, server_timeout=10.0)
    result = await sent.result(90.0)
    assert sent.status is GoalState.SUCCEEDED, result
    assert result.error_code == 0, result
    world.assert_at(*GOAL)
    assert world.track.closest(*WAYPOINTS[0][:2]) < 0.6


async def to_pose(world: World, tree: Path) -> None:
    done = await world.navigate(*GOAL, tree=str(tree), timeout=90.0)
    assert done.state is GoalState.SUCCEEDED, done.result
    assert done.result.error_code == 0, done.result
    world.assert_at(*GOAL)


async def follow(world: World, tree: Path) -> None:
    running = await world.start(*GOAL, tree=str(tree))
    near = await world.track.wait_for(
        lambda s: math.dist((s.x, s.y), GOAL[:2]) < FOLLOW_CLOSE, 60.0
    )
    assert near is not None, f"follow_point never came near the goal: {world.track.latest}"
    await running.goal.cancel(timeout=10.0)
    done = await running.end(20.0)
    assert done.state is GoalState.CANCELED, done.result
    assert await world.track.wait_still(1.0, 20.0), f"still moving: {world.track.latest}"


async def calibrate(world: World, tree: Path) -> None:
    await world.teleport(*SQUARE_START)
    world.track.restart()
    done = await world.navigate(*SQUARE_START, tree=str(tree), timeout=150.0)
    assert done.state is GoalState.SUCCEEDED, done.result
    assert world.track.driven > 3 * 4 * 2.0 * 0.9  # three squares of four 2 m sides
    assert world.track.distance_to(*SQUARE_START[:2]) < SQUARE_CLOSES, world.track.latest
    x, y, _ = SQUARE_START
    for corner in ((x + 2.0, y), (x + 2.0, y + 2.0), (x, y + 2.0)):  # turning left
        assert world.track.closest(*corner) < CORNER, corner


RUNS = {"through": through_poses, "to_pose": to_pose, "follow": follow, "calibrate": calibrate}


@pytest.mark.timeout(200)
@pytest.mark.parametrize("tree", trees_to_run(), ids=tree_id)
async def test_shipped_nav2_tree_runs_to_its_end(world: World, goals: ServerGoals, tree: Path):
    await RUNS[kind(tree)](world, tree)
    assert await goals.wait_idle(10.0), goals.active()
