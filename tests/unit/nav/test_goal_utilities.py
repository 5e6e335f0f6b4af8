"""GetPoseFromPath, ConcatenatePaths, GetNextFewGoals, AppendGoalPoseToGoals,
ExtractRouteNodesAsGoals."""

from __future__ import annotations

import pytest

from aiobt.core.errors import NodeError
from aiobt.core.status import Status
from aiobt.msgs import Goals, Path, Route, RouteNode
from aiobt.msgs.geometry import Header, Point
from tests.unit.nav.state_support import at, nav_tree, straight_path

S, F = Status.SUCCESS, Status.FAILURE


@pytest.mark.parametrize(("index", "x"), [(0, 0.0), (2, 2.0), (-1, 4.0), (-5, 0.0)])
async def test_get_pose_from_path_by_index(index: int, x: float) -> None:
    tree = nav_tree(None, f'<GetPoseFromPath path="{{p}}" index="{index}" pose="{{pose}}"/>')
    tree.root_blackboard["p"] = straight_path(5)
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["pose"].x == x


@pytest.mark.parametrize("index", [5, -6])
async def test_get_pose_from_path_out_of_range_or_empty_fails(index: int) -> None:
    tree = nav_tree(None, f'<GetPoseFromPath path="{{p}}" index="{index}" pose="{{pose}}"/>')
    tree.root_blackboard["p"] = straight_path(5)
    assert await tree.tick_exactly_once() is F
    tree.root_blackboard["p"] = Path()
    assert await tree.tick_exactly_once() is F


async def test_get_pose_from_path_gives_a_frameless_pose_the_path_frame() -> None:
    tree = nav_tree(None, '<GetPoseFromPath path="{p}" pose="{pose}"/>')
    tree.root_blackboard["p"] = Path(
        header=Header(frame_id="odom"), poses=[at(1.0).model_copy(update={"header": Header()})]
    )
    assert await tree.tick_exactly_once() is S
    assert tree.root_blackboard["pose"].header.frame_id == "odom"


async def test_concatenate_paths() -> None:
    tree = nav_tree(
        None, '<ConcatenatePaths input_path1="{a}" input_path2="{b}" output_path="{ab}"/>'
    )
    tree.root_blackboard["a"] = straight_path(2)
    tree.root_blackboard["b"] = Path(header=Header(frame_id="odom"), poses=[at(7.0)])
    assert await tree.tick_exactly_once() is S
    joined = tree.root_blackboard["ab"]
    assert [p.x for p in joined.poses] == [0.0, 1.0, 7.0]
    assert joined.header.frame_id == "map"
    tree.root_blackboard["a"] = Path()
    tree.root_blackboard["b"] = Path()
    assert await tree.tick_exactly_once() is F


async def test_get_next_few_goals() -> None:
    tree = nav_tree(
        None, '<GetNextFewGoals num_goals="2" input_goals="{g}" output_goals="{next}"/>'
    )
    tree.root_blackboard["g"] = Goals(goals=[at(1.0), at(2.0), at(3.0)])
    assert await tree.tick_exactly_once() is S
    assert [g.x for g in tree.root_blackboard["next"].goals] == [1.0, 2.0]
    tree.root_blackboard["g"] = Goals()
    assert await tree.tick_exactly_once() is F


async def test_get_next_few_goals_refuses_a_negative_count() -> None:
    tree = nav_tree(None, '<GetNextFewGoals num_goals="-1" input_goals="{g}" output_goals="{n}"/>')
    tree.root_blackboard["g"] = Goals(goals=[at(1.0)])
    with pytest.raises(NodeError, match="num_goals"):
        await tree.tick_exactly_once()


async def test_append_goal_pose_to_goals() -> None:
    tree = nav_tree(
        None,
        '<Sequence><AppendGoalPoseToGoals goal_pose="{goal}" output_goals="{goals}"/>'
        '<AppendGoalPoseToGoals goal_pose="2;0;0" input_goals="{goals}" output_goals="{goals}"/>'
        "</Sequence>",
    )
    tree.root_blackboard["goal"] = at(1.0)
    assert await tree.tick_exactly_once() is S
    assert [g.x for g in tree.root_blackboard["goals"].goals] == [1.0, 2.0]


async def test_extract_route_nodes_as_goals() -> None:
    tree = nav_tree(None, '<ExtractRouteNodesAsGoals route="{route}" goals="{goals}"/>')
    route = Route(
        header=Header(stamp=3.0, frame_id="map"),
        nodes=[RouteNode(nodeid=4, position=Point(x=1.0, y=2.0)), RouteNode(nodeid=9)],
    )
    tree.root_blackboard["route"] = route
    assert await tree.tick_exactly_once() is S
    goals = tree.root_blackboard["goals"]
    assert [(g.x, g.y) for g in goals.goals] == [(1.0, 2.0), (0.0, 0.0)]
    assert goals.goals[0].header == route.header
    tree.root_blackboard["route"] = Route()
    assert await tree.tick_exactly_once() is F
