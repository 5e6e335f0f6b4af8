"""The navigator service on an in-process bus: actions, goal_pose, the status stream."""

from __future__ import annotations

import asyncio
import logging
import math
from pathlib import Path

import pytest

from aiobt.core.clock import ManualClock, SystemClock
from aiobt.factory import BehaviorTreeFactory
from aiobt.geometry.correction import correction_message
from aiobt.msgs import (
    BtSnapshot,
    BtTree,
    GoalState,
    NavigateThroughPoses,
    NavigateToPose,
    Odometry,
    PoseStamped,
    TFMessage,
    pose_fields,
)
from aiobt.nav import register_nav2_nodes
from aiobt.nav.shared_topics import shared_topics
from aiobt.transport import Bus
from aiobt.transport.on_demand import LINGER
from aiobt_services.navigator.service import BusStatusSink, NavigatorService, NavRobotState

from .harness import WAIT, Rig, make_rig, pose

TREES = {"ToPose": '<Gate name="drive"/>', "ThroughPoses": '<Gate name="tour"/>'}


async def serve(rig: Rig, bus: Bus) -> NavigatorService:
    rig.navigator.stream.sink = BusStatusSink(bus)
    service = NavigatorService(bus, rig.navigator, SystemClock())
    service.start(snapshot_period=0.2)
    return service


