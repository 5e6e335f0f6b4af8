"""SimTime: stamps from another thread, the loop woken only for a due sleeper."""

from __future__ import annotations

import asyncio
import math

from aiobt.transport.simtime import SimTime


async def test_now_reads_the_newest_stamp_received() -> None:
    clock = SimTime()
    assert clock.receive(1.5) is False  # nobody sleeps: the loop need not look
    assert clock.now() == 1.5
    await asyncio.sleep(0)
    clock.receive(1.0)  # earlier (a restarted simulation): ignored
    assert clock.now() == 1.5


async def test_time_stands_still_within_one_turn_of_the_loop() -> None:
    clock = SimTime()
    clock.receive(1.0)
    assert clock.now() == 1.0
    clock.receive(1.2)  # arrives while this turn's work runs
    assert clock.now() == 1.0
    await asyncio.sleep(0)
    assert clock.now() == 1.2  # a later turn sees it


async def test_receive_says_when_a_sleeper_is_due() -> None:
    clock = SimTime(10.0)
    sleeper = asyncio.create_task(clock.sleep(2.0))
    await asyncio.sleep(0)
    assert clock.due == 12.0
    assert clock.receive(11.9) is False
    assert not sleeper.done()
    assert clock.receive(12.0) is True
    clock.catch_up()
    await asyncio.wait_for(sleeper, 1.0)
    assert clock.due == math.inf  # nobody left
    assert clock.now() == 12.0


async def test_sleep_counts_from_the_newest_stamp() -> None:
    clock = SimTime()
    clock.receive(5.0)  # not yet seen by the loop
    sleeper = asyncio.create_task(clock.sleep(1.0))
    await asyncio.sleep(0)
    assert clock.due == 6.0
    assert clock.receive(5.5) is False
    assert clock.receive(6.2) is True
    clock.catch_up()
    await asyncio.wait_for(sleeper, 1.0)


async def test_the_earliest_deadline_is_due_first() -> None:
    clock = SimTime()
    late = asyncio.create_task(clock.sleep(3.0))
    early = asyncio.create_task(clock.sleep(1.0))
    await asyncio.sleep(0)
    assert clock.due == 1.0
    clock.receive(1.0)
    clock.catch_up()
    await asyncio.wait_for(early, 1.0)
    assert not late.done()
    assert clock.due == 3.0
    clock.receive(3.0)
    clock.catch_up()
    await asyncio.wait_for(late, 1.0)


async def test_a_zero_sleep_yields_without_a_deadline() -> None:
    clock = SimTime()
    await clock.sleep(0.0)
    assert clock.due == math.inf
