"""``Latest`` reading a ring as Zenoh's ``RingChannel`` fills it (no Zenoh session):
what a read takes, decodes and refuses, ``keep``, the wait for a first message, close."""

from __future__ import annotations

import asyncio
import logging
import time
from collections import deque

import pytest
import zenoh

from aiobt.msgs import PoseStamped
from aiobt.transport.latest import WAIT_LOOK, WAIT_LOOK_MAX, Latest, look_after

from .test_subscription import FakePayload, FakeSample

KEY = "robot/pose"


class FakeRing:
    """A ring of ``capacity`` samples: a put past it drops the oldest (``RingChannel``).
    ``refill``: every read finds a new sample (a flood faster than the reader)."""

    def __init__(self, capacity: int, refill: bool = False) -> None:
        self.samples: deque[FakeSample] = deque(maxlen=capacity)
        self.reads = 0
        self.refill = refill

    def put(self, payload: bytes, kind: zenoh.SampleKind = zenoh.SampleKind.PUT) -> None:
        self.samples.append(FakeSample(FakePayload(payload), kind))

    def put_pose(self, x: float) -> None:
        self.put(PoseStamped.from_xy_yaw(x, 0.0, 0.0).to_json())

    def try_recv(self) -> FakeSample | None:
        self.reads += 1
        if self.refill:
            self.put_pose(float(self.reads))
        return self.samples.popleft() if self.samples else None


class Undeclared:
    def __init__(self) -> None:
        self.calls = 0

    def __call__(self) -> None:
        self.calls += 1


def bound(keep: int = 1, max_payload: int = 10_000) -> tuple[Latest[PoseStamped], FakeRing]:
    latest = Latest(KEY, PoseStamped, max_payload, keep=keep)
    ring = FakeRing(keep)
    latest.bind(ring, lambda: None)  # type: ignore[arg-type]
    return latest, ring


def test_a_read_takes_the_newest_the_ring_holds_and_decodes_it_once() -> None:
    latest, ring = bound()
    assert latest.get() is None
    assert latest.arrived != latest.arrived  # nan: nothing yet
    for x in (1.0, 2.0, 3.0):
        ring.put_pose(x)  # a ring of one keeps the newest
    before = time.monotonic()
    newest = latest.get()
    assert newest is not None
    assert newest.x == 3.0
    assert before <= latest.arrived <= time.monotonic()
    assert latest.get() is newest  # decoded once: the same object until a newer comes
    assert latest.received == 1  # the two pushed out before any read are not counted
    ring.put_pose(4.0)
    assert latest.received == 2  # reading the count takes too
    got = latest.get()
    assert got is not None
    assert got.x == 4.0


def test_a_delete_is_taken_and_not_counted() -> None:
    latest, ring = bound(keep=2)
    ring.put_pose(1.0)
    ring.put(b"", zenoh.SampleKind.DELETE)
    assert latest.received == 1
    got = latest.get()
    assert got is not None
    assert got.x == 1.0


def test_a_bad_payload_is_logged_once_naming_key_and_field_and_the_good_one_stays(
    caplog: pytest.LogCaptureFixture,
) -> None:
    latest, ring = bound()
    ring.put_pose(1.0)
    good = latest.get()
    with caplog.at_level(logging.WARNING, logger="aiobt.transport.latest"):
        for _ in range(3):
            ring.put(b'{"x": 1.0, "y": NaN}')
            assert latest.get() is good
    assert latest.dropped_invalid == 3
    warnings = [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]
    assert len(warnings) == 1, warnings
    assert KEY in warnings[0]
    assert "'y'" in warnings[0]


def test_a_payload_over_the_limit_is_refused() -> None:
    latest, ring = bound(max_payload=20)
    ring.put_pose(1.0)
    assert latest.get() is None
    assert latest.dropped_invalid == 1
    assert latest.received == 1


def test_kept_messages_come_newest_first_each_decoded_once_bad_ones_skipped() -> None:
    latest, ring = bound(keep=4)
    assert list(latest.newest_first()) == []
    for x in range(3):
        ring.put_pose(float(x))
    assert [p.x for p in latest.newest_first()] == [2.0, 1.0, 0.0]
    ring.put(b"{")
    for x in range(3, 6):
        ring.put_pose(float(x))  # the ring keeps 4: the bad one is among them
    reading = latest.newest_first()
    first = next(reading)
    assert first.x == 5.0
    assert latest.get() is first  # shared with get(): decoded once
    assert [p.x for p in reading] == [4.0, 3.0]  # the last 4 taken, the bad one skipped
    assert latest.dropped_invalid == 1
    assert next(latest.newest_first()) is first
    with pytest.raises(ValueError, match="keep"):
        Latest(KEY, PoseStamped, 100, keep=0)


def test_a_read_takes_a_bounded_number_from_a_ring_that_keeps_filling() -> None:
    latest = Latest(KEY, PoseStamped, 10_000, keep=2)
    ring = FakeRing(2, refill=True)
    latest.bind(ring, lambda: None)  # type: ignore[arg-type]
    assert latest.get() is not None  # returns although the ring is never empty
    assert ring.reads == latest.keep + 2


def test_close_takes_what_the_ring_holds_then_reads_it_no_more() -> None:
    latest = Latest(KEY, PoseStamped, 10_000)
    ring, undeclared, closed = FakeRing(1), Undeclared(), Undeclared()
    latest.bind(ring, undeclared)  # type: ignore[arg-type]
    latest.on_close = closed
    ring.put_pose(7.0)
    latest.close()
    latest.close()  # idempotent
    assert (undeclared.calls, closed.calls) == (1, 1)
    ring.put_pose(8.0)  # came after the close
    reads = ring.reads
    kept = latest.get()
    assert kept is not None
    assert kept.x == 7.0  # the last message taken stays the answer
    assert ring.reads == reads  # closed: the ring is not read again


async def test_wait_latest_returns_the_first_message_soon_after_it_came() -> None:
    latest, ring = bound()
    with pytest.raises(TimeoutError):
        await latest.wait_latest(timeout=0.02)  # nothing: bounded
    loop = asyncio.get_running_loop()
    loop.call_later(0.03, ring.put_pose, 5.0)
    began = loop.time()
    got = await latest.wait_latest(timeout=5.0)
    assert got.x == 5.0
    assert loop.time() - began < 0.03 + 0.03  # seen within a look (plus a loaded machine)
    ring.samples.clear()
    assert (await latest.wait_latest(timeout=0.01)).x == 5.0  # there already: no wait


def test_the_looks_for_a_first_message_are_a_tenth_of_the_wait_within_bounds() -> None:
    assert look_after(0.0) == WAIT_LOOK
    assert look_after(0.05) == pytest.approx(0.005)
    assert look_after(10.0) == WAIT_LOOK_MAX
