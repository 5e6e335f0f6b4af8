"""Every subscription is bounded: a burst keeps the newest messages, costs no memory
beyond its queue, and a slow callback cannot take more than a fifth of the loop.

Samples are fed straight to ``on_sample`` as Zenoh's thread would (no Zenoh session).
"""

from __future__ import annotations

import asyncio
import itertools
import logging
import time
from collections.abc import Callable

import pytest

from aiobt.msgs import PoseStamped
from aiobt.transport.bridge import LoopBridge
from aiobt.transport.topics import PAUSE_PER_WORK, Subscription

from .test_subscription import FakePayload, FakeSample, feed, xs

KEY = "robot/initialpose"


def make(
    queue_size: int, callback: Callable[[PoseStamped], object] | None = None
) -> Subscription[PoseStamped]:
    bridge = LoopBridge(asyncio.get_running_loop(), 10_000)
    return Subscription(KEY, PoseStamped, bridge, callback=callback, queue_size=queue_size)


async def settle(sub: Subscription[PoseStamped], received: int) -> None:
    """Until ``received`` messages were delivered (drains are loop callbacks: no event)."""
    async with asyncio.timeout(5.0):
        while sub.received < received:  # noqa: ASYNC110
            await asyncio.sleep(0.005)


def warnings_of(caplog: pytest.LogCaptureFixture) -> list[str]:
    return [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]


async def test_a_burst_to_a_callback_keeps_the_newest_and_warns_once(
    caplog: pytest.LogCaptureFixture,
) -> None:
    got: list[float] = []
    sub = make(10, lambda m: got.append(m.x))
    with caplog.at_level(logging.WARNING, logger="aiobt.transport.topics"):
        feed(sub, *xs(*range(500)))  # before the loop runs: one drain for all of them
        await settle(sub, 10)
        feed(sub, *xs(*range(500, 1000)))
        await settle(sub, 20)
    assert got[:10] == [float(x) for x in range(490, 500)]
    assert got[-1] == 999.0
    assert len(got) == 20
    assert sub.dropped_overflow == 980
    [warning] = warnings_of(caplog)
    assert KEY in warning
    assert "the callback falls behind" in warning
    assert "queue of 10" in warning


async def test_a_queue_of_one_keeps_the_latest_silently(caplog: pytest.LogCaptureFixture) -> None:
    sub = make(1)
    with caplog.at_level(logging.WARNING, logger="aiobt.transport.topics"):
        feed(sub, *xs(*range(100)))
        await settle(sub, 1)
    assert sub.latest is not None
    assert sub.latest.x == 99.0
    assert (await sub.next(timeout=1.0)).x == 99.0
    assert sub.dropped_overflow == 99
    assert warnings_of(caplog) == []


def test_queue_size_must_be_positive() -> None:
    async def build() -> None:
        make(0)

    with pytest.raises(ValueError, match=f"{KEY}: queue_size must be at least 1, got 0"):
        asyncio.run(build())


async def test_messages_of_a_burst_are_decoded_by_the_drain(
    caplog: pytest.LogCaptureFixture,
) -> None:
    sub = make(10)
    with caplog.at_level(logging.WARNING, logger="aiobt.transport.topics"):
        feed(sub, *xs(1), b'{"x": NaN}', *xs(2))  # the 2nd and 3rd come while a drain is due
        await settle(sub, 2)
    assert [(await sub.next(timeout=1.0)).x for _ in range(2)] == [1.0, 2.0]
    assert sub.dropped_invalid == 1
    assert sub.received == 2
    [warning] = warnings_of(caplog)
    assert "field 'x'" in warning


async def test_a_slow_callback_is_paused_in_proportion_to_its_work() -> None:
    """Each delivery takes WORK of CPU time; the next comes no sooner than
    PAUSE_PER_WORK * WORK later, so a flood gets at most a fifth of the loop."""
    work = 0.02
    starts: list[float] = []

    def slow(_: PoseStamped) -> None:
        starts.append(time.monotonic())
        began = time.thread_time()
        while time.thread_time() - began < work:  # a callback's CPU work, blocking the loop
            pass

    sub = make(1, slow)
    for x in range(4):
        feed(sub, *xs(x))
        await settle(sub, x + 1)
    gaps = [b - a for a, b in itertools.pairwise(starts)]
    assert len(gaps) == 3
    assert min(gaps) >= work * (1 + PAUSE_PER_WORK) * 0.95


async def test_deletes_in_a_burst_are_skipped() -> None:
    import zenoh

    sub = make(10)
    feed(sub, *xs(1))
    sub.on_sample(FakeSample(FakePayload(b""), kind=zenoh.SampleKind.DELETE))  # type: ignore[arg-type]
    feed(sub, *xs(2))
    await settle(sub, 2)
    assert sub.dropped_invalid == 0
    assert [(await sub.next(timeout=1.0)).x for _ in range(2)] == [1.0, 2.0]


async def test_a_callback_failing_on_every_message_logs_one_traceback(
    caplog: pytest.LogCaptureFixture,
) -> None:
    def broken(message: PoseStamped) -> None:
        raise RuntimeError(f"cannot use x={message.x}")

    sub = make(100, broken)
    with caplog.at_level(logging.ERROR, logger="aiobt.transport.topics"):
        for x in range(50):
            feed(sub, *xs(x))
            await settle(sub, x + 1)
        sub.close()
    errors = [r for r in caplog.records if r.levelno == logging.ERROR]
    assert len(errors) == 2, [r.getMessage() for r in errors]
    assert errors[0].exc_info is not None
    assert "cannot use x=0.0" in errors[0].getMessage()
    assert "failed 49 more times" in errors[1].getMessage()  # said when it closed
