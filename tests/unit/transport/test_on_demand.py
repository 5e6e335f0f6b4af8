"""OnDemand: the robot's streams subscribed while goals run, let go after a linger."""

from __future__ import annotations

import asyncio

import pytest

from aiobt.core.clock import ManualClock
from aiobt.transport.on_demand import OnDemand


class FakeStream:
    def __init__(self) -> None:
        self.arrived = asyncio.Event()
        self.closed = False

    async def wait_latest(self, timeout: float | None = None) -> object:  # noqa: ASYNC109
        await self.arrived.wait()
        return object()

    def close(self) -> None:
        self.closed = True


class Robot:
    """Counts attaches and forgets; its streams have a message at once unless told."""

    def __init__(self, silent: bool = False) -> None:
        self.attached: list[list[FakeStream]] = []
        self.forgotten = 0
        self.silent = silent

    def attach(self) -> list[FakeStream]:
        streams = [FakeStream() for _ in range(3)]
        if not self.silent:
            for stream in streams[:2]:
                stream.arrived.set()
        self.attached.append(streams)
        return streams

    def forget(self) -> None:
        self.forgotten += 1


def feed_of(robot: Robot, clock: ManualClock, linger: float = 5.0) -> OnDemand:
    return OnDemand(robot.attach, robot.forget, clock, linger=linger)


async def test_nothing_is_subscribed_until_a_goal_starts() -> None:
    robot = Robot()
    feed = feed_of(robot, ManualClock())
    assert not feed.attached
    assert robot.attached == []
    assert await feed.acquire(1.0) is True
    assert feed.attached
    assert len(robot.attached) == 1
    assert robot.forgotten == 1
    feed.detach()


async def test_streams_close_a_linger_after_the_last_goal() -> None:
    robot, clock = Robot(), ManualClock()
    feed = feed_of(robot, clock, linger=5.0)
    async with feed.active(1.0):
        async with feed.active(1.0):  # a second goal at once: the same streams
            pass
        await clock.forward(10.0)
        assert feed.attached  # one goal still runs
    await clock.forward(4.9)
    assert feed.attached
    await clock.forward(0.2)
    assert not feed.attached
    assert all(stream.closed for stream in robot.attached[0])
    assert len(robot.attached) == 1


async def test_a_goal_within_the_linger_keeps_the_streams() -> None:
    robot, clock = Robot(), ManualClock()
    feed = feed_of(robot, clock, linger=5.0)
    async with feed.active(1.0):
        pass
    await clock.forward(3.0)
    async with feed.active(1.0):
        await clock.forward(10.0)
        assert feed.attached
    assert len(robot.attached) == 1
    assert robot.forgotten == 1
    feed.detach()
    assert all(stream.closed for stream in robot.attached[0])


async def test_after_a_detach_the_next_goal_forgets_and_attaches_again() -> None:
    robot, clock = Robot(), ManualClock()
    feed = feed_of(robot, clock, linger=1.0)
    async with feed.active(1.0):
        pass
    await clock.forward(2.0)
    assert not feed.attached
    async with feed.active(1.0):
        assert feed.attached
    assert len(robot.attached) == 2
    assert robot.forgotten == 2
    feed.detach()


@pytest.mark.timeout(10)
async def test_no_samples_within_the_timeout_says_so() -> None:
    robot = Robot(silent=True)
    feed = feed_of(robot, ManualClock())
    async with feed.active(0.05) as fresh:
        assert fresh is False
        assert feed.attached  # the goal runs on; it sees no fresh pose
    feed.detach()


async def test_a_negative_linger_is_refused() -> None:
    with pytest.raises(ValueError, match="linger"):
        OnDemand(list, lambda: None, ManualClock(), linger=-1.0)


async def _spin(times: int = 20) -> None:
    for _ in range(times):
        await asyncio.sleep(0)


async def _one_behind_another(
    first_timeout: float = 5.0,
) -> tuple[Robot, OnDemand, asyncio.Task[bool], asyncio.Task[bool]]:
    """Silent streams on demand, waited for only on attach; a first user attaching and
    waiting, then a second arriving during that wait."""
    robot = Robot(silent=True)
    feed = OnDemand(robot.attach, robot.forget, ManualClock(), wait_on_attach_only=True)
    first = asyncio.create_task(feed.acquire(first_timeout))
    await _spin()
    second = asyncio.create_task(feed.acquire(5.0))
    await _spin()
    return robot, feed, first, second


def _messages_come(robot: Robot) -> None:
    for stream in robot.attached[0][:2]:
        stream.arrived.set()


@pytest.mark.timeout(10)
async def test_a_user_arriving_during_the_attach_wait_is_told_fresh_at_its_end() -> None:
    robot, feed, first, second = await _one_behind_another()
    assert not first.done()
    assert not second.done()
    _messages_come(robot)
    assert list(await asyncio.wait_for(asyncio.gather(first, second), 1.0)) == [True, True]
    assert len(robot.attached) == 1
    assert await asyncio.wait_for(feed.acquire(5.0), 1.0) is True  # attached: no wait
    feed.detach()


@pytest.mark.timeout(10)
async def test_an_attaching_user_cancelled_mid_wait_leaves_the_wait_to_the_next() -> None:
    """Before, the request behind a cancelled one was told fresh with nothing received
    (a candidate cause of the route server's 'no robot pose' in an e2e run, 2026-11-29)."""
    robot, feed, first, second = await _one_behind_another()
    first.cancel()
    await _spin()
    assert first.cancelled()
    assert not second.done()  # nothing came: still waiting, in the cancelled one's place
    _messages_come(robot)
    assert await asyncio.wait_for(second, 1.0) is True
    assert len(robot.attached) == 1  # the same streams
    feed.detach()


@pytest.mark.timeout(10)
async def test_silent_streams_cost_only_the_user_that_attached() -> None:
    _, feed, first, second = await _one_behind_another(first_timeout=0.05)
    assert await asyncio.wait_for(first, 1.0) is False
    assert await asyncio.wait_for(second, 1.0) is True  # its wait was the first's
    assert await asyncio.wait_for(feed.acquire(5.0), 1.0) is True  # and no wait after
    feed.detach()
