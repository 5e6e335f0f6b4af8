"""The planner service process over a real router: with the robot service, and alone."""

from __future__ import annotations

import asyncio
import math
from collections.abc import Callable, Sequence

import numpy as np
import pytest

from aiobt.geometry.correction import correction_message
from aiobt.msgs import (
    ClearCostmapAroundPose,
    ClearCostmapAroundRobot,
    ClearCostmapExceptRegion,
    ClearCostmapResponse,
    ClearEntireCostmap,
    ComputeCoveragePath,
    ComputePathThroughPoses,
    ComputePathToPose,
    Goals,
    GoalState,
    IsPathValid,
    OccupancyGrid,
    Odometry,
    Path,
    Point,
    PoseStamped,
    SmoothPath,
    TFMessage,
    pose_fields,
)
from aiobt.msgs.sim import Ack, RemoveObstacle, SpawnObstacle
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings
from aiobt.transport.keys import sim_namespace

from ..services import TRUTH, common, up

pytestmark = pytest.mark.integration
Spawn = Callable[[Sequence[str]], ServiceProcess]
To = ComputePathToPose.ErrorCode
BOX = (4.0, 9.75, 0.4, 1.0)  # x, y, size_x, size_y: in the corridor, 2 m ahead of the robot


async def plan(bus: Bus, x: float, y: float, **kw: object) -> ComputePathToPose.Result:
    client = bus.action_client("compute_path_to_pose", ComputePathToPose)
    goal = ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(x, y, 0.0), **kw)
    handle = await client.send_goal(goal, server_timeout=10.0)
    return await handle.result(timeout=20.0)


async def plan_when_ready(bus: Bus, x: float, y: float) -> ComputePathToPose.Result:
    """Plan, retrying while the planner has no map or pose yet (bounded)."""
    async with asyncio.timeout(20.0):
        while True:
            result = await plan(bus, x, y)
            if result.error_code not in (To.UNKNOWN, To.TF_ERROR):
                return result
            await asyncio.sleep(0.2)


async def is_valid(bus: Bus, path: Path) -> bool:
    reply = await bus.call("is_path_valid", IsPathValid.Request(path=path), IsPathValid.Response)
    return reply.is_valid


async def wait_validity(bus: Bus, path: Path, wanted: bool, polls: int = 100) -> None:
    """Poll is_path_valid every 0.1 s until it says ``wanted`` (fails after ``polls``)."""
    for _ in range(polls):
        if await is_valid(bus, path) == wanted:
            return
        await asyncio.sleep(0.1)
    pytest.fail(f"is_path_valid never became {wanted}")


def clearance_to_box(path: Path) -> float:
    x, y, sx, sy = BOX
    xy = path.xy_array()
    dx = np.maximum(np.abs(xy[:, 0] - x) - sx / 2, 0.0)
    dy = np.maximum(np.abs(xy[:, 1] - y) - sy / 2, 0.0)
    return float(np.hypot(dx, dy).min())


