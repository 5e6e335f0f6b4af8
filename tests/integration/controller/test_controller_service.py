"""The controller service process driving the robot service process, over a real router."""

from __future__ import annotations

import asyncio
import itertools
import math
import statistics

import pytest

from aiobt.msgs import (
    ClearCostmapAroundRobot,
    ClearCostmapExceptRegion,
    ClearCostmapResponse,
    ClearEntireCostmap,
    FollowPath,
    FollowPathError,
    GoalState,
    OccupancyGrid,
    Odometry,
    Path,
    PoseStamped,
    Twist,
)
from aiobt.msgs import TrackingFeedback as TrackingFeedbackMsg
from aiobt.transport import Bus, BusSettings
from aiobt.transport.keys import sim_namespace

from .helpers import Spawn, path_through, result_while_frozen, start, yaw_error

pytestmark = [pytest.mark.integration, pytest.mark.e2e]


async def _follow(bus: Bus, path: Path, **ids: str):
    client = bus.action_client("follow_path", FollowPath)
    return await client.send_goal(FollowPath.Goal(path=path, **ids), server_timeout=10.0)


@pytest.mark.parametrize("controller_id", ["FollowPath", "DWB"])
async def test_follows_a_curved_path_to_the_goal(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings, controller_id: str
):
    pose = bus.subscribe("pose", PoseStamped)
    tracking: list[TrackingFeedbackMsg] = []
    bus.subscribe("tracking_feedback", TrackingFeedbackMsg, tracking.append)
    local_plans: list[Path] = []
    cleared = asyncio.Event()

    def on_local_plan(msg: Path) -> None:
        local_plans.append(msg)
        if not msg.poses:
            cleared.set()

    bus.subscribe("local_plan", Path, on_local_plan)
    costmaps: list[OccupancyGrid] = []
    bus.subscribe("local_costmap/costmap", OccupancyGrid, costmaps.append)
    await start(spawn, bus, bus_settings, "controller")
    path = path_through([(0.0, 0.0), (1.0, 0.0), (1.5, 0.5), (1.5, 1.5)])
    goal = await _follow(bus, path, controller_id=controller_id)
    feedback_seen: list[FollowPath.Feedback] = []
    goal.on_feedback = feedback_seen.append
    result = await goal.result(timeout=40.0)
    assert goal.status is GoalState.SUCCEEDED, result
    # the local plan: the controller's predicted poses each cycle, then an empty one
    await asyncio.wait_for(cleared.wait(), 10.0)
    moving = [m for m in local_plans if len(m.poses) >= 2]
    assert len(moving) > 10, [len(m.poses) for m in local_plans]
    assert all(m.header.frame_id == "map" for m in local_plans)
    assert any(max(p.y for p in m.poses) > 0.5 for m in moving)  # it turned with the path
    assert local_plans[-1].poses == []
    # the local costmap at about 2 Hz of robot time around the robot, while the goal ran
    assert len(costmaps) >= 2
    stamps = [c.header.stamp for c in costmaps]
    assert min(b - a for a, b in itertools.pairwise(stamps)) >= 0.5 - 1e-9
    assert costmaps[0].info.width == costmaps[0].info.height == 100  # 5 m at 5 cm
    final = await pose.wait_latest(2.0)
    assert math.hypot(final.x - 1.5, final.y - 1.5) <= 0.25
    assert yaw_error(final.yaw, math.pi / 2) <= 0.3
    assert feedback_seen
    assert feedback_seen[0].distance_to_goal > 1.5
    # tracking feedback (IsWithinPathTrackingBounds): one per cycle, stamped on sim time
    assert len(tracking) > 10
    assert max(abs(t.cross_track_error) for t in tracking) < 0.3
    assert tracking[-1].distance_to_goal <= 0.25
    stamps = [t.header.stamp for t in tracking]
    assert stamps[-1] - stamps[0] > 1.0
    # a fixed 20 Hz control rate on sim time (median: a loaded machine may starve a cycle)
    assert statistics.median(b - a for a, b in itertools.pairwise(stamps)) == pytest.approx(
        0.05, abs=0.011
    )


