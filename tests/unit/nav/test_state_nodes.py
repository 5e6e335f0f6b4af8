"""Robot-state conditions and leaves, fed on the in-process bus."""

from __future__ import annotations

import math

import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.errors import NodeError
from aiobt.core.status import Status
from aiobt.msgs import (
    BatteryState,
    Odometry,
    PoseWithCovarianceStamped,
    PowerSupplyStatus,
    TrackingFeedback,
)
from aiobt.msgs.geometry import Header, Pose, Twist, Vector3
from aiobt.transport import Bus
from tests.unit.nav.state_support import at, deliver, nav_tree

S, F, R = Status.SUCCESS, Status.FAILURE, Status.RUNNING
pytestmark = pytest.mark.timeout(60)


def odom(
    stamp: float, vx: float = 0.0, x: float = 0.0, y: float = 0.0, yaw: float = 0.0, wz: float = 0.0
) -> Odometry:
    return Odometry(
        header=Header(stamp=stamp, frame_id="odom"),
        pose=Pose.from_xy_yaw(x, y, yaw),
        twist=Twist(linear=Vector3(x=vx), angular=Vector3(z=wz)),
    )


async def test_goal_reached_within_a_quarter_metre(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, '<GoalReached goal="{goal}"/>')
    tree.root_blackboard["goal"] = at(2.0, 1.0)
    assert await tree.tick_exactly_once() is F  # no pose yet
    await deliver(local_bus, "pose", at(1.7, 1.0))
    assert await tree.tick_exactly_once() is F
    await deliver(local_bus, "pose", at(1.8, 1.1))
    assert await tree.tick_exactly_once() is S


async def test_transform_available_once_the_frames_are_known_then_always(
    local_bus: Bus,
) -> None:
    tree = nav_tree(local_bus, '<TransformAvailable parent="map" child="odom"/>')
    assert await tree.tick_exactly_once() is F
    await deliver(local_bus, "pose", at(1.0))
    assert await tree.tick_exactly_once() is F  # map and base_link only
    await deliver(local_bus, "odom", odom(1.0))
    assert await tree.tick_exactly_once() is S


async def test_transform_available_without_frames_is_an_error() -> None:
    tree = nav_tree(None, '<TransformAvailable parent="map"/>')
    with pytest.raises(NodeError, match="child frame"):
        await tree.tick_exactly_once()


async def test_distance_traveled_fires_every_distance(local_bus: Bus) -> None:
    # ticked directly: a parent (and the tree) would reset the finished condition to IDLE,
    # and an IDLE DistanceTraveled starts over (as in Nav2)
    node = nav_tree(local_bus, '<DistanceTraveled distance="1.0"/>').root
    assert node.tick_sync() is F  # no pose: starts with none
    await deliver(local_bus, "pose", at(0.0))
    assert node.tick_sync() is F  # remembers the start now
    await deliver(local_bus, "pose", at(0.6))
    assert node.tick_sync() is F
    await deliver(local_bus, "pose", at(1.1))
    assert node.tick_sync() is S
    await deliver(local_bus, "pose", at(1.9))
    assert node.tick_sync() is F  # 0.8 m from the new start
    await deliver(local_bus, "pose", at(2.2))
    assert node.tick_sync() is S
    node.reset_status()
    assert node.tick_sync() is F  # IDLE again: a new start


async def test_initial_pose_received_port_then_topic(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, '<InitialPoseReceived initial_pose_received="{ipr}"/>')
    tree.root_blackboard["ipr"] = False
    assert await tree.tick_exactly_once() is F
    tree.root_blackboard["ipr"] = True
    assert await tree.tick_exactly_once() is S
    from_topic = nav_tree(local_bus, "<InitialPoseReceived/>")
    assert await from_topic.tick_exactly_once() is F
    await deliver(local_bus, "initialpose", PoseWithCovarianceStamped.from_xy_yaw(0.5, 0.5, 0.0))
    assert await from_topic.tick_exactly_once() is S


async def test_is_stuck_on_a_hard_deceleration(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, "<IsStuck/>")
    assert await tree.tick_exactly_once() is F
    await deliver(local_bus, "odom", odom(1.00, vx=0.5))
    await deliver(local_bus, "odom", odom(1.02, vx=0.45))  # -2.5 m/s^2: braking
    assert await tree.tick_exactly_once() is F
    await deliver(local_bus, "odom", odom(1.04, vx=0.0))  # -22.5 m/s^2: hit something
    assert await tree.tick_exactly_once() is S
    await deliver(local_bus, "odom", odom(1.04, vx=0.0))  # same stamp: ignored, no crash
    assert await tree.tick_exactly_once() is S
    await deliver(local_bus, "odom", odom(1.06, vx=0.0))
    assert await tree.tick_exactly_once() is F


