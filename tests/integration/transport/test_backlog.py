"""``Backlog``: a topic's recent messages kept by Zenoh, taken in order, over a real
router; and a publisher telling its readers' coming and going."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable

import pytest

from aiobt.msgs import PoseStamped
from aiobt.transport import Bus, BusSettings, open_bus
from aiobt.transport.backlog import Backlog, backlog

from .logs import assert_one_bad_message_warning
from .test_latest import CountingLoop

pytestmark = [pytest.mark.integration, pytest.mark.timeout(60)]


async def taken_until(
    ring: Backlog[PoseStamped], done: Callable[[list[float]], bool]
) -> list[float]:
    """The x of every message taken (looking every 10 ms) until ``done`` holds (5 s)."""
    xs: list[float] = []
    async with asyncio.timeout(5.0):
        while not done(xs):
            xs += [m.x for m in ring.take()]
            await asyncio.sleep(0.01)
    return xs


async def test_take_gives_what_came_since_the_last_take_in_order_without_the_loop(
    bus: Bus, bus_settings: BusSettings, monkeypatch: pytest.MonkeyPatch
) -> None:
    counting = CountingLoop(bus.bridge.loop)
    monkeypatch.setattr(bus.bridge, "loop", counting)
    odom = backlog(bus, "odom", PoseStamped, 16)
    assert odom.take() == []
    async with open_bus(bus_settings) as robot:
        pub = robot.publisher("odom", PoseStamped)
        assert await pub.wait_for_subscribers(5.0)
        for i in range(10):
            pub.put(PoseStamped.from_xy_yaw(float(i), 0.0, 0.0))
        assert await taken_until(odom, lambda xs: len(xs) >= 10) == [float(i) for i in range(10)]
        for i in range(10, 15):
            pub.put(PoseStamped.from_xy_yaw(float(i), 0.0, 0.0))
        assert await taken_until(odom, lambda xs: len(xs) >= 5) == [10.0, 11.0, 12.0, 13.0, 14.0]
    assert odom.received == 15
    assert counting.handed == 0  # no arrival called into the event loop


async def test_a_full_ring_keeps_the_newest(bus: Bus, bus_settings: BusSettings) -> None:
    odom = backlog(bus, "odom", PoseStamped, 8)
    came: list[PoseStamped] = []
    all_came = asyncio.Event()

    def count(message: PoseStamped) -> None:
        came.append(message)
        if len(came) == 30:
            all_came.set()

    bus.subscribe("odom", PoseStamped, count)  # declared after: tells when all 30 came
    async with open_bus(bus_settings) as robot:
        pub = robot.publisher("odom", PoseStamped)
        assert await pub.wait_for_subscribers(5.0)
        for i in range(30):
            pub.put(PoseStamped.from_xy_yaw(float(i), 0.0, 0.0))
        async with asyncio.timeout(5.0):
            await all_came.wait()
        first = [m.x for m in odom.take()]
        xs = first + await taken_until(odom, lambda xs: 29.0 in first + xs)
    # the ring's capacity of the newest (the 30th may come just after the first take)
    assert first == [float(i) for i in range(int(first[-1]) - 7, int(first[-1]) + 1)]
    assert first[-1] >= 28.0
    assert xs == [float(i) for i in range(int(xs[0]), 30)]  # the newest, in order


async def test_a_bad_payload_is_skipped_logged_once_and_counted(
    bus: Bus, bus_settings: BusSettings, caplog: pytest.LogCaptureFixture
) -> None:
    odom = backlog(bus, "odom", PoseStamped, 8)
    key = f"{bus.namespace}/odom"
    async with open_bus(bus_settings) as other:
        raw = other.session.declare_publisher(key)
        await asyncio.sleep(0.3)  # let the subscriber's declaration reach the router
        with caplog.at_level(logging.WARNING, logger="aiobt.transport.backlog"):
            raw.put(b'{"x": 1.0, "y": 2.0, "yaw": 0.0}')
            raw.put(b'{"x": 1.0, "y": NaN}')
            raw.put(b'{"x": 1.0, "y": NaN}')
            raw.put(b'{"x": 3.0, "y": 2.0, "yaw": 0.0}')
            xs = await taken_until(odom, lambda xs: 3.0 in xs)
        raw.undeclare()  # type: ignore[no-untyped-call]
    assert xs == [1.0, 3.0]
    assert (odom.received, odom.dropped_invalid) == (4, 2)
    assert_one_bad_message_warning(caplog, key, "'y'")


async def test_closed_it_is_undeclared_and_takes_nothing_more(
    bus: Bus, bus_settings: BusSettings
) -> None:
    odom = backlog(bus, "odom", PoseStamped, 8)
    async with open_bus(bus_settings) as robot:
        pub = robot.publisher("odom", PoseStamped)
        assert await pub.wait_for_subscribers(5.0)
        odom.close()
        odom.close()  # idempotent
        async with asyncio.timeout(5.0):
            while pub.matched:  # noqa: ASYNC110 - the router forgets the subscriber
                await asyncio.sleep(0.01)
        pub.put(PoseStamped.from_xy_yaw(1.0, 0.0, 0.0))
    assert odom.take() == []
    assert odom.received == 0


async def test_a_publisher_tells_the_loop_when_readers_come_and_go(
    bus: Bus, bus_settings: BusSettings
) -> None:
    pub = bus.publisher("pose", PoseStamped)
    seen: list[bool] = []
    changed = asyncio.Event()

    def on_change() -> None:
        seen.append(pub.matched)
        changed.set()

    pub.on_matching_change(on_change)
    assert not pub.matched
    async with open_bus(bus_settings) as reader_bus:
        reader = reader_bus.latest("pose", PoseStamped)
        async with asyncio.timeout(5.0):
            await changed.wait()
        assert seen == [True]
        changed.clear()
        reader.close()
        async with asyncio.timeout(5.0):
            await changed.wait()
    assert seen == [True, False]
    with pytest.raises(TypeError, match="latched"):
        bus.latched_publisher("map", PoseStamped).on_matching_change(on_change)
