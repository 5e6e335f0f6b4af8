"""Localization sends its map -> odom correction on ``{ns}/tf`` with every scan, the robot
standing (no filter update) included, and a reader composing odometry with it has
``{ns}/pose`` (aiobt.robot.correction): over a real router, the robot's process and
localization's."""

from __future__ import annotations

import asyncio
import itertools
import statistics

import pytest

from aiobt.msgs import Odometry, PoseStamped, TFMessage
from aiobt.robot.correction import Correction, compose, correction_of
from aiobt.transport import Bus, BusSettings

from .stack import START, Spawn, set_initial_pose, start_stack

pytestmark = [pytest.mark.integration, pytest.mark.e2e, pytest.mark.timeout(120)]

WANTED = 30  # corrections: three seconds of scans at 1x


async def test_the_correction_comes_with_every_scan_and_composes_to_the_pose(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    await start_stack(spawn, bus, bus_settings, speed=1.0)
    await set_initial_pose(bus, *START)
    odoms: dict[float, Odometry] = {}
    poses: dict[float, PoseStamped] = {}
    corrections: list[Correction] = []
    enough = asyncio.Event()

    def on_tf(msg: TFMessage) -> None:
        correction = correction_of(msg)
        if correction is not None:
            corrections.append(correction)
            if len(corrections) >= WANTED:
                enough.set()

    bus.subscribe("odom", Odometry, lambda m: odoms.__setitem__(m.header.stamp, m), queue_size=50)
    bus.subscribe(
        "pose", PoseStamped, lambda m: poses.__setitem__(m.header.stamp, m), queue_size=50
    )
    bus.subscribe("tf", TFMessage, on_tf, queue_size=50)
    await asyncio.wait_for(enough.wait(), 30.0)
    # with every scan (10 Hz), standing: the filter does not update, the correction comes
    stamps = [c.stamp for c in corrections]
    assert all(b > a for a, b in itertools.pairwise(stamps))
    gaps = [b - a for a, b in itertools.pairwise(stamps)]
    assert statistics.median(gaps) == pytest.approx(0.1, abs=0.02)
    # standing still, the last corrections are one: each pose is the odometry composed with it
    last = corrections[-1]
    assert corrections[-5].transform == pytest.approx(last.transform, abs=1e-12)
    matched = 0
    for stamp, pose in poses.items():
        odom = odoms.get(stamp)
        if odom is None or stamp < corrections[-5].stamp:
            continue
        p = odom.pose
        mine = compose(last.transform, p.position.x, p.position.y, p.yaw)
        assert mine == pytest.approx((pose.x, pose.y, pose.yaw), abs=1e-9)
        matched += 1
    assert matched >= 10