async def test_battery_low_by_percentage_or_voltage_and_charging(local_bus: Bus) -> None:
    low = nav_tree(local_bus, '<IsBatteryLow min_battery="0.2"/>')
    volts = nav_tree(local_bus, '<IsBatteryLow min_battery="11.0" is_voltage="true"/>')
    charging = nav_tree(local_bus, "<IsBatteryCharging/>")
    for tree in (low, volts, charging):
        assert await tree.tick_exactly_once() is F  # nothing received
    await deliver(local_bus, "battery", BatteryState(percentage=0.5, voltage=10.5))
    assert [await t.tick_exactly_once() for t in (low, volts, charging)] == [F, S, F]
    charged = BatteryState(
        percentage=0.1, voltage=12.0, power_supply_status=PowerSupplyStatus.CHARGING
    )
    await deliver(local_bus, "battery", charged)
    assert [await t.tick_exactly_once() for t in (low, volts, charging)] == [S, F, S]


async def test_battery_topic_names_another_key(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, '<IsBatteryCharging battery_topic="/dock/battery"/>')
    charging = BatteryState(power_supply_status=PowerSupplyStatus.CHARGING)
    await deliver(local_bus, "dock/battery", charging)
    assert await tree.tick_exactly_once() is S


async def test_are_poses_near_in_one_frame_and_across_map_and_odom(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, '<ArePosesNear ref_pose="{a}" target_pose="{b}" tolerance="0.5"/>')
    tree.root_blackboard["a"] = at(1.0, 1.0)
    tree.root_blackboard["b"] = at(1.3, 1.3)
    assert await tree.tick_exactly_once() is S
    tree.root_blackboard["b"] = at(1.5, 1.5)
    assert await tree.tick_exactly_once() is F
    # robot at (2, 0) in map and at (0, 0) facing +y in odom: odom = map rotated by -90 deg
    tree.root_blackboard["b"] = at(0.0, 1.0).model_copy(update={"header": Header(frame_id="odom")})
    assert await tree.tick_exactly_once() is F  # cannot transform yet
    await deliver(local_bus, "pose", at(2.0, 0.0, yaw=0.0))
    await deliver(local_bus, "odom", odom(1.0, yaw=math.pi / 2))
    tree.root_blackboard["a"] = at(3.0, 0.0)  # (0, 1) in odom is 1 m ahead of the robot
    assert await tree.tick_exactly_once() is S


async def test_path_tracking_bounds_from_port_or_controller_topic(local_bus: Bus) -> None:
    tree = nav_tree(
        local_bus,
        '<IsWithinPathTrackingBounds max_error_left="0.3" max_error_right="0.1" '
        'max_error_heading="0.5"/>',
    )
    assert await tree.tick_exactly_once() is S  # no feedback: Nav2 says SUCCESS
    await deliver(local_bus, "tracking_feedback", TrackingFeedback(cross_track_error=0.2))
    assert await tree.tick_exactly_once() is S
    await deliver(local_bus, "tracking_feedback", TrackingFeedback(cross_track_error=-0.2))
    assert await tree.tick_exactly_once() is F  # right of the path, beyond 0.1
    await deliver(local_bus, "tracking_feedback", TrackingFeedback(heading_error=-0.6))
    assert await tree.tick_exactly_once() is F
    port = nav_tree(local_bus, '<IsWithinPathTrackingBounds tracking_feedback="{fb}"/>')
    port.root_blackboard["fb"] = TrackingFeedback(cross_track_error=0.4)
    assert await port.tick_exactly_once() is S


async def test_get_current_pose_in_map_or_odom(local_bus: Bus) -> None:
    tree = nav_tree(local_bus, '<GetCurrentPose current_pose="{p}"/>')
    in_odom = nav_tree(local_bus, '<GetCurrentPose global_frame="odom" current_pose="{p}"/>')
    assert await tree.tick_exactly_once() is F
    await deliver(local_bus, "pose", at(4.0, 2.0))
    await deliver(local_bus, "odom", odom(1.0, x=3.0))
    assert await tree.tick_exactly_once() is S
    assert (tree.root_blackboard["p"].x, tree.root_blackboard["p"].header.frame_id) == (4.0, "map")
    assert await in_odom.tick_exactly_once() is S
    assert in_odom.root_blackboard["p"].x == 3.0


async def test_check_stop_status_waits_out_the_duration(local_bus: Bus) -> None:
    clock = ManualClock()
    tree = nav_tree(local_bus, '<CheckStopStatus duration_stopped="500"/>', clock=clock)
    assert await tree.tick_exactly_once() is F  # no odometry
    await deliver(local_bus, "odom", odom(1.0, vx=0.3))
    assert await tree.tick_exactly_once() is F
    await deliver(local_bus, "odom", odom(2.0, vx=0.001))
    assert await tree.tick_exactly_once() is R
    clock.advance(0.4)
    assert await tree.tick_exactly_once() is R
    clock.advance(0.2)
    assert await tree.tick_exactly_once() is S
    await deliver(local_bus, "odom", odom(3.0, wz=0.2))
    assert await tree.tick_exactly_once() is F