@pytest.mark.e2e
async def test_plans_around_a_new_obstacle_and_clearing_removes_it(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    # the box's edge exactly where it is: a lidar without its default range noise and dropouts
    # (a 1 cm error can shift a marked cell, and the path's clearance with it, by 5 cm)
    exact = ["--lidar-noise", "0", "--lidar-dropout", "0"]
    robot = spawn(["-m", "aiobt_services.robot", "--speed", "4", *exact, *TRUTH,
                   *common(bus_settings)])  # fmt: skip
    # clear only up to 1 m: a removed obstacle 2 m away stays marked until cleared
    planner = spawn(["-m", "aiobt_services.planner", "--raytrace-range", "1.0",
                     *common(bus_settings)])  # fmt: skip
    await up(bus, "robot", robot)
    await up(bus, "planner", planner)

    across = await plan_when_ready(bus, 17.5, 2.0)  # corridor to the far south-east room
    assert across.error_code == 0, across.error_msg
    assert across.path.poses[-1].x == 17.5
    assert 16.0 < sum(np.hypot(*np.diff(across.path.xy_array(), axis=0).T)) < 30.0

    straight = await plan(bus, 7.0, 9.75)
    assert straight.error_code == 0, straight.error_msg
    assert clearance_to_box(straight.path) == 0.0  # runs through where the box will be
    assert await is_valid(bus, straight.path)

    x, y, sx, sy = BOX
    sim = sim_namespace(bus.namespace)  # the simulation's services
    ack = await bus.call(
        "obstacles/spawn",
        SpawnObstacle(id="box", x=x, y=y, size_x=sx, size_y=sy),
        Ack,
        namespace=sim,
    )
    assert ack.ok, ack.message
    await wait_validity(bus, straight.path, wanted=False)
    around = await plan(bus, 7.0, 9.75)
    assert around.error_code == 0, around.error_msg
    assert clearance_to_box(around.path) > 0.2

    ack = await bus.call("obstacles/remove", RemoveObstacle(id="box"), Ack, namespace=sim)
    assert ack.ok, ack.message
    await asyncio.sleep(0.5)  # a few scans: the stale marks are beyond the raytrace range
    assert not await is_valid(bus, straight.path)
    name = ClearEntireCostmap.service_name("global_costmap")
    cleared = await bus.call(name, ClearEntireCostmap.Request(), ClearCostmapResponse)
    assert cleared.success
    assert await is_valid(bus, straight.path)
    again = await plan(bus, 7.0, 9.75)
    assert clearance_to_box(again.path) == 0.0


async def test_error_codes_and_cancel_over_the_wire(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    cells = np.zeros((400, 400), dtype=np.int8)  # 20 x 20 m, a wall at x = 10 m
    cells[:, 200] = 100
    cells[20:40, 200] = 0  # its only door, at y = 1..2 m
    bus.latched_publisher("map", OccupancyGrid).put(OccupancyGrid.from_array(cells, 0.05))
    pose = bus.publisher("pose", PoseStamped)
    planner = spawn(["-m", "aiobt_services.planner", "--downsample", "1", *common(bus_settings)])
    await up(bus, "planner", planner)
    async with asyncio.timeout(20.0):
        while True:
            pose.put(PoseStamped.from_xy_yaw(1.0, 19.0, 0.0))
            result = await plan(bus, 9.0, 9.0)
            if result.error_code not in (To.UNKNOWN, To.TF_ERROR):
                break
            await asyncio.sleep(0.2)
    assert result.error_code == 0, result.error_msg
    assert (await plan(bus, 21.0, 1.0)).error_code == To.GOAL_OUTSIDE_MAP
    assert (await plan(bus, 10.02, 5.0)).error_code == To.GOAL_OCCUPIED
    assert (await plan(bus, 3.0, 3.0, planner_id="Bogus")).error_code == To.INVALID_PLANNER
    odom = ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(3.0, 3.0, frame_id="odom"))
    client = bus.action_client("compute_path_to_pose", ComputePathToPose)
    wrong_frame = await (await client.send_goal(odom, server_timeout=5.0)).result(timeout=10.0)
    assert wrong_frame.error_code == To.TF_ERROR

    # ~2 s of ThetaStar at full resolution: down to the door and back up
    slow = ComputePathToPose.Goal(goal=PoseStamped.from_xy_yaw(19.0, 19.0), planner_id="ThetaStar")
    handle = await client.send_goal(slow, server_timeout=5.0)
    await asyncio.sleep(0.1)
    # the other servers answer while the long search runs in its worker thread
    through = await through_poses(bus, [(5.0, 15.0), (5.0, 10.0)])
    assert through.error_code == 0, through.error_msg
    assert not handle.done
    await handle.cancel(timeout=2.0)
    assert handle.status is GoalState.CANCELED
    assert (await plan(bus, 9.0, 9.0)).error_code == 0  # the server is still healthy
    assert math.isfinite(result.planning_time)
    await smooth_coverage_and_clearing(bus, result.path)


async def through_poses(
    bus: Bus, points: list[tuple[float, float]]
) -> ComputePathThroughPoses.Result:
    client = bus.action_client("compute_path_through_poses", ComputePathThroughPoses)
    goals = Goals(goals=[PoseStamped.from_xy_yaw(x, y) for x, y in points])
    handle = await client.send_goal(ComputePathThroughPoses.Goal(goals=goals), server_timeout=5.0)
    result = await handle.result(timeout=5.0)
    if result.error_code == 0:
        xy = result.path.xy_array()
        for x, y in points:  # every via point is on the path
            assert np.hypot(xy[:, 0] - x, xy[:, 1] - y).min() < 1e-6
    return result


async def smooth_coverage_and_clearing(bus: Bus, path: Path) -> None:
    """SmoothPath, ComputeCoveragePath and the other clearing services answer over the wire."""
    smoother = bus.action_client("smooth_path", SmoothPath)
    smoothed = await (
        await smoother.send_goal(SmoothPath.Goal(path=path), server_timeout=5.0)
    ).result(timeout=5.0)
    assert smoothed.error_code == 0, smoothed.error_msg
    assert len(smoothed.path.poses) == len(path.poses)
    coverage = bus.action_client("compute_coverage_path", ComputeCoveragePath)
    field = [[Point(x=x, y=y) for x, y in [(1.0, 11.0), (8.0, 11.0), (8.0, 15.0), (1.0, 15.0)]]]
    covered = await (
        await coverage.send_goal(ComputeCoveragePath.Goal(polygons=field), server_timeout=5.0)
    ).result(timeout=5.0)
    assert covered.error_code == 0, covered.error_msg
    assert len(covered.coverage_path.poses) == 2 * 6  # 6 swaths, 0.5 m apart, 0.5 m headland
    region = ClearCostmapExceptRegion.Request(reset_distance=2.0)
    for kind in (ClearCostmapExceptRegion, ClearCostmapAroundRobot):
        reply = await bus.call(kind.service_name("global_costmap"), region, ClearCostmapResponse)
        assert reply.success, reply.message
    around = ClearCostmapAroundPose.Request(pose=PoseStamped.from_xy_yaw(5.0, 5.0))
    name = ClearCostmapAroundPose.service_name("global_costmap")
    assert (await bus.call(name, around, ClearCostmapResponse)).success


async def test_the_start_is_the_odometry_composed_with_localizations_correction(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    """With localization's map -> odom on tf, the planner plans from the odometry composed
    with it (as Nav2's costmap reads TF) and leaves ``{ns}/pose`` unread."""
    cells = np.zeros((400, 400), dtype=np.int8)  # 20 x 20 m, free
    bus.latched_publisher("map", OccupancyGrid).put(OccupancyGrid.from_array(cells, 0.05))
    odom, tf = bus.publisher("odom", Odometry), bus.publisher("tf", TFMessage)
    pose = bus.publisher("pose", PoseStamped)  # never put on: whether anybody reads it
    planner = spawn(["-m", "aiobt_services.planner", "--downsample", "1", *common(bus_settings)])
    await up(bus, "planner", planner)
    here = {"header": {"stamp": 5.0, "frame_id": "odom"}, "pose": pose_fields(1.0, 0.5, 0.0)}
    async with asyncio.timeout(20.0):
        while True:
            odom.put(Odometry.model_validate(here))
            tf.put(correction_message((2.0, 3.0, math.pi / 2), 5.0))  # odom (1, 0.5): map (1.5, 4)
            result = await plan(bus, 9.0, 9.0)
            if result.error_code not in (To.UNKNOWN, To.TF_ERROR):
                break
            await asyncio.sleep(0.2)
    assert result.error_code == 0, result.error_msg
    start = result.path.poses[0]
    assert (start.x, start.y) == pytest.approx((1.5, 4.0), abs=0.05)
    assert result.path.header.stamp == 5.0  # the odometry's
    async with asyncio.timeout(5.0):
        while pose.matched:  # noqa: ASYNC110 - let go at the first correction read
            await asyncio.sleep(0.05)
