"""``make_clock(..., odometry=TOPIC)``: on sim time, the robot's time from the stamps
of its odometry instead of ``{ns}/clock`` (the safety chain's services use it), and
the messages handed on to a service that keeps them (an ``OdometryTap``)."""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator, Coroutine
from typing import Any

import pytest

from aiobt.msgs import Clock as ClockMsg
from aiobt.msgs import Header, Odometry, Pose
from aiobt.system.odometry_tap import OdometryTap
from aiobt.system.service import make_clock
from aiobt.transport import Bus


def odometry(stamp: float) -> Odometry:
    return Odometry(header=Header(stamp=stamp, frame_id="odom"), pose=Pose.from_xy_yaw(0, 0))


@contextlib.asynccontextmanager
async def running(feed: Coroutine[Any, Any, None]) -> AsyncIterator[asyncio.Task[None]]:
    """``feed`` as a task for the block, cancelled at its end."""
    task = asyncio.create_task(feed)
    try:
        yield task
    finally:
        task.cancel()
        await asyncio.gather(task, return_exceptions=True)


async def test_the_time_is_the_newest_odometry_stamp_and_the_clock_is_not_read(
    local_bus: Bus,
) -> None:
    clock_pub = local_bus.publisher("clock", ClockMsg)
    odom_pub = local_bus.publisher("odom", Odometry)

    async def feed() -> None:
        for i in range(200):
            clock_pub.put(ClockMsg(clock=100.0 + i))  # another time: must not be followed
            odom_pub.put(odometry(3.5))
            await asyncio.sleep(0.01)

    feeding = asyncio.create_task(feed())
    try:
        async with asyncio.timeout(5.0):
            clock, follower = await make_clock(local_bus, sim_time=True, odometry="odom")
        assert follower is not None
        assert clock.now() == 3.5
        feeding.cancel()
        sleeper = asyncio.create_task(clock.sleep(0.5))  # until 4.0
        await asyncio.sleep(0.05)
        assert not sleeper.done()
        odom_pub.put(odometry(4.25))
        async with asyncio.timeout(5.0):
            await sleeper  # woken by the odometry stamped 4.25
        assert clock.now() == 4.25
    finally:
        feeding.cancel()
        await asyncio.gather(feeding, return_exceptions=True)


async def test_without_odometry_the_clock_is_followed(local_bus: Bus) -> None:
    clock_pub = local_bus.publisher("clock", ClockMsg)

    async def feed() -> None:
        for _ in range(200):
            clock_pub.put(ClockMsg(clock=7.0))
            await asyncio.sleep(0.01)

    feeding = asyncio.create_task(feed())
    try:
        async with asyncio.timeout(5.0):
            clock, _ = await make_clock(local_bus, sim_time=True)
        assert clock.now() == 7.0
    finally:
        feeding.cancel()
        await asyncio.gather(feeding, return_exceptions=True)


async def test_the_odometry_is_listened_to_only_while_the_clock_is_held(local_bus: Bus) -> None:
    odom_pub = local_bus.publisher("odom", Odometry)

    async def feed() -> None:
        stamp = 1.0
        while True:
            odom_pub.put(odometry(stamp))
            stamp += 0.02
            await asyncio.sleep(0.01)

    async with running(feed()):
        clock, follower = await asyncio.wait_for(
            make_clock(local_bus, sim_time=True, odometry="odom"), 5.0
        )
        assert follower is not None
        async with asyncio.timeout(5.0):  # nobody holds it: let go after the linger
            while follower.attached:  # noqa: ASYNC110 - the detach has no event to await
                await asyncio.sleep(0.05)
        idle = clock.now()
        await asyncio.sleep(0.1)
        assert clock.now() == idle  # stamps sent meanwhile were not received
        async with asyncio.timeout(5.0):
            await clock.sleep(0.1)  # a sleeper holds it: attached, woken by the stamps
        assert follower.attached
        assert clock.now() >= idle + 0.1 + 0.1  # time caught up past the idle stretch


async def test_a_tap_gets_each_odometry_message_the_clock_follows(local_bus: Bus) -> None:
    odom_pub = local_bus.publisher("odom", Odometry)
    tap, idle_tap = OdometryTap(keep=64), OdometryTap(keep=64)
    assert not tap.tapped

    async def feed() -> None:
        for _ in range(200):
            odom_pub.put(odometry(1.0))
            await asyncio.sleep(0.01)

    feeding = asyncio.create_task(feed())
    try:
        async with asyncio.timeout(5.0):
            clock, _ = await make_clock(local_bus, sim_time=True, odometry="odom", taps=[tap])
            await make_clock(local_bus, sim_time=False, odometry="odom", taps=[idle_tap])
    finally:
        feeding.cancel()
        await asyncio.gather(feeding, return_exceptions=True)
    assert tap.tapped
    assert not idle_tap.tapped  # the wall clock follows nothing: the service subscribes
    assert {m.header.stamp for m in tap.take()} == {1.0}
    for k in range(5):
        odom_pub.put(odometry(2.0 + k))
    async with asyncio.timeout(5.0):
        while clock.now() < 6.0:
            await clock.sleep(0.5)
    assert [m.header.stamp for m in tap.take()] == [2.0, 3.0, 4.0, 5.0, 6.0]  # in order, once
    assert tap.take() == []
    assert idle_tap.take() == []


def test_a_tap_keeps_the_newest_and_refuses_a_bad_size() -> None:
    tap = OdometryTap(keep=2)
    for k in range(3):
        tap.put(odometry(float(k)))
    assert [m.header.stamp for m in tap.take()] == [1.0, 2.0]
    with pytest.raises(ValueError, match="keep must be >= 1"):
        OdometryTap(keep=0)
