"""SimTime bound to a source: listened to only while held, fresh again after idle."""

from __future__ import annotations

import asyncio

import pytest

from aiobt.core.clock import ManualClock
from aiobt.transport.actions.fresh import FreshGate, held_during
from aiobt.transport.on_demand import OnDemand
from aiobt.transport.simtime import SimTime, clock_held

LINGER = 0.05  # wall s


class Sim:
    """A fake clock source: records attaches and detaches; ``tick`` sends a stamp the
    way the follower does (receive on 'its thread', then the loop hears of it)."""

    def __init__(self, clock: SimTime) -> None:
        self.clock = clock
        self.time = 0.0
        self.attaches = 1  # subscribed before binding, as the follower is
        self.detaches = 0
        self.detached = asyncio.Event()
        clock.bind(self)

    @property
    def attached(self) -> bool:
        return self.attaches > self.detaches

    def attach(self) -> None:
        self.attaches += 1
        self.detached.clear()

    def detach(self) -> None:
        self.detaches += 1
        self.detached.set()

    def tick(self, dt: float = 0.01) -> None:
        """The simulation moved on by ``dt``; a stamp reaches us only while attached."""
        self.time += dt
        if self.attached:
            self.clock.receive(self.time)
            self.clock.arrived()


async def bound() -> tuple[SimTime, Sim]:
    clock = SimTime(linger=LINGER)
    return clock, Sim(clock)


async def run_sim(sim: Sim, until: asyncio.Future[object] | asyncio.Task[object]) -> None:
    """Tick every loop turn (bounded) until ``until`` is done."""
    for _ in range(10_000):
        if until.done():
            return
        sim.tick()
        await asyncio.sleep(0)
    raise AssertionError("never done")


async def test_idle_it_lets_the_source_go_after_the_linger_and_time_stands() -> None:
    clock, sim = await bound()
    sim.tick()
    assert clock.fresh
    assert clock.listening
    await asyncio.wait_for(sim.detached.wait(), 2.0)
    assert not clock.listening
    assert not clock.fresh
    before = clock.now()
    sim.tick(5.0)  # the robot's time moves on unheard
    assert clock.now() == before


async def test_a_sleep_after_idle_attaches_and_counts_from_a_fresh_stamp() -> None:
    clock, sim = await bound()
    sim.tick()
    await asyncio.wait_for(sim.detached.wait(), 2.0)
    sim.tick(10.0)  # 10 robot s pass while nobody listens: clock still at 0.01
    sleeper = asyncio.ensure_future(clock.sleep(0.5))
    await asyncio.sleep(0)
    assert sim.attached
    assert sim.attaches == 2
    await run_sim(sim, sleeper)
    assert clock.now() >= 10.01 + 0.5  # counted from the robot's time, not the stale 0.01
    assert clock.now() < 10.01 + 0.5 + 0.05


async def test_held_keeps_listening_beyond_the_linger_then_lets_go() -> None:
    clock, sim = await bound()
    sim.tick()
    async with clock.held(1.0) as fresh:
        assert fresh
        await asyncio.sleep(LINGER * 4)
        assert sim.attached
        assert sim.detaches == 0
    await asyncio.wait_for(sim.detached.wait(), 2.0)


async def test_a_hold_after_detaching_waits_for_a_fresh_stamp() -> None:
    clock, sim = await bound()
    sim.tick()
    await asyncio.wait_for(sim.detached.wait(), 2.0)
    sim.tick(3.0)
    entered = asyncio.Event()

    async def goal() -> float:
        async with clock.held(1.0):
            entered.set()
            return clock.now()

    task = asyncio.ensure_future(goal())
    await asyncio.sleep(0)
    assert not entered.is_set()
    sim.tick()
    assert await asyncio.wait_for(task, 1.0) == pytest.approx(3.02)


async def test_held_times_out_without_stamps_and_says_so() -> None:
    clock, sim = await bound()
    sim.tick()
    await asyncio.wait_for(sim.detached.wait(), 2.0)
    async with clock.held(0.05) as fresh:
        assert fresh is False
        assert clock.now() == pytest.approx(0.01)


async def test_a_stamp_in_flight_after_detaching_does_not_attach_again() -> None:
    clock, sim = await bound()
    sim.tick()
    await asyncio.wait_for(sim.detached.wait(), 2.0)
    clock.receive(0.5)
    clock.arrived()  # delivered by the old subscription after the undeclare
    assert sim.attaches == 1
    assert not clock.listening
    assert clock.now() == 0.5


