"""``Relay``: a callback on Zenoh's thread for each message, over a real router."""

from __future__ import annotations

import asyncio
import logging
import threading
from collections.abc import Callable

import pytest

from aiobt.msgs import PoseStamped
from aiobt.transport import Bus, BusSettings, open_bus
from aiobt.transport.relay import relay

from .logs import assert_one_bad_message_warning
from .test_latest import CountingLoop

pytestmark = [pytest.mark.integration, pytest.mark.timeout(60)]


async def until(holds: Callable[[], bool]) -> None:
    async with asyncio.timeout(5.0):
        while not holds():  # noqa: ASYNC110 - the relay never wakes the loop
            await asyncio.sleep(0.01)


async def test_each_message_is_handed_over_on_zenohs_thread_in_order(
    bus: Bus, bus_settings: BusSettings, monkeypatch: pytest.MonkeyPatch
) -> None:
    counting = CountingLoop(bus.bridge.loop)
    monkeypatch.setattr(bus.bridge, "loop", counting)
    got: list[tuple[float, int]] = []
    odom = relay(bus, "odom", PoseStamped, lambda m: got.append((m.x, threading.get_ident())))
    async with open_bus(bus_settings) as robot:
        pub = robot.publisher("odom", PoseStamped)
        assert await pub.wait_for_subscribers(5.0)
        for i in range(20):
            pub.put(PoseStamped.from_xy_yaw(float(i), 0.0, 0.0))
        await until(lambda: len(got) == 20)
    assert [x for x, _ in got] == [float(i) for i in range(20)]
    assert threading.get_ident() not in {thread for _, thread in got}  # not the loop's
    assert counting.handed == 0
    assert odom.received == 20


async def test_errors_and_bad_payloads_are_logged_and_the_stream_goes_on(
    bus: Bus, bus_settings: BusSettings, caplog: pytest.LogCaptureFixture
) -> None:
    got: list[float] = []

    def fn(message: PoseStamped) -> None:
        if message.x == 2.0:
            raise ValueError("two")
        got.append(message.x)

    odom = relay(bus, "odom", PoseStamped, fn)
    key = f"{bus.namespace}/odom"
    async with open_bus(bus_settings) as other:
        raw = other.session.declare_publisher(key)
        await asyncio.sleep(0.3)  # let the subscriber's declaration reach the router
        with caplog.at_level(logging.WARNING):
            for payload in (b'{"x": 1.0, "y": 0.0, "yaw": 0.0}', b'{"x": 1.0, "y": NaN}',
                            b'{"x": 2.0, "y": 0.0, "yaw": 0.0}', b'{"x": 1.0, "y": NaN}',
                            b'{"x": 3.0, "y": 0.0, "yaw": 0.0}'):  # fmt: skip
                raw.put(payload)
            await until(lambda: 3.0 in got)
        raw.undeclare()  # type: ignore[no-untyped-call]
    assert got == [1.0, 3.0]
    assert (odom.received, odom.dropped_invalid) == (5, 2)
    failed = [r for r in caplog.records if "relay callback failed" in r.getMessage()]
    assert len(failed) == 1
    assert "two" in failed[0].getMessage()
    assert_one_bad_message_warning(caplog, key, "'y'")


async def test_closed_it_is_undeclared(bus: Bus, bus_settings: BusSettings) -> None:
    got: list[float] = []
    odom = relay(bus, "odom", PoseStamped, lambda m: got.append(m.x))
    async with open_bus(bus_settings) as robot:
        pub = robot.publisher("odom", PoseStamped)
        assert await pub.wait_for_subscribers(5.0)
        odom.close()
        odom.close()  # idempotent
        await until(lambda: not pub.matched)
        pub.put(PoseStamped.from_xy_yaw(1.0, 0.0, 0.0))
    assert got == []