@pytest.mark.timeout(60)
async def test_navigate_to_pose_over_the_bus(local_bus: Bus, tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    service = await serve(rig, local_bus)
    try:
        trees = local_bus.subscribe("bt/tree", BtTree, latched=True)
        snapshots = local_bus.subscribe("bt/snapshot", BtSnapshot)
        client = local_bus.action_client("navigate_to_pose", NavigateToPose)
        goal = await client.send_goal(NavigateToPose.Goal(pose=pose(1, 2)), server_timeout=WAIT)
        await rig.gates.wait_started("drive")
        feedback = await asyncio.wait_for(anext(goal.feedback()), WAIT)
        assert feedback.navigation_time >= 0.0
        structure = await trees.next(timeout=WAIT)
        assert structure.tree_id == "ToPose"
        snapshot = await snapshots.next(timeout=WAIT)
        while snapshot.state != "navigating":
            snapshot = await snapshots.next(timeout=WAIT)
        assert snapshot.goal_id == goal.goal_id
        rig.gates.open("drive")
        result = await goal.result(timeout=WAIT)
        assert result.error_code == 0
    finally:
        await service.aclose()


@pytest.mark.timeout(60)
async def test_goal_pose_starts_a_navigation_and_cancel_stops_it(
    local_bus: Bus, tmp_path: Path, caplog: pytest.LogCaptureFixture
) -> None:
    rig = make_rig(tmp_path, TREES)
    service = await serve(rig, local_bus)
    key = local_bus.keys.topic("goal_pose")
    try:
        with caplog.at_level(logging.WARNING):
            local_bus.session.put(key, b'{"x": "twelve", "y": 4, "yaw": 0}')
            local_bus.session.put(key, b'{"x": 3.5, "y": -1, "yaw": 0.5}')
            await rig.gates.wait_started("drive")
        assert "PoseStamped field 'x'" in caplog.text
        navigation = rig.navigator.current
        assert navigation is not None
        assert navigation.request.poses[0].pose.position.x == 3.5
        assert navigation.request.poses[0].pose.position.y == -1
        client = local_bus.action_client("navigate_to_pose", NavigateToPose)
        canceled = await client.cancel_all(timeout=WAIT)
        assert canceled == [navigation.request.goal_id]
        for _ in range(200):
            if rig.gates.halts.get("drive"):
                break
            await asyncio.sleep(0.02)
        assert rig.gates.halts["drive"] == 1
    finally:
        await service.aclose()


@pytest.mark.timeout(60)
async def test_a_second_goal_of_the_same_action_takes_the_navigation_over(
    local_bus: Bus, tmp_path: Path
) -> None:
    rig = make_rig(tmp_path, TREES)
    service = await serve(rig, local_bus)
    try:
        client = local_bus.action_client("navigate_through_poses", NavigateThroughPoses)
        poses = {"goals": [pose(1, 1).model_dump(), pose(2, 2).model_dump()]}
        make = NavigateThroughPoses.Goal.model_validate
        first = await client.send_goal(make({"poses": poses}), server_timeout=WAIT)
        await rig.gates.wait_started("tour")
        second = await client.send_goal(make({"poses": poses}), server_timeout=WAIT)
        old = await first.result(timeout=WAIT)
        assert "preempted" in old.error_msg
        assert (await client.fetch_result(first.goal_id))[0] is GoalState.ABORTED
        rig.gates.open("tour")
        assert (await second.result(timeout=WAIT)).error_code == 0
        assert rig.gates.halts.get("tour", 0) == 0  # the same tree went on
    finally:
        await service.aclose()


@pytest.mark.timeout(60)
async def test_the_robot_state_comes_from_the_shared_pose_and_odometry(local_bus: Bus) -> None:
    nav = register_nav2_nodes(BehaviorTreeFactory(), local_bus)
    clock = ManualClock()
    robot = NavRobotState(nav, clock, pose_timeout=WAIT)
    assert shared_topics(nav, "test").live() == []  # nothing subscribed while idle
    assert robot.current_pose() is None
    assert robot.linear_speed() == 0.0
    assert not await robot.wait_for_pose(0.05)
    waiting = asyncio.create_task(robot.wait_for_pose(WAIT))
    release = asyncio.Event()

    async def navigation() -> bool:  # the streams are subscribed while a goal runs
        async with robot.active() as fresh:
            await release.wait()
        return fresh

    goal = asyncio.create_task(navigation())
    poses = local_bus.publisher("pose", PoseStamped)
    odometry = local_bus.publisher("odom", Odometry)
    moving = Odometry.model_validate({"twist": {"linear": {"x": 0.3, "y": 0.4}}})
    for _ in range(500):
        poses.put(pose(1.0, 2.0))
        odometry.put(moving)
        if robot.current_pose() is not None and robot.linear_speed() > 0.0:
            break
        await asyncio.sleep(0.01)
    current = robot.current_pose()
    assert current is not None
    assert current.pose.position.x == 1.0
    assert robot.linear_speed() == pytest.approx(0.5)
    assert await asyncio.wait_for(waiting, WAIT)
    release.set()
    assert await asyncio.wait_for(goal, WAIT) is True
    await clock.forward(LINGER + 0.1)  # the goal ended a linger ago: streams let go
    assert robot.current_pose() is None
    assert shared_topics(nav, "test").live() == []


@pytest.mark.timeout(60)
async def test_with_a_correction_the_pose_is_composed_and_pose_let_go_each_navigation(
    local_bus: Bus,
) -> None:
    """As Nav2's navigator reads map -> base_link from TF: the odometry composed with
    localization's map -> odom on tf; ``{ns}/pose`` read only until a correction came,
    in every navigation (the streams are subscribed afresh each time)."""
    nav = register_nav2_nodes(BehaviorTreeFactory(), local_bus)
    clock = ManualClock()
    robot = NavRobotState(nav, clock, pose_timeout=WAIT)
    hub = shared_topics(nav, "test")
    pose_key = f"{local_bus.namespace}/pose"
    odometry = local_bus.publisher("odom", Odometry)
    tf = local_bus.publisher("tf", TFMessage)
    header = {"stamp": 1.0, "frame_id": "odom"}
    moved = Odometry.model_validate({"header": header, "pose": pose_fields(0.5, 0.0, 0.0)})

    async def robot_and_localization() -> None:
        while True:
            odometry.put(moved)
            tf.put(correction_message((1.0, 2.0, 0.5 * math.pi), moved.header.stamp))
            await asyncio.sleep(0.01)

    sending = asyncio.create_task(robot_and_localization())
    for n in range(2):
        moved = moved.model_copy(
            update={"header": moved.header.model_copy(update={"stamp": 1.0 + n})}
        )
        async with robot.active() as fresh:
            assert fresh
            async with asyncio.timeout(WAIT):
                while (current := robot.current_pose()) is None or current.header.stamp != 1.0 + n:  # noqa: ASYNC110
                    await asyncio.sleep(0.01)
            assert (current.x, current.y, current.yaw) == pytest.approx((1.0, 2.5, 0.5 * math.pi))
            assert current.header.frame_id == "map"
            assert pose_key not in hub.live()  # read only until the correction came
        await clock.forward(LINGER + 0.1)
        assert hub.live() == []
        assert robot.current_pose() is None
    sending.cancel()


@pytest.mark.timeout(60)
async def test_a_goal_with_nan_is_refused_naming_the_field(local_bus: Bus, tmp_path: Path) -> None:
    rig = make_rig(tmp_path, TREES)
    service = await serve(rig, local_bus)
    key = local_bus.keys.action("navigate_to_pose").goal
    payload = b'{"pose": {"pose": {"position": {"x": NaN, "y": 1.0}}}}'

    def ask() -> list[str]:
        replies = local_bus.session.get(f"{key}?id=nan1", payload=payload, timeout=10.0)
        answers = []
        for reply in replies:
            answer = reply.err if reply.err is not None else reply.ok
            assert answer is not None
            answers.append(answer.payload.to_string())
        return answers

    try:
        answers = await asyncio.wait_for(asyncio.to_thread(ask), WAIT)
        assert len(answers) == 1
        assert "pose.pose.position.x" in answers[0]
        assert "finite number" in answers[0]
        assert rig.navigator.current is None
        assert rig.sink.trees == []
    finally:
        await service.aclose()


@pytest.mark.timeout(60)
async def test_idle_and_unwatched_the_snapshots_leave_the_robot_clock_alone(
    local_bus: Bus, tmp_path: Path
) -> None:
    rig = make_rig(tmp_path, TREES)
    rig.navigator.stream.sink = BusStatusSink(local_bus)
    clock = ManualClock()
    service = NavigatorService(local_bus, rig.navigator, clock)
    service.start(snapshot_period=0.2)
    try:
        for _ in range(5):
            await asyncio.sleep(0)
        assert clock.pending_sleepers == 0  # nobody watches, nothing runs: no robot time needed
        snapshots = local_bus.subscribe("bt/snapshot", BtSnapshot)
        snapshot = await snapshots.next(timeout=WAIT)  # a watcher: snapshots while idle too
        assert snapshot.state != "navigating"
        async with asyncio.timeout(WAIT):
            while clock.pending_sleepers == 0:  # noqa: ASYNC110 - its period on the robot clock
                await asyncio.sleep(0.01)
        clock.advance(0.2)  # its period passed: the next snapshot
        assert (await snapshots.next(timeout=WAIT)).state == snapshot.state
    finally:
        await service.aclose()
