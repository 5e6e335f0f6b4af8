"""The service's ``pose`` stream over a real router: the odometry is subscribed per
message only while ``pose`` has a reader, each message then gives one pose (the
correction composed with it, its stamp); the filter's odometry comes from the ring."""

from __future__ import annotations

import asyncio
import math
from collections.abc import Callable

import numpy as np
import pytest

from aiobt.msgs import Odometry, PoseStamped, pose_fields
from aiobt.robot.correction import compose
from aiobt.transport import Bus, BusSettings, open_bus
from aiobt_services.localization.main import Outputs, PoseStream
from aiobt_services.localization.node import LocalizationNode
from aiobt_services.localization.params import AmclParams

pytestmark = [pytest.mark.integration, pytest.mark.timeout(60)]
CORRECTION = (1.0, 2.0, 0.5)


async def until(holds: Callable[[], bool], what: str) -> None:
    try:
        async with asyncio.timeout(5.0):
            while not holds():  # noqa: ASYNC110 - Zenoh's matching news has no awaitable
                await asyncio.sleep(0.01)
    except TimeoutError:
        pytest.fail(f"{what} within 5 s")


def _odom(stamp: float, x: float) -> Odometry:
    return Odometry.model_validate(
        {"header": {"stamp": stamp, "frame_id": "odom"}, "pose": pose_fields(x, 0.0, 0.3)}
    )


async def test_pose_is_made_from_each_odometry_only_while_it_has_a_reader(
    bus: Bus, bus_settings: BusSettings
) -> None:
    outputs = Outputs(bus)
    node = LocalizationNode(AmclParams.from_mapping({}), wanted=outputs.listened)
    node.amcl.map_to_odom = np.array(CORRECTION)
    stream = PoseStream(bus, node, outputs)
    assert not stream.following
    async with open_bus(bus_settings) as robot:
        odom = robot.publisher("odom", Odometry)
        await asyncio.sleep(0.3)  # the router has heard of everything declared so far
        assert not odom.matched  # nobody takes each odometry message: no reader of pose
        poses = robot.subscribe("pose", PoseStamped, queue_size=50)
        await until(lambda: stream.following, "the stream following a reader")
        assert await odom.wait_for_subscribers(5.0)
        for i in range(5):
            odom.put(_odom(0.02 * i, 0.1 * i))
        got = [await poses.next(timeout=5.0) for _ in range(5)]
        for i, pose in enumerate(got):
            assert pose.header.stamp == pytest.approx(0.02 * i)
            expected = compose(CORRECTION, 0.1 * i, 0.0, 0.3)
            assert (pose.x, pose.y) == pytest.approx(expected[:2], abs=1e-9)
            assert math.remainder(pose.yaw - expected[2], math.tau) == pytest.approx(0.0, abs=1e-9)
        poses.close()
        await until(lambda: not stream.following, "the stream letting the odometry go")
        await until(lambda: not odom.matched, "the odometry unsubscribed")
        stream.close()  # the service stopping: a reader now changes nothing
        late = robot.subscribe("pose", PoseStamped, queue_size=1)
        await until(lambda: outputs.listened("pose"), "the late reader matching")
        stream.follow()  # as the matching listener would
        assert not stream.following
        late.close()
