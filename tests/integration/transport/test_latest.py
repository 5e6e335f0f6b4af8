"""``bus.latest``: the newest message, decoded when read, over a real router.

It reads a Zenoh ring of ``keep`` samples: a burst faster than the reads leaves the
newest ones (``received`` counts what was taken), and no arrival calls the loop."""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import Callable
from typing import Any

import pytest

from aiobt.msgs import OccupancyGrid, PoseStamped
from aiobt.transport import Bus, BusSettings, Latest, open_bus

from .logs import assert_one_bad_message_warning

pytestmark = [pytest.mark.integration, pytest.mark.timeout(60)]


async def wait_for(holds: Callable[[], bool], timeout: float = 5.0) -> None:  # noqa: ASYNC109
    """Poll ``holds`` (Latest never wakes the loop, so there is nothing to await)."""
    async with asyncio.timeout(timeout):
        while not holds():  # noqa: ASYNC110 - nothing to await: no wake-up is the point
            await asyncio.sleep(0.01)


def newest_x(latest: Latest[PoseStamped]) -> float | None:
    pose = latest.get()
    return None if pose is None else pose.x


async def test_get_answers_the_newest_message_and_when_it_came(
    bus: Bus, bus_settings: BusSettings
) -> None:
    pose = bus.latest("pose", PoseStamped)
    assert pose.get() is None
    async with open_bus(bus_settings) as robot:
        pub = robot.publisher("pose", PoseStamped)
        assert await pub.wait_for_subscribers(5.0)
        before = time.monotonic()
        for i in range(20):
            pub.put(PoseStamped.from_xy_yaw(float(i), 0.0, 0.0))
        await wait_for(lambda: newest_x(pose) == 19.0)
    assert 1 <= pose.received <= 20  # the ring of one keeps the newest
    newest = pose.get()
    assert newest is not None
    assert newest.x == 19.0
    assert before <= pose.arrived <= time.monotonic()
    assert pose.get() is newest  # decoded once: the same object until a newer arrives


class CountingLoop:
    """The bus's loop, counting the calls handed to it from other threads."""

    def __init__(self, loop: asyncio.AbstractEventLoop) -> None:
        self.loop = loop
        self.handed = 0

    def call_soon_threadsafe(self, *args: Any) -> Any:
        self.handed += 1
        return self.loop.call_soon_threadsafe(*args)

    def __getattr__(self, name: str) -> Any:
        return getattr(self.loop, name)


async def test_arrivals_never_call_into_the_event_loop(
    bus: Bus, bus_settings: BusSettings, monkeypatch: pytest.MonkeyPatch
) -> None:
    counting = CountingLoop(bus.bridge.loop)
    monkeypatch.setattr(bus.bridge, "loop", counting)
    pose: Latest[PoseStamped] = bus.latest("pose", PoseStamped)
    async with open_bus(bus_settings) as robot:
        pub = robot.publisher("pose", PoseStamped)
        assert await pub.wait_for_subscribers(5.0)
        for i in range(50):
            pub.put(PoseStamped.from_xy_yaw(float(i), 0.0, 0.0))
        await wait_for(lambda: newest_x(pose) == 49.0)
        assert counting.handed == 0
        subscribed = bus.subscribe("pose", PoseStamped, queue_size=1)  # the control
        await asyncio.sleep(0.3)  # let the subscriber's declaration reach the router
        pub.put(PoseStamped.from_xy_yaw(2.0, 0.0, 0.0))
        await subscribed.next(timeout=5.0)
    assert counting.handed >= 1  # a subscription does call in: the count can see it
    newest = pose.get()
    assert newest is not None
    assert newest.x == 2.0


async def test_a_bad_payload_is_logged_once_and_the_last_good_message_stays(
    bus: Bus, bus_settings: BusSettings, caplog: pytest.LogCaptureFixture
) -> None:
    pose = bus.latest("goal_pose", PoseStamped)
    key = f"{bus.namespace}/goal_pose"
    async with open_bus(bus_settings) as other:
        raw = other.session.declare_publisher(key)
        await asyncio.sleep(0.3)  # let the subscriber's declaration reach the router
        raw.put(b'{"x": 1.0, "y": 2.0, "yaw": 0.0}')
        await wait_for(lambda: pose.received == 1)
        good = pose.get()
        with caplog.at_level(logging.WARNING, logger="aiobt.transport.latest"):
            for n in range(2, 5):
                raw.put(b'{"x": 1.0, "y": NaN}')
                await wait_for(lambda n=n: pose.received == n)  # type: ignore[misc]
                assert pose.get() is good
        raw.undeclare()  # type: ignore[no-untyped-call]
    assert good is not None
    assert (good.x, good.y) == (1.0, 2.0)
    assert pose.dropped_invalid == 3
    assert_one_bad_message_warning(caplog, key, "'y'")


async def test_a_payload_over_the_limit_is_refused(bus_settings: BusSettings) -> None:
    small = BusSettings(
        connect=bus_settings.connect, namespace=bus_settings.namespace, max_payload=200
    )
    async with open_bus(small) as bus, open_bus(bus_settings) as mapper:
        grid = bus.latest("map", OccupancyGrid)
        pub = mapper.publisher("map", OccupancyGrid)
        assert await pub.wait_for_subscribers(5.0)
        pub.put(OccupancyGrid.from_array([[i % 100 for i in range(300)]], 0.1))
        await wait_for(lambda: grid.received == 1)
        assert grid.get() is None
        assert grid.dropped_invalid == 1


