"""TruncatePath, TruncatePathLocal, RemovePassedGoals, IsGoalNearby against Nav2's behaviour."""

from __future__ import annotations

import math

import pytest

from aiobt.core.status import Status
from aiobt.msgs import Goals, Path, WaypointState, WaypointStatus
from aiobt.transport import Bus
from tests.unit.nav.state_support import at, deliver, nav_tree, straight_path

S, F = Status.SUCCESS, Status.FAILURE
pytestmark = pytest.mark.timeout(60)


def xs(path: Path) -> list[float]:
    return [p.pose.position.x for p in path.poses]


async def test_truncate_path_drops_the_poses_near_the_goal_and_faces_it() -> None:
    tree = nav_tree(None, '<TruncatePath distance="2.5" input_path="{p}" output_path="{out}"/>')
    tree.root_blackboard["p"] = straight_path(10)
    assert await tree.tick_exactly_once() is S
    out = tree.root_blackboard["out"]
    assert xs(out) == [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
    assert out.poses[-1].yaw == pytest.approx(0.0)
    tree.root_blackboard["p"] = Path(poses=[at(0, 0), at(0, 1), at(0, 2)])
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["out"].poses[-1].yaw == pytest.approx(math.pi / 2)


async def test_truncate_path_keeps_two_poses_and_passes_an_empty_path() -> None:
    tree = nav_tree(None, '<TruncatePath distance="100" input_path="{p}" output_path="{out}"/>')
    tree.root_blackboard["p"] = straight_path(5)
    assert await tree.tick_exactly_once() is S
    assert xs(tree.root_blackboard["out"]) == [0.0, 1.0]
    tree.root_blackboard["p"] = Path()
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["out"].poses == []


def local(extra: str = "", forward: str = "2.5", backward: str = "1.5") -> str:
    return (
        f'<TruncatePathLocal input_path="{{p}}" output_path="{{out}}" '
        f'distance_forward="{forward}" distance_backward="{backward}" {extra}/>'
    )


async def test_truncate_path_local_keeps_the_window_around_the_robot(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, local())
    tree.root_blackboard["p"] = straight_path(20)
    assert await tree.tick_exactly_once() is F  # no robot pose yet
    await deliver(local_bus, "pose", at(7.2, 0.3))
    assert await tree.tick_exactly_once() is S
    assert xs(tree.root_blackboard["out"]) == [6.0, 7.0, 8.0, 9.0]


async def test_truncate_path_local_uses_the_given_pose_and_forward_minus_one() -> None:
    tree = nav_tree(None, local('pose="{robot}"', forward="-1"))
    tree.root_blackboard["p"] = straight_path(10)
    tree.root_blackboard["robot"] = at(4.0)
    assert await tree.tick_exactly_once() is S
    assert xs(tree.root_blackboard["out"]) == [3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]


async def test_truncate_path_local_search_bound_follows_a_looping_path() -> None:
    # out along x and back: the robot at x=1 on the way out must not jump to the way back
    out_and_back = Path(poses=[at(float(x)) for x in (0, 1, 2, 3, 2, 1, 0)])
    tree = nav_tree(None, local('pose="{robot}" max_robot_pose_search_dist="1.5"'))
    tree.root_blackboard["p"] = out_and_back
    tree.root_blackboard["robot"] = at(1.0)
    assert await tree.tick_exactly_once() is S
    assert len(tree.root_blackboard["out"].poses) == 4  # 0,1 | 2,3: the way out
    unbounded = nav_tree(None, local('pose="{robot}"'))
    unbounded.root_blackboard["p"] = out_and_back
    unbounded.root_blackboard["robot"] = at(1.0)
    assert await unbounded.tick_exactly_once() is S
    assert xs(unbounded.root_blackboard["out"])[-1] == 0.0  # the last of equals: the way back


async def test_truncate_path_local_angular_weight_prefers_the_matching_heading() -> None:
    path = Path(poses=[at(0.0, yaw=math.pi), at(0.2, yaw=0.0)])
    for weight, expected in (("", 0.0), ('angular_distance_weight="1.0"', 0.2)):
        tree = nav_tree(None, local(f'pose="{{r}}" {weight}', forward="0", backward="0"))
        tree.root_blackboard["p"] = path
        tree.root_blackboard["r"] = at(0.05)
        assert await tree.tick_exactly_once() is S
        assert xs(tree.root_blackboard["out"]) == [expected], weight


async def test_is_goal_nearby_measures_the_path_left(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, '<IsGoalNearby path="{p}" proximity_threshold="2.5"/>')
    tree.root_blackboard["p"] = straight_path(10)
    assert await tree.tick_exactly_once() is F  # no pose
    await deliver(local_bus, "pose", at(5.0, 0.5))
    assert await tree.tick_exactly_once() is F  # 4 m left
    await deliver(local_bus, "pose", at(7.1))
    assert await tree.tick_exactly_once() is S  # 2 m left
    tree.root_blackboard["p"] = Path()
    assert await tree.tick_exactly_once() is F


async def test_remove_passed_goals_drops_reached_viapoints_and_marks_them(local_bus: Bus) -> None:
    tree = nav_tree(
        local_bus,
        '<RemovePassedGoals input_goals="{g}" output_goals="{g}" radius="0.5" '
        'input_waypoint_statuses="{st}" output_waypoint_statuses="{st}"/>',
    )
    goals = [at(1.0), at(2.0), at(3.0)]
    tree.root_blackboard["g"] = Goals(goals=goals)
    tree.root_blackboard["st"] = [
        WaypointStatus(waypoint_index=i, waypoint_pose=g) for i, g in enumerate(goals)
    ]
    await deliver(local_bus, "pose", at(1.2))
    assert await tree.tick_exactly_once() is S
    assert [g.x for g in tree.root_blackboard["g"].goals] == [2.0, 3.0]
    states = [s.waypoint_status for s in tree.root_blackboard["st"]]
    assert states == [WaypointState.COMPLETED, WaypointState.PENDING, WaypointState.PENDING]
    await deliver(local_bus, "pose", at(3.0))
    assert await tree.tick_exactly_once() is S  # 2.0 is 1 m away: kept, so 3.0 too
    assert [g.x for g in tree.root_blackboard["g"].goals] == [2.0, 3.0]


async def test_remove_passed_goals_never_removes_the_last_goal(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, '<RemovePassedGoals input_goals="{g}" output_goals="{g}"/>')
    tree.root_blackboard["g"] = Goals(goals=[at(1.0), at(1.1)])
    await deliver(local_bus, "pose", at(1.05))
    assert await tree.tick_exactly_once() is S
    assert [g.x for g in tree.root_blackboard["g"].goals] == [1.1]


async def test_remove_passed_goals_fails_without_a_matching_status(local_bus: Bus) -> None:
    tree = nav_tree(
        local_bus,
        '<RemovePassedGoals input_goals="{g}" output_goals="{g}" input_waypoint_statuses="{st}"/>',
    )
    tree.root_blackboard["g"] = Goals(goals=[at(1.0), at(2.0)])
    tree.root_blackboard["st"] = [WaypointStatus(waypoint_pose=at(5.0))]
    await deliver(local_bus, "pose", at(1.0))
    assert await tree.tick_exactly_once() is F
