"""The rest of Nav2's remote leaves: through-poses planning, smoothing, navigation,
coverage, route, docking and following actions, cost checks and the monitor toggle."""

from __future__ import annotations

import asyncio
from typing import Any

import pytest

from aiobt.core.status import Status
from aiobt.msgs import (
    ClearCostmapResponse,
    ComputeCoveragePath,
    ComputePathThroughPoses,
    GetCosts,
    Goals,
    NavigateToPose,
    Point,
    PoseStamped,
    SmoothPath,
    Toggle,
)
from aiobt.msgs.remote_actions import ComputeAndTrackRoute, DockRobot, FollowObject
from aiobt.msgs.route import Route
from aiobt.transport import Bus

from .support import nav_tree, run_to_end, straight_path, tick_until, tick_until_true

pytestmark = pytest.mark.timeout(30)
S, F, R = Status.SUCCESS, Status.FAILURE, Status.RUNNING
A, B = PoseStamped.from_xy_yaw(1.0, 0.0, 0.0), PoseStamped.from_xy_yaw(2.0, 1.0, 0.0)


def serve_once(bus: Bus, name: str, action: Any, result: Any) -> list[Any]:
    goals: list[Any] = []

    async def execute(goal: Any, handle: Any) -> Any:
        goals.append(goal)
        return result

    bus.action_server(name, action, execute)
    return goals


async def test_compute_path_through_poses_plans_through_the_goals(local_bus: Bus) -> None:
    path = straight_path(2.0)
    goals = serve_once(local_bus, "compute_path_through_poses", ComputePathThroughPoses,
                       ComputePathThroughPoses.Result(path=path))  # fmt: skip
    tree = nav_tree(local_bus, '<ComputePathThroughPoses goals="{goals}" path="{path}" '
                    'last_reached_index="{last}"/>', goals=Goals(goals=[A, B]))  # fmt: skip
    assert await run_to_end(tree) is S
    assert goals[0].goals.goals == [A, B]
    assert tree.root_blackboard["path"] == path
    assert tree.root_blackboard["last"] == -1


async def test_smooth_path_writes_the_smoothed_path_and_its_duration(local_bus: Bus) -> None:
    smoothed = straight_path(1.0, step=0.05)
    result = SmoothPath.Result(path=smoothed, smoothing_duration=0.2, was_completed=True)
    goals = serve_once(local_bus, "smooth_path", SmoothPath, result)
    tree = nav_tree(local_bus, '<SmoothPath unsmoothed_path="{path}" smoothed_path="{out}" '
                    'smoothing_duration="{took}" was_completed="{done}" '
                    'max_smoothing_duration="1.5"/>', path=straight_path())  # fmt: skip
    assert await run_to_end(tree) is S
    bb = tree.root_blackboard
    assert (bb["out"], bb["took"], bb["done"]) == (smoothed, 0.2, True)
    assert goals[0].max_smoothing_duration == 1.5


async def test_navigate_to_pose_sends_the_goal_and_tree(local_bus: Bus) -> None:
    goals = serve_once(local_bus, "navigate_to_pose", NavigateToPose, NavigateToPose.Result())
    tree = nav_tree(local_bus, '<NavigateToPose goal="{goal}" behavior_tree="mine.xml"/>', goal=B)
    assert await run_to_end(tree) is S
    assert (goals[0].pose, goals[0].behavior_tree) == (B, "mine.xml")


async def test_compute_coverage_path_sends_the_field_polygons(local_bus: Bus) -> None:
    nav_path = straight_path(3.0)
    result = ComputeCoveragePath.Result(nav_path=nav_path, planning_time=0.5)
    goals = serve_once(local_bus, "compute_coverage_path", ComputeCoveragePath, result)
    field = [[Point(x=0.0, y=0.0), Point(x=2.0, y=0.0), Point(x=2.0, y=2.0)]]
    tree = nav_tree(local_bus, '<ComputeCoveragePath polygons="{field}" nav_path="{path}" '
                    'planning_time="{took}"/>', field=[{"points": field[0]}])  # fmt: skip
    assert await run_to_end(tree) is S
    assert goals[0].polygons == field
    assert not goals[0].use_gml_file
    assert (tree.root_blackboard["path"], tree.root_blackboard["took"]) == (nav_path, 0.5)


