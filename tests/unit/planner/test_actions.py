"""The action executes and services on a GlobalCostmap fed with messages (no Zenoh)."""

from __future__ import annotations

import asyncio
import logging
import math
import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aiobt.costmap import LETHAL, NO_INFORMATION
from aiobt.geometry import XYYaw
from aiobt.msgs import (
    ComputeCoveragePath,
    ComputePathThroughPoses,
    ComputePathToPose,
    Goals,
    Header,
    LaserScan,
    OccupancyGrid,
    Path,
    Point,
    PoseStamped,
    SmoothPath,
)
from aiobt_services.planner.actions import TALLY_EVERY, ActionOptions, PlannerActions, to_path
from aiobt_services.planner.state import CostmapOptions, GlobalCostmap
from aiobt_services.planner.traversal import SearchParams

To = ComputePathToPose.ErrorCode
Through = ComputePathThroughPoses.ErrorCode


def world(size: int = 100, downsample: int = 1) -> GlobalCostmap:
    cells = np.zeros((size, size), dtype=np.int8)
    cells[:, size // 2] = 100
    cells[size // 4, size // 2] = 0  # a one-cell door is closed by inflation
    cells[size // 4 - 8 : size // 4 + 9, size // 2] = 0  # a 0.85 m door
    grid = GlobalCostmap(CostmapOptions(search=SearchParams(downsample=downsample)))
    grid.on_map(OccupancyGrid.from_array(cells, 0.05))
    grid.on_pose(PoseStamped.from_xy_yaw(1.0, 1.0, 0.0, stamp=3.0))
    return grid


def to_pose(x: float, y: float, **kw: object) -> ComputePathToPose.Goal:
    return ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(x, y, 0.0, **kw))  # type: ignore[arg-type]


async def test_plan_from_the_robot_pose() -> None:
    actions = PlannerActions(world())
    result = await actions.compute_path_to_pose(to_pose(4.0, 4.0), None)
    assert result.error_code == 0, result.error_msg
    first, last = result.path.poses[0], result.path.poses[-1]
    assert (first.x, first.y) == (1.0, 1.0)
    assert (last.x, last.y) == (4.0, 4.0)
    assert result.path.header.frame_id == "map"
    assert result.path.header.stamp == 3.0
    assert all(abs(p.x - 2.5) > 0.05 or 0.8 < p.y < 1.7 for p in result.path.poses)


async def test_viapoints_are_passed_in_order_before_the_goal() -> None:
    actions = PlannerActions(world())
    via = [PoseStamped.from_xy_yaw(1.0, 4.0), PoseStamped.from_xy_yaw(4.0, 1.5)]
    goal = ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(4.0, 4.0), viapoints=via)
    result = await actions.compute_path_to_pose(goal, None)
    assert result.error_code == 0, result.error_msg
    xy = [(p.x, p.y) for p in result.path.poses]
    first_via, second_via = xy.index((1.0, 4.0)), xy.index((4.0, 1.5))
    assert 0 < first_via < second_via < len(xy) - 1
    assert xy[-1] == (4.0, 4.0)
    bad = ComputePathToPose.Goal(
        goal=PoseStamped.from_xy_yaw(4.0, 4.0), viapoints=[PoseStamped.from_xy_yaw(9.0, 1.0)]
    )
    refused = await actions.compute_path_to_pose(bad, None)
    assert refused.error_code == To.GOAL_OUTSIDE_MAP, refused


@pytest.mark.parametrize(
    ("goal", "code", "text"),
    [
        (to_pose(9.0, 1.0), To.GOAL_OUTSIDE_MAP, "outside"),
        (to_pose(2.52, 4.0), To.GOAL_OCCUPIED, "occupied"),
        (to_pose(1.0, 1.0, frame_id="odom"), To.TF_ERROR, "'odom'"),
        (
            ComputePathToPose.Goal(
                goal=PoseStamped.from_xy_yaw(4.0, 4.0),
                start=PoseStamped.from_xy_yaw(-1.0, 1.0),
                use_start=True,
            ),
            To.START_OUTSIDE_MAP,
            "start",
        ),
        (
            ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(4.0, 4.0), planner_id="Nope"),
            To.INVALID_PLANNER,
            "Nope",
        ),
    ],
)
async def test_bad_goals_get_nav2_codes(goal: ComputePathToPose.Goal, code: int, text: str) -> None:
    result = await PlannerActions(world()).compute_path_to_pose(goal, None)
    assert result.error_code == code
    assert text in result.error_msg


async def test_missing_map_or_pose() -> None:
    result = await PlannerActions(GlobalCostmap()).compute_path_to_pose(to_pose(1, 1), None)
    assert (result.error_code, "no map" in result.error_msg) == (To.UNKNOWN, True)
    grid = world()
    grid.pose = None
    result = await PlannerActions(grid).compute_path_to_pose(to_pose(1, 1), None)
    assert result.error_code == To.TF_ERROR


async def test_through_poses_codes() -> None:
    actions = PlannerActions(world())
    empty = ComputePathThroughPoses.Goal(goals=Goals(goals=[]))
    result = await actions.compute_path_through_poses(empty, None)
    assert result.error_code == Through.NO_VIAPOINTS_GIVEN
    goals = Goals(goals=[PoseStamped.from_xy_yaw(4.0, 1.0), PoseStamped.from_xy_yaw(2.52, 1.0)])
    result = await actions.compute_path_through_poses(
        ComputePathThroughPoses.Goal(goals=goals), None
    )
    assert result.error_code == Through.GOAL_OCCUPIED
    goals = Goals(goals=[PoseStamped.from_xy_yaw(4.0, 1.0), PoseStamped.from_xy_yaw(1.0, 4.0)])
    result = await actions.compute_path_through_poses(
        ComputePathThroughPoses.Goal(goals=goals), None
    )
    assert result.error_code == 0
    assert any(math.hypot(p.x - 4.0, p.y - 1.0) < 1e-9 for p in result.path.poses)