async def test_latched_value_reaches_a_late_reader(bus: Bus, bus_settings: BusSettings) -> None:
    bus.latched_publisher("map", OccupancyGrid).put(OccupancyGrid.from_array([[0, 100]], 0.5))
    async with open_bus(bus_settings) as late:
        grid = late.latest("map", OccupancyGrid, latched=True)
        await wait_for(lambda: grid.get() is not None)
        got = grid.get()
    assert got is not None
    assert got.array.tolist() == [[0, 100]]


async def test_closed_it_keeps_the_last_message_and_hears_no_more(
    bus: Bus, bus_settings: BusSettings
) -> None:
    pose = bus.latest("pose", PoseStamped)
    control = bus.latest("pose", PoseStamped)  # stays open: shows the next message came
    async with open_bus(bus_settings) as robot:
        pub = robot.publisher("pose", PoseStamped)
        assert await pub.wait_for_subscribers(5.0)
        pub.put(PoseStamped.from_xy_yaw(3.0, 0.0, 0.0))
        await wait_for(lambda: pose.received == 1 and control.received == 1)
        pose.close()
        pose.close()  # idempotent
        assert pose not in bus._closables
        pub.put(PoseStamped.from_xy_yaw(4.0, 0.0, 0.0))
        await wait_for(lambda: control.received == 2)
    kept, newest = pose.get(), control.get()
    assert kept is not None
    assert kept.x == 3.0
    assert newest is not None
    assert newest.x == 4.0
    assert pose.received == 1


async def test_kept_messages_come_newest_first_decoded_as_far_as_read(
    bus: Bus, bus_settings: BusSettings
) -> None:
    poses = bus.latest("pose", PoseStamped, keep=4)
    assert list(poses.newest_first()) == []
    async with open_bus(bus_settings) as robot:
        pub = robot.publisher("pose", PoseStamped)
        assert await pub.wait_for_subscribers(5.0)
        for i in range(6):
            pub.put(PoseStamped.from_xy_yaw(float(i), 0.0, 0.0))
        await wait_for(lambda: newest_x(poses) == 5.0)
    reading = poses.newest_first()
    first = next(reading)
    assert first.x == 5.0
    assert poses.get() is first  # decoded once, shared with get()
    assert [p.x for p in reading] == [4.0, 3.0, 2.0]  # the last 4 only
    again = list(poses.newest_first())
    assert again[0] is first  # not decoded twice
    with pytest.raises(ValueError, match="keep"):
        bus.latest("pose", PoseStamped, keep=0)


async def test_a_malformed_kept_payload_is_skipped_and_counted_once(
    bus: Bus, bus_settings: BusSettings
) -> None:
    poses = bus.latest("goal_pose", PoseStamped, keep=3)
    async with open_bus(bus_settings) as other:
        raw = other.session.declare_publisher(f"{bus.namespace}/goal_pose")
        await asyncio.sleep(0.3)  # let the subscriber's declaration reach the router
        raw.put(b'{"x": 1.0, "y": 2.0, "yaw": 0.0}')
        raw.put(b'{"x": 1.0, "y": NaN}')
        raw.put(b'{"x": 3.0, "y": 2.0, "yaw": 0.0}')
        await wait_for(lambda: poses.received == 3)
        raw.undeclare()  # type: ignore[no-untyped-call]
    assert [p.x for p in poses.newest_first()] == [3.0, 1.0]
    assert [p.x for p in poses.newest_first()] == [3.0, 1.0]
    assert poses.dropped_invalid == 1


async def test_wait_latest_waits_for_a_first_message_and_nothing_calls_the_loop(
    bus: Bus, bus_settings: BusSettings, monkeypatch: pytest.MonkeyPatch
) -> None:
    counting = CountingLoop(bus.bridge.loop)
    monkeypatch.setattr(bus.bridge, "loop", counting)
    pose = bus.latest("pose", PoseStamped)
    with pytest.raises(TimeoutError):
        await pose.wait_latest(timeout=0.05)  # nothing yet: bounded
    async with open_bus(bus_settings) as robot:
        pub = robot.publisher("pose", PoseStamped)
        assert await pub.wait_for_subscribers(5.0)
        waiters = [asyncio.ensure_future(pose.wait_latest(timeout=5.0)) for _ in range(2)]
        await asyncio.sleep(0)
        pub.put(PoseStamped.from_xy_yaw(7.0, 0.0, 0.0))
        got = await asyncio.gather(*waiters)
        assert [g.x for g in got] == [7.0, 7.0]
        for i in range(30):
            pub.put(PoseStamped.from_xy_yaw(float(i), 0.0, 0.0))
        await wait_for(lambda: newest_x(pose) == 29.0)
    assert counting.handed == 0  # no arrival, the first either, calls into the loop
    assert (await pose.wait_latest(timeout=0.01)).x == 29.0  # there: no wait
