"""The velocity smoother stopped on sim time: its timer lets the clock go (an idle
smoother receives no stamps); the next command goes out at once, without waiting
for a stamp, ramped from the last output as Nav2's, and counts its age from the
robot's time once a stamp comes."""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator

import pytest

from aiobt.msgs import Twist
from aiobt.transport import Bus, Subscription
from aiobt.transport.simtime import SimTime
from aiobt_services.velocity_smoother import SmootherParams, VelocitySmoother
from aiobt_services.velocity_smoother.service import SmootherService
from tests.unit.transport.test_simtime_on_demand import Sim

LINGER = 0.05  # wall s the clock stays attached after the last hold


@contextlib.asynccontextmanager
async def running(bus: Bus) -> AsyncIterator[tuple[SmootherService, Sim, asyncio.Event]]:
    """The smoother (``velocity_timeout`` 0.2 s) on a :class:`SimTime` fed by a fake
    simulation running at about 10x (10 ms of sim time per wall ms) while the event
    yielded is set (at first), heard while attached."""
    going = asyncio.Event()
    going.set()
    clock = SimTime(linger=LINGER)
    sim = Sim(clock)
    sim.tick()

    async def simulate() -> None:
        while True:
            await going.wait()
            sim.tick()
            await asyncio.sleep(0.001)

    ticker = asyncio.create_task(simulate())
    params = SmootherParams(velocity_timeout=0.2)
    service = SmootherService(bus, clock, VelocitySmoother(params))
    service.start()
    try:
        yield service, sim, going
    finally:
        await service.stop()
        ticker.cancel()
        await asyncio.gather(ticker, return_exceptions=True)


async def outputs(out: Subscription[Twist]) -> list[float]:
    """The outputs until 0.3 wall s pass without one (30 sim s: long stopped)."""
    seen = []
    while True:
        try:
            seen.append((await out.next(timeout=0.3)).linear.x)
        except TimeoutError:
            return seen


async def test_stopped_it_lets_the_clock_go_and_the_next_command_ramps_at_robot_time(
    local_bus: Bus,
) -> None:
    out = local_bus.subscribe("cmd_vel_smoothed", Twist)
    async with running(local_bus) as (service, sim, going):
        async with asyncio.timeout(2.0):  # no command yet: nothing to publish, no clock
            await sim.detached.wait()
        assert service.resting
        for burst in range(2):  # the first command, then one after a stop
            stood = sim.time
            await asyncio.sleep(0.05)  # the robot's time moves on unheard
            assert sim.time > stood + 0.2  # by more than velocity_timeout
            going.clear()  # and then stands: no stamp to wait for
            service.on_command(Twist.planar(0.5, 0.0))
            first = await out.next(timeout=1.0)  # sent at once, without a stamp
            going.set()
            seen = [first.linear.x, *await outputs(out)]
            # one period's step from 0 within max_accel (2.5 m/s^2, 0.05 s), then, its
            # age counted from the fresh stamp, up to the command and the timeout's
            # ramp to zero (its age from the stale time: straight to zero)
            assert seen[0] == pytest.approx(0.125), burst
            assert max(seen) == pytest.approx(0.5), burst
            assert seen[-1] == 0.0, burst
            assert service.resting
            async with asyncio.timeout(2.0):  # stopped again: the clock let go
                await sim.detached.wait()
            assert not sim.attached


async def test_a_command_while_the_clock_is_still_held_goes_out_at_once(
    local_bus: Bus,
) -> None:
    out = local_bus.subscribe("cmd_vel_smoothed", Twist)
    async with running(local_bus) as (service, sim, _):
        for _ in range(100):  # bounded: the timer's first turn finds nothing to send
            if service.resting:
                break
            await asyncio.sleep(0)
        assert service.resting
        assert not sim.detached.is_set()  # within the linger: time still fresh
        service.on_command(Twist.planar(0.3, 0.0))
        first = await out.next(timeout=1.0)
        assert first.linear.x == pytest.approx(0.125)
        assert sim.attaches == 1  # never let go, never attached again