@pytest.mark.parametrize("planner_id", ["GridBased", "ThetaStar"])
async def test_timeout_code(planner_id: str) -> None:
    actions = PlannerActions(world(400), ActionOptions(max_planning_time=1e-6))
    goal = ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(18.0, 18.0), planner_id=planner_id)
    result = await actions.compute_path_to_pose(goal, None)
    assert result.error_code == To.TIMEOUT


async def test_cancelling_a_long_plan_is_prompt_and_does_not_block_others() -> None:
    actions = PlannerActions(world(400))
    slow = ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(18.0, 18.0), planner_id="ThetaStar")
    long_plan = asyncio.create_task(actions.compute_path_to_pose(slow, None))
    await asyncio.sleep(0.05)
    quick = await asyncio.wait_for(actions.compute_path_to_pose(to_pose(2.0, 2.0), None), 5.0)
    assert quick.error_code == 0
    assert not long_plan.done()
    began = time.monotonic()
    long_plan.cancel()
    with pytest.raises(asyncio.CancelledError):
        await long_plan
    assert time.monotonic() - began < 0.5


async def test_scan_marks_then_clear_removes_obstacle() -> None:
    grid = world()
    scan = LaserScan(angle_min=0.0, angle_max=0.0, angle_increment=0.01, range_min=0.1,
                     range_max=5.0, ranges=[1.0])  # fmt: skip
    grid.on_scan(scan)
    snapshot = grid.snapshot()
    assert snapshot is not None
    assert snapshot.costs[20, 40] == LETHAL  # (2.0, 1.0) seen ahead of the robot at (1, 1)
    assert grid.costmap is not None
    grid.costmap.clear_entirely()
    snapshot = grid.snapshot()
    assert snapshot is not None
    assert snapshot.costs[20, 40] not in (LETHAL, NO_INFORMATION)


async def test_smooth_path_codes() -> None:
    actions = PlannerActions(world())
    planned = await actions.compute_path_to_pose(to_pose(4.0, 4.0), None)
    result = await actions.smooth_path(
        SmoothPath.Goal(path=planned.path, check_for_collisions=True), None
    )
    assert result.error_code == 0, result.error_msg
    assert result.was_completed
    assert len(result.path.poses) == len(planned.path.poses)
    bad = await actions.smooth_path(SmoothPath.Goal(path=planned.path, smoother_id="x"), None)
    assert bad.error_code == SmoothPath.ErrorCode.INVALID_SMOOTHER
    empty = await actions.smooth_path(SmoothPath.Goal(path=Path()), None)
    assert empty.error_code == SmoothPath.ErrorCode.INVALID_PATH


async def test_coverage_codes() -> None:
    actions = PlannerActions(world())
    square = [[Point(x=x, y=y) for x, y in [(0.5, 0.5), (2.0, 0.5), (2.0, 2.0), (0.5, 2.0)]]]
    ok = await actions.compute_coverage_path(ComputeCoveragePath.Goal(polygons=square), None)
    assert ok.error_code == 0, ok.error_msg
    assert len(ok.coverage_path.poses) == 2 * 1  # one swath at 0.5 m spacing, 0.5 m headland
    assert len(ok.nav_path.poses) > 10
    gml = await actions.compute_coverage_path(ComputeCoveragePath.Goal(use_gml_file=True), None)
    assert gml.error_code == ComputeCoveragePath.ErrorCode.INVALID_REQUEST
    frame = ComputeCoveragePath.Goal(polygons=square, frame_id="odom")
    assert (await actions.compute_coverage_path(frame, None)).error_code == 803


@given(
    st.lists(
        st.tuples(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3), st.floats(-4 * math.pi, 4 * math.pi)),
        max_size=30,
    ),
    st.floats(0.0, 1e6),
)
@settings(max_examples=60, deadline=None)
def test_to_path_is_the_message_built_pose_by_pose(poses: list[XYYaw], stamp: float) -> None:
    built = Path(
        header=Header(stamp=stamp, frame_id="map"),
        poses=[PoseStamped.from_xy_yaw(x, y, yaw, "map", stamp) for x, y, yaw in poses],
    )
    path = to_path(poses, stamp)
    assert path == built
    assert path.to_json() == built.to_json()


async def test_a_replan_to_the_same_goal_from_a_moved_robot_reuses_the_search(
    caplog: pytest.LogCaptureFixture,
) -> None:
    grid = world()
    actions = PlannerActions(grid)
    first = await actions.compute_path_to_pose(to_pose(4.0, 4.0), None)
    grid.on_pose(PoseStamped.from_xy_yaw(1.5, 1.0, 0.0, stamp=4.0))
    again = await actions.compute_path_to_pose(to_pose(4.0, 4.0), None)
    other = await actions.compute_path_to_pose(to_pose(4.0, 1.0), None)
    assert (first.error_code, again.error_code, other.error_code) == (0, 0, 0)
    assert (again.path.poses[0].x, again.path.poses[0].y) == (1.5, 1.0)
    assert actions.tally == [3, 3, 1]  # plans, searches, served by a kept one
    caplog.set_level(logging.INFO, logger="aiobt_services.planner.actions")
    for _ in range(TALLY_EVERY - 3):
        await actions.compute_path_to_pose(to_pose(4.0, 4.0), None)
    assert f"{TALLY_EVERY} plans: {TALLY_EVERY} searches, {TALLY_EVERY - 2} of them" in caplog.text
