"""The controller composes its pose in map from odometry and localization's correction on
``{ns}/tf`` (aiobt.robot.correction), and lets ``{ns}/pose`` go once a correction comes:
over a real router, the robot's process and the controller's."""

from __future__ import annotations

import asyncio
import math

import pytest

from aiobt.msgs import FollowPath, GoalState, Odometry, PoseStamped, TFMessage
from aiobt.robot.correction import correction_message
from aiobt.transport import Bus, BusSettings
from aiobt.transport.keys import sim_topic

from .helpers import Spawn, path_through, start

pytestmark = [pytest.mark.integration, pytest.mark.e2e]

SHIFT = 0.6  # m in map's y the test's correction puts the robot away from the truth
EVERY = 5  # odometry messages per correction: localization's 10 Hz with the robot's 50


def _correction(truth: PoseStamped, odom: Odometry) -> tuple[float, float, float]:
    """``truth * odom^-1``: map -> odom as a localization with the truth would send it."""
    yaw = truth.yaw - odom.pose.yaw
    ox, oy = odom.pose.position.x, odom.pose.position.y
    c, s = math.cos(yaw), math.sin(yaw)
    return truth.x - (c * ox - s * oy), truth.y - (s * ox + c * oy), yaw


@pytest.mark.timeout(120)
async def test_the_pose_in_map_is_the_odometry_composed_with_the_correction(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    truth = bus.subscribe(sim_topic("pose"), PoseStamped, queue_size=1)
    odometry = bus.subscribe("odom", Odometry, queue_size=1)
    await start(spawn, bus, bus_settings, "controller")
    first_truth, first_odom = await truth.wait_latest(10.0), await odometry.wait_latest(10.0)
    exact = _correction(first_truth, first_odom)
    shifted = (exact[0], exact[1] + SHIFT, exact[2])  # a correction that is off by SHIFT
    tf = bus.publisher("tf", TFMessage)
    seen = [0]

    def send(msg: Odometry) -> None:  # with every EVERY-th odometry, stamped on it
        seen[0] += 1
        if seen[0] % EVERY == 0:
            tf.put(correction_message(shifted, msg.header.stamp))

    bus.subscribe("odom", Odometry, send)
    pose_probe = bus.publisher("pose", PoseStamped)  # matched while anyone reads pose
    start_x, start_y = first_truth.x, first_truth.y
    end = (start_x + 1.5 * math.cos(first_truth.yaw), start_y + 1.5 * math.sin(first_truth.yaw))
    path = path_through([(start_x, start_y + SHIFT), (end[0], end[1] + SHIFT)])
    client = bus.action_client("follow_path", FollowPath)
    goal = await client.send_goal(FollowPath.Goal(path=path), server_timeout=10.0)
    result = await goal.result(timeout=60.0)
    assert goal.status is GoalState.SUCCEEDED, result
    # the controller drove its composed pose (the truth + SHIFT) to the path's end (within
    # the goal checker's 0.25 m): the truth ended on the unshifted line; driving the truth
    # from {ns}/pose it would have ended at least SHIFT - 0.25 m off it
    final = await truth.wait_latest(2.0)
    assert math.hypot(final.x - end[0], final.y - end[1]) <= 0.3, (final, end)
    # and it let {ns}/pose go (still attached: the streams linger after a goal)
    async with asyncio.timeout(5.0):
        while pose_probe.matched:  # noqa: ASYNC110 - the matching status is Zenoh's
            await asyncio.sleep(0.05)
