"""The velocity smoother between a command and the base, with real processes: a step
command reaches the base as a ramp within ``max_accel`` (by odometry), and a command
that stops coming stops the base after ``velocity_timeout``."""

from __future__ import annotations

import asyncio
from collections.abc import Callable

import pytest

from aiobt.msgs import Twist
from aiobt.transport import Bus, BusSettings, Publisher

from .chain import Spawn, Trace, start_chain

pytestmark = [pytest.mark.integration, pytest.mark.e2e]
ACCEL, DECEL, TIMEOUT, TOP = 0.5, 2.5, 0.5, 0.5  # max_accel, |max_decel|, velocity_timeout, m/s


@pytest.mark.timeout(120)
async def test_a_step_is_a_ramp_and_a_stale_command_stops_the_base(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    trace = Trace(bus)
    smoother = ["--cmd-vel-out", "cmd_vel", "--max-accel", str(ACCEL), "0", "3.2",
                "--velocity-timeout", str(TIMEOUT)]  # fmt: skip
    await start_chain(spawn, bus, bus_settings, smoother=smoother, monitor=None, controller=None)
    command = bus.publisher("cmd_vel_nav", Twist)
    await trace.until(lambda: trace.now > 0.0, 10.0, "clock")
    start = trace.now
    sending = asyncio.create_task(_send(command, trace, until=lambda: trace.now > start + 2.0))
    await trace.until(sending.done, 60.0, "two seconds of commands")
    last = trace.now  # the last command, on the sim clock (within a clock tick)
    await trace.until(lambda: trace.still_since(0.3), 30.0, "standstill")

    ramp = [(o.header.stamp, o.twist.linear.x) for o in trace.odom if o.header.stamp <= last]
    moving = [t for t, v in ramp if v > 1e-3]
    cruising = [t for t, v in ramp if v >= TOP - 1e-3]
    print(f"ramp {cruising[0] - moving[0]:.3f} s to {TOP} m/s; last command at {last:.2f}")
    assert cruising[0] - moving[0] >= TOP / ACCEL - 0.1  # not the base's own 2.5 m/s^2
    for (t1, v1), (t2, v2) in zip(ramp, ramp[5:], strict=False):  # over 0.1 s
        assert v2 - v1 <= ACCEL * (t2 - t1) + 0.03, (t1, v1, t2, v2)
    after = [(o.header.stamp - last, o.twist.linear.x) for o in trace.odom if o.header.stamp > last]
    still = next(dt for dt, v in after if abs(v) < 1e-3)
    print(f"base stopped {still:.3f} s after the last command")
    assert all(v >= TOP - 0.02 for dt, v in after if dt < TIMEOUT - 0.05)  # kept on until then
    assert TIMEOUT <= still <= TIMEOUT + TOP / DECEL + 0.1


async def _send(command: Publisher[Twist], trace: Trace, until: Callable[[], bool]) -> None:
    """A step to full speed, sent again after every other odometry message (50 Hz of sim
    time), until ``until()``: bounded waits, no fixed sleeps."""
    while not until():
        command.put(Twist.planar(TOP, 0.0))
        seen = len(trace.odom)
        await trace.until(lambda seen=seen: len(trace.odom) >= seen + 2, 10.0, "odometry")  # type: ignore[misc]
