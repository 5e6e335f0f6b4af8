"""The robot-state provider: one subscription per key per bus and namespace, shared by
every node, tree and factory; the last good value kept through bad data."""

from __future__ import annotations

import logging

import pytest

from aiobt.core.errors import NodeError
from aiobt.core.status import Status
from aiobt.msgs import Odometry, PoseStamped
from aiobt.msgs.geometry import Header, Pose
from aiobt.nav import NavContext
from aiobt.nav.frames import transform_pose
from aiobt.nav.robot_state import robot_state
from aiobt.nav.shared_topics import shared_topics
from aiobt.testing.bus import open_local_bus
from aiobt.transport import Bus
from tests.unit.nav.state_support import at, deliver, nav_tree, wait_received

S, F = Status.SUCCESS, Status.FAILURE
pytestmark = pytest.mark.timeout(60)
POSE_READERS = (
    '<Sequence><GoalReached goal="{goal}"/><GetCurrentPose current_pose="{p}"/>'
    '<IsGoalNearby path="{path}"/></Sequence>'
)


async def test_one_pose_subscription_for_every_node_tree_and_factory(local_bus: Bus) -> None:
    trees = [nav_tree(local_bus, POSE_READERS) for _ in range(3)]
    hub = shared_topics(NavContext(bus=local_bus), "test")
    assert hub.subscribed().count(f"{local_bus.namespace}/pose") == 1
    await deliver(local_bus, "pose", at(1.0))
    for tree in trees:
        tree.root_blackboard["goal"] = at(1.0)
        assert await tree.root.children_nodes()[1].tick() is S
        assert tree.root_blackboard["p"].x == 1.0


async def test_subscribed_on_first_use_not_before(local_bus: Bus) -> None:
    hub = shared_topics(NavContext(bus=local_bus), "test")
    nav_tree(local_bus, '<TruncatePath input_path="{p}" output_path="{o}"/>')
    assert hub.subscribed() == []
    nav_tree(local_bus, "<IsStuck/>")
    assert hub.subscribed() == [f"{local_bus.namespace}/odom"]


async def test_another_namespace_has_its_own_state(local_bus: Bus) -> None:
    mine = robot_state(NavContext(bus=local_bus), "test")
    other = robot_state(NavContext(bus=local_bus, namespace="robot2"), "test")
    assert mine is not other
    assert mine is robot_state(NavContext(bus=local_bus), "test")
    other.prepare("pose")  # robot2/pose
    await deliver(local_bus, "pose", at(3.0))
    assert mine.pose is not None
    assert mine.pose.x == 3.0
    assert other.pose is None


async def test_a_second_bus_gets_its_own_subscriptions() -> None:
    async with open_local_bus() as first, open_local_bus(first.namespace) as second:
        assert robot_state(NavContext(bus=first), "a") is not robot_state(
            NavContext(bus=second), "b"
        )


async def test_bad_pose_data_keeps_the_last_good_pose_and_logs_once(
    local_bus: Bus, caplog: pytest.LogCaptureFixture
) -> None:
    tree = nav_tree(local_bus, '<GetCurrentPose current_pose="{p}"/>')
    await deliver(local_bus, "pose", at(2.0))
    topic = shared_topics(NavContext(bus=local_bus), "test").topic("pose", PoseStamped)
    assert topic.reader is not None
    key = f"{local_bus.namespace}/pose"
    with caplog.at_level(logging.WARNING):
        for payload in (b'{"x": "far"}', b"not json", b'{"x": "far"}', b'{"x": 1e999}', b"{"):
            before = topic.received
            local_bus.session.put(key, payload)
            await wait_received(topic, before)  # read while it is the newest
            assert await tree.tick_exactly_once() is S
            assert tree.root_blackboard["p"].x == 2.0
    assert topic.reader.dropped_invalid == 5
    warnings = [r for r in caplog.records if key in r.getMessage()]
    assert len(warnings) == 2  # once per bad field ("x", the payload), not per message


async def test_without_a_bus_trees_build_and_a_tick_names_the_node() -> None:
    tree = nav_tree(None, '<GetCurrentPose current_pose="{p}"/>')
    with pytest.raises(NodeError, match=r"GetCurrentPose.*without a bus"):
        await tree.tick_exactly_once()


async def test_transform_between_map_and_odom(local_bus: Bus) -> None:
    robot = robot_state(NavContext(bus=local_bus), "test")
    robot.prepare("pose", "odom")
    await deliver(local_bus, "pose", at(5.0, 5.0, yaw=0.0))
    await deliver(
        local_bus,
        "odom",
        Odometry(header=Header(stamp=1.0, frame_id="odom"), pose=Pose.from_xy_yaw(1.0, 0.0)),
    )
    in_odom = at(2.0, 0.0).model_copy(update={"header": Header(frame_id="odom")})
    moved = transform_pose(in_odom, "map", robot)
    assert moved is not None
    assert moved.x == pytest.approx(6.0)
    assert (moved.y, moved.header.frame_id) == (5.0, "map")
    assert transform_pose(in_odom, "earth", robot) is None


async def test_a_closed_bus_is_not_kept_alive_by_its_shared_topics() -> None:
    import gc
    import weakref

    async with open_local_bus() as bus:
        nav_tree(bus, POSE_READERS)
        gone = weakref.ref(bus)
    del bus
    gc.collect()
    assert gone() is None


async def test_speed_is_the_mean_over_the_last_window_of_odometry_stamps(local_bus: Bus) -> None:
    def moving(stamp: float, vx: float) -> Odometry:
        return Odometry.model_validate(
            {"header": {"stamp": stamp, "frame_id": "odom"}, "twist": {"linear": {"x": vx}}}
        )

    robot = robot_state(NavContext(bus=local_bus), "test")
    robot.prepare("odom")
    assert robot.speed() is None
    for stamp, vx in ((1.0, 1.0), (1.1, 1.0), (1.5, 0.0), (1.6, 0.2)):
        await deliver(local_bus, "odom", moving(stamp, vx))
    assert robot.speed() == pytest.approx(0.1)  # 1.5 and 1.6: within 0.3 s of the newest
    await deliver(local_bus, "odom", moving(0.2, 0.4))  # time went back (a reset)
    assert robot.speed() == pytest.approx(0.4)  # only what came since
    await deliver(local_bus, "odom", moving(0.3, 0.0))
    assert robot.speed() == pytest.approx(0.2)
