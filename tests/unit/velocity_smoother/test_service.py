"""The velocity smoother's service on an in-process bus and a hand-advanced clock: a
command is smoothed and sent as it arrives, the timer ramps a stale one down, and bad
commands are dropped and counted."""

from __future__ import annotations

import itertools

import pytest

from aiobt.core.clock import ManualClock
from aiobt.msgs import Twist
from aiobt.transport import Bus, Subscription
from aiobt_services.velocity_smoother import SmootherParams, VelocitySmoother
from aiobt_services.velocity_smoother.service import SmootherService


async def first_output(bus: Bus, out: Subscription[Twist], vx: float) -> float:
    command = bus.publisher("cmd_vel_nav", Twist)
    for _ in range(50):
        command.put(Twist.planar(vx, 0.0))
        try:
            return (await out.next(timeout=0.1)).linear.x
        except TimeoutError:
            continue
    raise AssertionError("no output")


async def test_sent_as_it_arrives_then_ramped_down_on_the_timer(local_bus: Bus) -> None:
    clock = ManualClock(10.0)
    service = SmootherService(
        local_bus, clock, VelocitySmoother(SmootherParams(velocity_timeout=0.2))
    )
    out = local_bus.subscribe("cmd_vel_smoothed", Twist)
    service.start()
    try:
        assert await first_output(local_bus, out, 0.5) == pytest.approx(0.125)  # no tick needed
        await clock.forward(1.0, step=0.01)  # the timer ramps up, the command goes stale
        seen = []
        while True:
            try:
                seen.append((await out.next(timeout=0.2)).linear.x)
            except TimeoutError:
                break
        peak = seen.index(max(seen))
        assert seen[peak] == pytest.approx(0.5)
        assert seen[-1] == 0.0  # then nothing more: stopped
        steps = [b - a for a, b in itertools.pairwise(seen[peak:])]
        assert all(-0.126 < d <= 0.0 for d in steps)
    finally:
        await service.stop()


async def test_malformed_and_nan_commands_are_dropped_and_counted(local_bus: Bus) -> None:
    clock = ManualClock(0.0)
    service = SmootherService(local_bus, clock, VelocitySmoother())
    service.start()
    try:
        key = local_bus.keys.topic("cmd_vel_nav")
        for payload in (b'{"linear": {"x": NaN}}', b'{"linear": {"x": "fast"}}'):
            local_bus.session.put(key, payload)
        service.on_command(Twist.model_construct(linear=Twist().linear.model_copy(
            update={"x": float("inf")}), angular=Twist().angular))  # fmt: skip
        for _ in range(500):  # the bad payloads' way through Zenoh: bounded
            if service.dropped >= 3:
                break
            await clock.forward(0.05)
        assert service.dropped == 3
    finally:
        await service.stop()
