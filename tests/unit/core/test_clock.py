"""Clocks: ManualClock moves only when told; ScaledClock runs faster than the wall."""

from __future__ import annotations

import asyncio
import time

import pytest

from aiobt.core.clock import Clock, ManualClock, ScaledClock, SystemClock


def test_clocks_satisfy_protocol():
    for clock in (SystemClock(), ScaledClock(2.0), ManualClock()):
        assert isinstance(clock, Clock)


async def test_manual_clock_wakes_sleepers_in_deadline_order():
    clock = ManualClock(start=10.0)
    woke: list[str] = []

    async def sleeper(name: str, seconds: float) -> None:
        await clock.sleep(seconds)
        woke.append(f"{name}@{clock.now()}")

    tasks = [
        asyncio.ensure_future(sleeper("late", 2.0)),
        asyncio.ensure_future(sleeper("early", 1.0)),
    ]
    await asyncio.sleep(0)
    assert clock.pending_sleepers == 2
    assert clock.next_deadline() == 11.0
    clock.advance(0.5)
    await asyncio.sleep(0)
    assert woke == []
    clock.advance(2.0)
    await asyncio.gather(*tasks)
    assert woke == ["early@12.5", "late@12.5"]
    assert clock.pending_sleepers == 0
    assert clock.next_deadline() is None


async def test_manual_clock_set_never_goes_back_and_zero_sleep_returns():
    clock = ManualClock(5.0)
    clock.set(3.0)
    assert clock.now() == 5.0
    await asyncio.wait_for(clock.sleep(0.0), 1.0)
    await asyncio.wait_for(clock.sleep(-1.0), 1.0)


async def test_manual_clock_forward_lets_sleepers_sleep_again():
    clock = ManualClock()
    ticks: list[float] = []

    async def periodic() -> None:
        while True:
            await clock.sleep(1.0)
            ticks.append(clock.now())

    task = asyncio.ensure_future(periodic())
    await asyncio.sleep(0)
    try:
        await clock.forward(3.0, step=0.5)
    finally:
        task.cancel()
    assert ticks == [1.0, 2.0, 3.0]
    assert clock.now() == 3.0


async def test_cancelled_sleeper_is_not_pending():
    clock = ManualClock()
    task = asyncio.ensure_future(clock.sleep(1.0))
    await asyncio.sleep(0)
    task.cancel()
    await asyncio.sleep(0)
    assert clock.pending_sleepers == 0
    clock.advance(2.0)  # must not fail on the cancelled future


def test_scaled_clock_rejects_bad_factor():
    with pytest.raises(ValueError, match="factor"):
        ScaledClock(0.0)


async def test_scaled_clock_runs_faster():
    clock = ScaledClock(100.0, start=50.0)
    assert clock.factor == 100.0
    start_wall, start = time.monotonic(), clock.now()
    assert start >= 50.0
    await clock.sleep(1.0)  # 10 ms of wall time
    elapsed_wall = time.monotonic() - start_wall
    assert clock.now() - start >= 1.0
    assert elapsed_wall < 0.5
