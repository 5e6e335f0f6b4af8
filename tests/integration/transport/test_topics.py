"""Typed pub/sub, latched topics, bad payloads, the sim clock, over a real router."""

from __future__ import annotations

import asyncio
import logging

import pytest

from aiobt.core.clock import ManualClock
from aiobt.msgs import Clock, OccupancyGrid, PoseStamped, Twist
from aiobt.transport import Bus, BusSettings, PayloadTooLarge, SimClockFollower, open_bus

from .logs import assert_one_bad_message_warning

pytestmark = pytest.mark.integration


async def test_publish_subscribe_between_two_sessions(bus: Bus, bus_settings: BusSettings) -> None:
    sub = bus.subscribe("cmd_vel", Twist)
    async with open_bus(bus_settings) as other:
        pub = other.publisher("cmd_vel", Twist)
        assert await pub.wait_for_subscribers(5.0)
        for i in range(5):
            pub.put(Twist.planar(0.1 * i, -0.1 * i))
        received = [await sub.next(timeout=5.0) for _ in range(5)]
    assert [t.linear.x for t in received] == pytest.approx([0.0, 0.1, 0.2, 0.3, 0.4])
    assert sub.latest == received[-1]


async def test_waiting_for_subscribers_says_whether_one_came(bus_settings: BusSettings) -> None:
    async with open_bus(bus_settings) as bus:
        lonely = bus.publisher("nobody_listens", Twist)
        assert await lonely.wait_for_subscribers(0.2) is False
        bus.subscribe("nobody_listens", Twist)
        assert await lonely.wait_for_subscribers(5.0) is True


async def test_callback_runs_in_the_event_loop(bus: Bus, bus_settings: BusSettings) -> None:
    loop = asyncio.get_running_loop()
    got: asyncio.Queue[tuple[Twist, bool]] = asyncio.Queue()

    def on_twist(twist: Twist) -> None:
        got.put_nowait((twist, asyncio.get_running_loop() is loop))

    bus.subscribe("cmd_vel", Twist, callback=on_twist)
    async with open_bus(bus_settings) as other:
        pub = other.publisher("cmd_vel", Twist)
        assert await pub.wait_for_subscribers(5.0)
        pub.put(Twist.planar(0.5, 0.0))
        twist, in_loop = await asyncio.wait_for(got.get(), 5.0)
    assert twist.linear.x == 0.5
    assert in_loop


async def test_subscribing_again_after_a_close(bus: Bus, bus_settings: BusSettings) -> None:
    first = bus.subscribe("pose", PoseStamped)
    first.close()  # closed by its owner: the bus lets go of it
    assert first not in bus._closables
    again = bus.subscribe("pose", PoseStamped)
    async with open_bus(bus_settings) as other:
        pub = other.publisher("pose", PoseStamped)
        assert await pub.wait_for_subscribers(5.0)
        pub.put(PoseStamped.from_xy_yaw(1.0, 2.0, 0.0))
        assert (await again.next(timeout=5.0)).x == 1.0
    assert first.received == 0


async def test_latched_topic_reaches_a_late_joiner(bus: Bus, bus_settings: BusSettings) -> None:
    grid = OccupancyGrid.from_array([[0, 100], [-1, 0]], 0.5)
    latched = bus.latched_publisher("map", OccupancyGrid)
    latched.put(grid)
    await asyncio.sleep(0.2)
    async with open_bus(bus_settings) as late:
        sub = late.subscribe("map", OccupancyGrid, latched=True)
        received = await sub.wait_latest(timeout=5.0)
    assert received == grid
    assert received.array.tolist() == [[0, 100], [-1, 0]]


async def test_bad_payload_is_logged_once_and_dropped(
    bus: Bus, bus_settings: BusSettings, caplog: pytest.LogCaptureFixture
) -> None:
    sub = bus.subscribe("goal_pose", PoseStamped)
    key = f"{bus.namespace}/goal_pose"
    async with open_bus(bus_settings) as other:
        raw = other.session.declare_publisher(key)
        await asyncio.sleep(0.3)  # let the subscriber's declaration reach the router
        with caplog.at_level(logging.WARNING, logger="aiobt.transport.topics"):
            for _ in range(3):
                raw.put(b'{"x": 1.0, "y": NaN}')
            raw.put(b'{"x": 1.0, "y": 2.0, "yaw": 0.0}')
            good = await sub.next(timeout=5.0)
        raw.undeclare()  # type: ignore[no-untyped-call]
    assert (good.x, good.y) == (1.0, 2.0)
    assert sub.dropped_invalid == 3
    assert_one_bad_message_warning(caplog, key, "'y'")


async def test_oversized_payload_is_refused(bus_settings: BusSettings) -> None:
    small = BusSettings(
        connect=bus_settings.connect, namespace=bus_settings.namespace, max_payload=200
    )
    async with open_bus(small) as bus:
        pub = bus.publisher("map", OccupancyGrid)
        big = OccupancyGrid.from_array([[i % 100 for i in range(300)]], 0.1)
        with pytest.raises(PayloadTooLarge, match=r"exceeds the limit of 200 bytes"):
            pub.put(big)


async def test_sim_clock_follower_drives_a_manual_clock(
    bus: Bus, bus_settings: BusSettings
) -> None:
    follower = SimClockFollower(bus, ManualClock())
    woke = asyncio.Event()

    async def sleeper() -> None:
        await follower.clock.sleep(2.0)
        woke.set()

    task = asyncio.create_task(sleeper())
    async with open_bus(bus_settings) as sim:
        pub = sim.publisher("clock", Clock)
        assert await pub.wait_for_subscribers(5.0)
        pub.put(Clock(clock=1.0))
        assert await follower.wait_started(5.0) == 1.0
        assert not woke.is_set()
        pub.put(Clock(clock=2.5))
        await asyncio.wait_for(woke.wait(), 5.0)
    assert follower.clock.now() == 2.5
    await task


async def test_sim_clock_follower_default_clock_wakes_sleepers_when_due(
    bus: Bus, bus_settings: BusSettings
) -> None:
    follower = SimClockFollower(bus)  # a SimTime: the loop looks only when a sleeper is due
    async with open_bus(bus_settings) as sim:
        pub = sim.publisher("clock", Clock, reliable=True)
        assert await pub.wait_for_subscribers(5.0)
        pub.put(Clock(clock=1.0))
        assert await follower.wait_started(5.0) == 1.0
        sleeper = asyncio.create_task(follower.clock.sleep(1.0))
        sooner = asyncio.create_task(follower.clock.sleep(0.9))  # both from 1.0, before 1.5
        await asyncio.sleep(0)
        pub.put(Clock(clock=1.5))
        pub.put(Clock(clock=1.99))
        await asyncio.wait_for(sooner, 5.0)  # due at 1.9: woken by 1.99
        assert follower.clock.now() == 1.99
        assert not sleeper.done()  # 1.99 < its deadline 2.0
        pub.put(Clock(clock=2.0))
        await asyncio.wait_for(sleeper, 5.0)
    assert follower.clock.now() == 2.0
    follower.close()
