"""A subscription's handling of samples: decode, drop bad ones (logged once per field), size.

Samples are fed straight to ``on_sample`` as Zenoh's thread would (no Zenoh session).
"""

from __future__ import annotations

import asyncio
import logging
from dataclasses import dataclass

import pytest
import zenoh

from aiobt.msgs import PoseStamped, Twist
from aiobt.transport.bridge import LoopBridge
from aiobt.transport.topics import Subscription

KEY = "robot/goal_pose"


@dataclass
class FakePayload:
    data: bytes

    def to_bytes(self) -> bytes:
        return self.data


class FakeSample:
    def __init__(self, payload: FakePayload, kind: zenoh.SampleKind = zenoh.SampleKind.PUT) -> None:
        self.payload = payload
        self.kind = kind


def feed(sub: Subscription[PoseStamped], *payloads: bytes) -> None:
    for data in payloads:
        sub.on_sample(FakeSample(FakePayload(data)))  # type: ignore[arg-type]


def subscription(max_payload: int = 10_000) -> Subscription[PoseStamped]:
    bridge = LoopBridge(asyncio.get_running_loop(), max_payload)
    return Subscription(KEY, PoseStamped, bridge, callback=None, queue_size=10)


async def test_bad_payloads_are_dropped_and_logged_once_per_field(
    caplog: pytest.LogCaptureFixture,
) -> None:
    sub = subscription()
    with caplog.at_level(logging.DEBUG, logger="aiobt.transport.topics"):
        feed(
            sub,
            b'{"x": 1.0, "y": NaN}',
            b"not json at all",
            b'{"x": 1.0, "y": Infinity}',
            b'{"header": {}, "pose": {}, "colour": "red"}',
            b"{broken",
            b'{"x": 1.0, "y": 2.0}',
        )
        good = await sub.next(timeout=1.0)
    assert (good.x, good.y) == (1.0, 2.0)
    assert sub.dropped_invalid == 5
    assert sub.received == 1
    warnings = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]
    assert len(warnings) == 3  # 'y' once, '<payload>' once, 'colour' once
    assert all(KEY in w for w in warnings)
    assert any("field 'y'" in w for w in warnings)
    assert any("field '<payload>'" in w for w in warnings)
    assert any("field 'colour'" in w for w in warnings)


async def test_oversized_payload_is_refused_on_receipt(caplog: pytest.LogCaptureFixture) -> None:
    sub = subscription(max_payload=100)
    big = PoseStamped.from_xy_yaw(1.0, 2.0, frame_id="m" * 200).to_json()
    with caplog.at_level(logging.WARNING, logger="aiobt.transport.topics"):
        feed(sub, big, b'{"x": 3.0, "y": 4.0}')
        good = await sub.next(timeout=1.0)
    assert good.x == 3.0
    assert sub.dropped_invalid == 1
    [warning] = [r.getMessage() for r in caplog.records]
    assert "exceeds the limit of 100 bytes" in warning
    assert KEY in warning


async def test_deletes_are_ignored_and_latest_is_kept() -> None:
    sub = subscription()
    sub.on_sample(FakeSample(FakePayload(b""), kind=zenoh.SampleKind.DELETE))  # type: ignore[arg-type]
    feed(sub, b'{"x": 1.0, "y": 1.0}', b'{"x": 2.0, "y": 2.0}')
    assert (await sub.wait_latest(timeout=1.0)).x == 2.0
    assert [(await sub.next(timeout=1.0)).x for _ in range(2)] == [1.0, 2.0]
    assert sub.dropped_invalid == 0


async def test_a_failing_callback_is_logged_and_later_messages_still_arrive(
    caplog: pytest.LogCaptureFixture,
) -> None:
    got: list[float] = []

    def on_twist(twist: Twist) -> None:
        if twist.linear.x < 0:
            raise ValueError("reverse not allowed")
        got.append(twist.linear.x)

    bridge = LoopBridge(asyncio.get_running_loop(), 10_000)
    sub = Subscription("robot/cmd_vel", Twist, bridge, callback=on_twist, queue_size=10)
    with caplog.at_level(logging.ERROR, logger="aiobt.transport.topics"):
        for x in (-1.0, 0.5):
            sub.on_sample(FakeSample(FakePayload(Twist.planar(x, 0.0).to_json())))  # type: ignore[arg-type]
        await asyncio.sleep(0)
    assert got == [0.5]
    assert any("subscriber callback failed" in r.getMessage() for r in caplog.records)


def xs(*values: float) -> list[bytes]:
    return [PoseStamped.from_xy_yaw(x, 0.0).to_json() for x in values]


async def test_a_full_queue_keeps_the_newest_messages_and_says_so_once(
    caplog: pytest.LogCaptureFixture,
) -> None:
    bridge = LoopBridge(asyncio.get_running_loop(), 10_000)
    sub = Subscription(KEY, PoseStamped, bridge, callback=None, queue_size=3)
    feed(sub, *xs(1, 2, 3, 4, 5))
    await asyncio.sleep(0)
    assert [(await sub.next(timeout=1.0)).x for _ in range(3)] == [3.0, 4.0, 5.0]
    with pytest.raises(TimeoutError):
        await sub.next(timeout=0.05)
    assert sub.dropped_overflow == 2
    warnings = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]
    assert len(warnings) == 1
    assert KEY in warnings[0]
    assert "queue of 3 is full" in warnings[0]


async def test_close_ends_iteration_after_the_queued_messages() -> None:
    sub = subscription()
    feed(sub, *xs(1, 2))
    await asyncio.sleep(0)

    async def read_all() -> list[float]:
        return [message.x async for message in sub]

    reader = asyncio.create_task(read_all())
    await asyncio.sleep(0.01)
    assert not reader.done()  # both read, now waiting for more
    sub.close()
    feed(sub, *xs(3))  # after the close: not queued
    assert await asyncio.wait_for(reader, 1.0) == [1.0, 2.0]
    with pytest.raises(StopAsyncIteration):
        await sub.next(timeout=1.0)


async def test_concurrent_readers_each_get_a_message() -> None:
    sub = subscription()
    readers = [asyncio.create_task(sub.next(timeout=1.0)) for _ in range(2)]
    await asyncio.sleep(0.01)
    feed(sub, *xs(1, 2))
    got = sorted(message.x for message in await asyncio.gather(*readers))
    assert got == [1.0, 2.0]


async def test_close_tells_its_owner_once() -> None:
    sub = subscription()
    told: list[str] = []
    sub.on_close = lambda: told.append(sub.key)
    sub.close()
    sub.close()  # idempotent: the owner (the bus) is told once
    assert told == [KEY]
