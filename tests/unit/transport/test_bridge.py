"""The thread-to-loop bridge: order, batching, failures, a closed loop (no Zenoh)."""

from __future__ import annotations

import asyncio
import logging
import threading

import pytest

from aiobt.transport import PayloadTooLarge
from aiobt.transport.bridge import LoopBridge


async def test_calls_from_threads_run_in_the_loop_in_order() -> None:
    loop = asyncio.get_running_loop()
    bridge = LoopBridge(loop, max_payload=100)
    seen: list[tuple[int, bool]] = []
    done = asyncio.Event()

    def record(i: int) -> None:
        seen.append((i, asyncio.get_running_loop() is loop))
        if i == 999:
            done.set()

    def produce() -> None:
        for i in range(1000):
            bridge.call(record, i)

    thread = threading.Thread(target=produce)
    thread.start()
    thread.join(timeout=10.0)
    await asyncio.wait_for(done.wait(), 5.0)
    assert [i for i, _ in seen] == list(range(1000))
    assert all(in_loop for _, in_loop in seen)


async def test_a_burst_wakes_the_loop_once(monkeypatch: pytest.MonkeyPatch) -> None:
    loop = asyncio.get_running_loop()
    bridge = LoopBridge(loop, max_payload=100)
    wakes = 0
    real = loop.call_soon_threadsafe

    def counting(*args: object) -> asyncio.Handle:
        nonlocal wakes
        wakes += 1
        return real(*args)  # type: ignore[arg-type]

    monkeypatch.setattr(loop, "call_soon_threadsafe", counting)
    got: list[int] = []
    for i in range(5):
        bridge.call(got.append, i)
    await asyncio.sleep(0)
    assert got == [0, 1, 2, 3, 4]
    assert wakes == 1
    bridge.call(got.append, 5)  # after the drain: a new wake
    await asyncio.sleep(0)
    assert got[-1] == 5
    assert wakes == 2


async def test_a_call_made_while_draining_runs_in_a_later_pass() -> None:
    bridge = LoopBridge(asyncio.get_running_loop(), max_payload=100)
    order: list[str] = []

    def first() -> None:
        order.append("first")
        bridge.call(order.append, "nested")

    bridge.call(first)
    bridge.call(order.append, "second")
    for _ in range(3):
        await asyncio.sleep(0)
    assert order == ["first", "second", "nested"]


async def test_a_failing_call_is_logged_and_the_rest_still_run(
    caplog: pytest.LogCaptureFixture,
) -> None:
    bridge = LoopBridge(asyncio.get_running_loop(), max_payload=100)
    got: list[int] = []

    def broken() -> None:
        raise RuntimeError("boom")

    with caplog.at_level(logging.ERROR, logger="aiobt.transport"):
        bridge.call(broken)
        bridge.call(got.append, 1)
        await asyncio.sleep(0)
    assert got == [1]
    [record] = [r for r in caplog.records if "failed in the event loop" in r.getMessage()]
    assert "broken" in record.getMessage()
    assert record.exc_info is not None
    assert str(record.exc_info[1]) == "boom"


def test_calls_after_the_loop_closed_are_dropped_quietly() -> None:
    loop = asyncio.new_event_loop()
    bridge = LoopBridge(loop, max_payload=100)
    loop.close()
    bridge.call(print, "never")  # no RuntimeError into the Zenoh thread
    assert bridge.closed
    bridge.call(print, "still never")


def test_size_check_names_key_size_and_limit() -> None:
    bridge = LoopBridge(asyncio.new_event_loop(), max_payload=10)
    try:
        bridge.check_size("robot/map", b"x" * 10)
        with pytest.raises(PayloadTooLarge, match=r"robot/map: payload of 11 bytes exceeds"):
            bridge.check_size("robot/map", b"x" * 11)
    finally:
        bridge.loop.close()