async def test_follows_the_office_corridor_between_its_walls(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    pose = bus.subscribe("pose", PoseStamped)
    await start(spawn, bus, bus_settings, "controller", world="office")
    start_pose = await pose.wait_latest(5.0)  # the office world's start: (2.0, 9.75, 0)
    path = path_through([(start_pose.x, start_pose.y), (5.0, 9.75), (8.0, 9.75)])
    goal = await _follow(bus, path)
    result = await goal.result(timeout=60.0)
    assert goal.status is GoalState.SUCCEEDED, result
    final = await pose.wait_latest(2.0)
    assert math.hypot(final.x - 8.0, final.y - 9.75) <= 0.25


async def test_obstacle_ahead_stops_before_contact_with_no_valid_control(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    from aiobt.msgs.sim import Ack, SpawnObstacle

    pose = bus.subscribe("pose", PoseStamped)
    # --failure-tolerance 0 (Nav2's default): the refused command fails the goal at once
    await start(spawn, bus, bus_settings, "controller", "--failure-tolerance", "0")
    goal = await _follow(bus, path_through([(0.0, 0.0), (2.1, 0.0)]))
    async with asyncio.timeout(20.0):
        async for p in pose:
            if p.x >= 0.3:
                break
    # dropped 1.1 m ahead of the moving robot: its near face at x + 1.0
    face = p.x + 1.0
    obstacle = SpawnObstacle(x=face + 0.1, y=0.0, size_x=0.2, size_y=0.6)
    sim = sim_namespace(bus.namespace)  # the simulation's services
    ack = await bus.call("obstacles/spawn", obstacle, Ack, namespace=sim)
    assert ack.ok, ack.message
    result = await goal.result(timeout=40.0)
    assert goal.status is GoalState.ABORTED
    assert result.error_code == FollowPathError.NO_VALID_CONTROL
    assert "collision ahead" in result.error_msg
    final = await pose.wait_latest(2.0)
    assert final.x < face - 0.22  # robot radius 0.22: no contact


async def test_cancel_stops_the_robot_within_one_control_period(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    from aiobt.msgs import Clock

    clock = bus.subscribe("clock", Clock)
    odom = bus.subscribe("odom", Odometry)
    twists: list[tuple[float, Twist]] = []
    moving = asyncio.Event()

    def on_twist(twist: Twist) -> None:
        twists.append((_now(clock), twist))
        if twist.linear.x > 0.3:
            moving.set()

    bus.subscribe("cmd_vel", Twist, on_twist)
    await start(spawn, bus, bus_settings, "controller")
    goal = await _follow(bus, path_through([(0.0, 0.0), (2.0, 0.0)]))
    await asyncio.wait_for(moving.wait(), 20.0)
    cancelled_at = _now(clock)
    result = await goal.cancel(timeout=5.0)
    answered_at = _now(clock)
    assert result is not None
    assert goal.status is GoalState.CANCELED
    await asyncio.sleep(0.3)
    after = [(t, tw) for t, tw in twists if t >= cancelled_at]
    first_zero = next(t for t, tw in after if tw.linear.x == 0.0 and tw.angular.z == 0.0)
    # the zero twist goes out as the cancel is handled, not at the next control tick:
    # no later than one 20 Hz period after the cancel was answered (sim time)
    assert first_zero <= answered_at + 0.05
    assert after[-1][1].linear.x == 0.0
    assert abs((await odom.wait_latest(2.0)).twist.linear.x) < 0.05  # the base has stopped


async def test_new_path_takes_over_without_stopping(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    pose = bus.subscribe("pose", PoseStamped)
    twists: list[Twist] = []
    bus.subscribe("cmd_vel", Twist, twists.append)
    await start(spawn, bus, bus_settings, "controller")
    first = await _follow(bus, path_through([(0.0, 0.0), (2.0, 0.0)]))
    async with asyncio.timeout(20.0):
        async for p in pose:
            if p.x >= 0.6:
                break
    seen = len(twists)
    second = await _follow(bus, path_through([(p.x, 0.0), (1.5, 0.0), (1.5, -1.5)]))
    result = await second.result(timeout=40.0)
    assert second.status is GoalState.SUCCEEDED, result
    old = await first.result(timeout=2.0)
    assert first.status is GoalState.ABORTED
    assert "preempted" in old.error_msg
    takeover = [t.linear.x for t in twists[seen : seen + 10]]
    assert min(takeover) > 0.2  # kept driving through the hand-over
    final = await pose.wait_latest(2.0)
    assert math.hypot(final.x - 1.5, final.y + 1.5) <= 0.25


async def test_bad_goals_get_nav2_codes_and_clearing_services_answer(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    await start(spawn, bus, bus_settings, "controller")
    cases = [
        (Path(), {}, FollowPathError.INVALID_PATH, "empty"),
        (
            path_through([(0.0, 0.0), (1.0, 0.0)]),
            {"controller_id": "MPPI"},
            FollowPathError.INVALID_CONTROLLER,
            "MPPI",
        ),
        (
            Path.model_validate(
                {"header": {"frame_id": "base_link"}, "poses": path_through([(0, 0), (1, 0)]).poses}
            ),
            {},
            FollowPathError.TF_ERROR,
            "base_link",
        ),
    ]
    for path, ids, code, words in cases:
        goal = await _follow(bus, path, **ids)
        result = await goal.result(timeout=5.0)
        assert result.error_code == code
        assert words in result.error_msg
    reply = await bus.call(
        "local_costmap/clear_entirely_local_costmap",
        ClearEntireCostmap.Request(),
        ClearCostmapResponse,
    )
    assert reply.success
    await bus.subscribe("pose", PoseStamped).wait_latest(5.0)
    for kind, words in ((ClearCostmapExceptRegion, "outside"), (ClearCostmapAroundRobot, "inside")):
        reply = await bus.call(
            kind.service_name("local_costmap"),
            kind.Request(reset_distance=2.0),
            ClearCostmapResponse,
        )
        assert reply.success, reply.message
        assert f"{words} a 2.00 m square" in reply.message


def _now(clock) -> float:
    latest = clock.latest
    return latest.clock if latest is not None else 0.0


async def test_robot_gone_mid_goal_fails_with_tf_error(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    pose = bus.subscribe("pose", PoseStamped)
    robot = await start(spawn, bus, bus_settings, "controller")
    goal = await _follow(bus, path_through([(0.0, 0.0), (2.0, 0.0)]))
    async with asyncio.timeout(20.0):
        async for p in pose:
            if p.x >= 0.3:
                break
    robot.kill()
    result = await goal.result(timeout=6.0)  # --clock-timeout 2 s of wall time
    assert goal.status is GoalState.ABORTED
    assert result.error_code == FollowPathError.TF_ERROR
    assert "clock stopped" in result.error_msg


async def test_robot_stopped_mid_goal_is_a_stale_pose_on_the_wall_clock(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    """On the wall clock nothing stops the loop when the robot hangs: the stale-pose rule
    does (nothing new from the robot for --pose-timeout of wall time)."""
    pose = bus.subscribe("pose", PoseStamped)
    robot = await start(spawn, bus, bus_settings, "controller", speed="1", sim_time=False)
    goal = await _follow(bus, path_through([(0.0, 0.0), (2.0, 0.0)]))
    async with asyncio.timeout(30.0):
        async for p in pose:
            if p.x >= 0.1:
                break
    result = await result_while_frozen(robot, goal)
    assert goal.status is GoalState.ABORTED
    assert result.error_code == FollowPathError.TF_ERROR
    assert "robot pose in frame 'map' is stale: nothing new from the robot" in result.error_msg
    assert "pose_timeout 0.50 s" in result.error_msg


async def test_speed_limit_caps_the_running_goal_and_the_next_until_lifted(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    from aiobt.msgs.speed_limit import SpeedLimit
    from aiobt.testing.navwatch import wait_until

    speeds: list[float] = []
    changed = asyncio.Event()

    def on_twist(twist: Twist) -> None:
        speeds.append(twist.linear.x)
        changed.set()

    def seen(since: int, low: float, high: float) -> bool:
        return any(low < v <= high for v in speeds[since:])

    bus.subscribe("cmd_vel", Twist, on_twist)
    limits = bus.publisher("speed_limit", SpeedLimit, reliable=True)
    await start(spawn, bus, bus_settings, "controller")
    out = await _follow(bus, path_through([(0.0, 0.0), (2.0, 0.0)]))
    assert await wait_until(changed, lambda: seen(0, 0.4, 1.0), 20.0), speeds
    limits.put(SpeedLimit(percentage=True, speed_limit=40.0))  # 40 % of 0.5 m/s
    asked = len(speeds)
    assert await wait_until(changed, lambda: seen(asked, 0.0, 0.2), 5.0), speeds[asked:]
    limited = next(i for i in range(asked, len(speeds)) if 0.0 < speeds[i] <= 0.2)
    await out.result(timeout=40.0)
    assert out.status is GoalState.SUCCEEDED
    assert max(speeds[limited:]) <= 0.2 + 1e-6
    # the limit stays for the next goal, until a 0 (Nav2's NO_SPEED_LIMIT) lifts it
    back_from = len(speeds)
    back = await _follow(bus, path_through([(2.0, 0.0), (1.5, -0.5), (0.0, -0.5)]))
    assert await wait_until(changed, lambda: seen(back_from, 0.15, 0.2), 20.0)
    assert max(speeds[back_from:]) <= 0.2 + 1e-6
    limits.put(SpeedLimit(percentage=True, speed_limit=0.0))
    lifted = len(speeds)
    assert await wait_until(changed, lambda: seen(lifted, 0.4, 1.0), 20.0)  # mid-goal
    await back.result(timeout=40.0)
    assert back.status is GoalState.SUCCEEDED
