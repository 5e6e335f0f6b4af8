"""bench.system.probes' robot pose: what a user's services read, on an in-process bus."""

from __future__ import annotations

import asyncio

import pytest

from aiobt.geometry.correction import correction_message
from aiobt.msgs import Odometry, PoseStamped, TFMessage, pose_fields
from aiobt.transport import Bus
from bench.system.probes import RobotPose

pytestmark = pytest.mark.timeout(30)


async def test_the_robot_pose_is_the_odometry_composed_with_the_correction(
    local_bus: Bus,
) -> None:
    track = RobotPose(local_bus, poll=0.005)
    odometry, tf = local_bus.publisher("odom", Odometry), local_bus.publisher("tf", TFMessage)
    pose = local_bus.publisher("pose", PoseStamped)  # never put on: a viewer's stream
    here = Odometry.model_validate(
        {"header": {"stamp": 2.0, "frame_id": "odom"}, "pose": pose_fields(1.0, 0.0, 0.0)}
    )
    async with track.held():
        async with asyncio.timeout(10.0):
            while (got := track.peek()) is None:
                odometry.put(here)
                tf.put(correction_message((0.5, 2.0, 0.0), 2.0))
                await asyncio.sleep(0.01)
        assert (got.x, got.y, got.header.stamp) == pytest.approx((1.5, 2.0, 2.0))
        async with asyncio.timeout(5.0):
            while pose.matched:  # noqa: ASYNC110 - let go once the correction was read
                await asyncio.sleep(0.01)
    assert track.peek() is None  # not held: nothing subscribed