async def test_compute_and_track_route_writes_its_feedback_while_running(local_bus: Bus) -> None:
    fed, finish = asyncio.Event(), asyncio.Event()

    async def execute(goal: Any, handle: Any) -> Any:
        feedback = ComputeAndTrackRoute.Feedback(next_node_id=7, rerouted=True, route=Route())
        handle.publish_feedback(feedback)
        fed.set()
        await finish.wait()
        return ComputeAndTrackRoute.Result(execution_duration=3.0)

    local_bus.action_server("compute_and_track_route", ComputeAndTrackRoute, execute)
    tree = nav_tree(local_bus, '<ComputeAndTrackRoute start_id="1" goal_id="9" '
                    'next_node_id="{next}" rerouted="{rerouted}" '
                    'execution_duration="{took}"/>')  # fmt: skip
    assert await tick_until(tree, fed) is R
    # the feedback reaches the client a moment after the server sent it
    assert await tick_until_true(tree, lambda: "next" in tree.root_blackboard) is R
    assert (tree.root_blackboard["next"], tree.root_blackboard["rerouted"]) == (7, True)
    finish.set()
    assert await run_to_end(tree) is S
    assert tree.root_blackboard["took"] == 3.0
    assert tree.root_blackboard["next"] == 0  # reset at the end, as Nav2


@pytest.mark.timeout(20)
async def test_dock_robot_without_a_docking_server_fails_naming_it(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, '<DockRobot dock_id="home" server_timeout="200" '
                    'error_code_id="{code}" error_msg="{msg}"/>')  # fmt: skip
    assert await run_to_end(tree) is F
    assert "dock_robot" in tree.root_blackboard["msg"]
    assert tree.root_blackboard["code"] == DockRobot.ErrorCode.TIMEOUT


async def test_follow_object_reports_the_elapsed_time(local_bus: Bus) -> None:
    goals = serve_once(local_bus, "follow_object", FollowObject,
                       FollowObject.Result(total_elapsed_time=4.0))  # fmt: skip
    tree = nav_tree(local_bus, '<FollowObject max_duration="5" total_elapsed_time="{t}"/>')
    assert await run_to_end(tree) is S
    assert goals[0].pose_topic == "dynamic_pose"
    assert tree.root_blackboard["t"] == 4.0


def costs(bus: Bus, values: list[float]) -> list[Any]:
    requests: list[Any] = []

    def handle(request: Any) -> Any:
        requests.append(request)
        return GetCosts.Response(costs=values[: len(request.poses)])

    bus.serve("global_costmap/get_cost_global_costmap", GetCosts.Request, GetCosts.Response,
              handle)  # fmt: skip
    return requests


async def test_check_pose_occupancy_is_success_on_an_occupied_pose(local_bus: Bus) -> None:
    costs(local_bus, [254.0])
    tree = nav_tree(local_bus, '<CheckPoseOccupancy pose="{p}"/>', p=A)
    assert await run_to_end(tree) is S


async def test_check_pose_occupancy_treats_unknown_as_free_unless_told(local_bus: Bus) -> None:
    costs(local_bus, [255.0])
    tree = nav_tree(local_bus, '<CheckPoseOccupancy pose="{p}"/>', p=A)
    assert await run_to_end(tree) is F
    tree = nav_tree(local_bus, '<CheckPoseOccupancy pose="{p}" '
                    'consider_unknown_as_obstacle="true"/>', p=A)  # fmt: skip
    assert await run_to_end(tree) is S


async def test_remove_in_collision_goals_keeps_the_free_ones(local_bus: Bus) -> None:
    requests = costs(local_bus, [10.0, 254.0])
    statuses = [{"waypoint_status": 0, "waypoint_index": 0, "waypoint_pose": A},
                {"waypoint_status": 0, "waypoint_index": 1, "waypoint_pose": B}]  # fmt: skip
    tree = nav_tree(local_bus, '<RemoveInCollisionGoals input_goals="{goals}" '
                    'output_goals="{kept}" input_waypoint_statuses="{st}" '
                    'output_waypoint_statuses="{st}"/>',
                    goals=Goals(goals=[A, B]), st=statuses)  # fmt: skip
    assert await run_to_end(tree) is S
    assert requests[0].use_footprint
    assert tree.root_blackboard["kept"].goals == [A]
    assert [s["waypoint_status"] for s in tree.root_blackboard["st"]] == [0, 2]


async def test_toggle_collision_monitor(local_bus: Bus) -> None:
    seen: list[bool] = []

    def handle(request: Any) -> Any:
        seen.append(request.enable)
        return ClearCostmapResponse(success=True)

    local_bus.serve("collision_monitor/toggle", Toggle.Request, Toggle.Response, handle)
    tree = nav_tree(local_bus, '<ToggleCollisionMonitor enable="false" '
                    'service_name="collision_monitor/toggle"/>')  # fmt: skip
    assert await run_to_end(tree) is S
    assert seen == [False]