async def test_a_new_user_within_the_linger_keeps_the_subscription() -> None:
    clock, sim = await bound()
    sim.tick()
    for _ in range(5):  # short gaps between users: never detached
        async with clock.held(1.0):
            await asyncio.sleep(LINGER / 5)
        await asyncio.sleep(LINGER / 5)
    assert sim.detaches == 0
    assert sim.attaches == 1


async def test_time_never_runs_backwards_across_detach_and_attach() -> None:
    clock, sim = await bound()
    sim.time = 50.0
    sim.tick()
    await asyncio.wait_for(sim.detached.wait(), 2.0)
    sim.time = 1.0  # the simulation restarted while nobody listened
    async with clock.held(0.05) as fresh:
        sim.tick()
        await asyncio.sleep(0)
        assert fresh is False or clock.now() >= 50.01
    assert clock.now() == pytest.approx(50.01)


async def test_an_unbound_sim_time_is_always_fresh() -> None:
    clock = SimTime()
    assert clock.fresh
    assert clock.listening
    assert await clock.wait_fresh(0.0) is True
    async with clock_held(ManualClock(), 0.0) as fresh:
        assert fresh


async def test_linger_must_be_finite_and_not_negative() -> None:
    with pytest.raises(ValueError, match="linger"):
        SimTime(linger=-1.0)


# -- action goals on it ----------------------------------------------------------------------


async def test_the_gate_starts_at_once_when_fresh_and_in_order_once_fresh() -> None:
    clock, sim = await bound()
    sim.tick()
    started: list[tuple[str, float]] = []
    gate: FreshGate[str] = FreshGate(
        clock, lambda name: started.append((name, clock.now())), timeout=1.0
    )
    gate("a")
    assert [(n, round(t, 6)) for n, t in started] == [("a", 0.01)]
    await asyncio.wait_for(sim.detached.wait(), 2.0)
    sim.tick(2.0)
    gate("b")
    gate("c")
    await asyncio.sleep(0)
    assert [name for name, _ in started] == ["a"]  # b, c wait for the robot's time
    assert sim.attached
    sim.tick()
    for _ in range(10):
        await asyncio.sleep(0)
    assert [(n, round(t, 6)) for n, t in started[1:]] == [("b", 2.02), ("c", 2.02)]


async def test_the_gate_starts_anyway_after_its_timeout_and_on_close() -> None:
    clock, sim = await bound()
    sim.tick()
    await asyncio.wait_for(sim.detached.wait(), 2.0)
    started: list[str] = []
    gate = FreshGate(clock, started.append, timeout=0.05)
    gate("late")
    await asyncio.sleep(0.2)
    assert started == ["late"]
    gate("closing")
    await gate.aclose()
    assert started == ["late", "closing"]


async def test_a_held_execute_keeps_the_clock_for_its_run() -> None:
    clock, sim = await bound()
    sim.tick()
    release = asyncio.Event()

    async def execute(x: int) -> int:
        await release.wait()
        return x

    task = asyncio.ensure_future(held_during(clock, execute)(7))
    await asyncio.sleep(LINGER * 4)
    assert sim.detaches == 0
    release.set()
    assert await task == 7
    await asyncio.wait_for(sim.detached.wait(), 2.0)
    assert held_during(ManualClock(), execute) is execute


async def test_on_demand_streams_attach_once_the_clock_is_fresh() -> None:
    clock, sim = await bound()
    sim.tick()
    await asyncio.wait_for(sim.detached.wait(), 2.0)
    stamps: list[float] = []

    class Stream:
        async def wait_latest(self, timeout: float | None = None) -> object:  # noqa: ASYNC109
            return object()

        def close(self) -> None:
            pass

    def attach() -> list[Stream]:
        stamps.append(clock.now())
        return [Stream(), Stream()]

    feed = OnDemand(attach, lambda: None, clock, linger=0.5)
    acquired = asyncio.ensure_future(feed.acquire(1.0))
    await run_sim(sim, acquired)
    assert acquired.result() is True
    assert stamps
    assert stamps[0] > 0.01
    feed.release()
    detacher = asyncio.ensure_future(run_sim(sim, asyncio.ensure_future(asyncio.sleep(1.0))))
    await asyncio.wait_for(sim.detached.wait(), 3.0)  # 0.5 robot s of linger, then the clock's
    assert not feed.attached
    detacher.cancel()
