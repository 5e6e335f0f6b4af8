"""A robot (hardware-like: no pose in map) and the localization service on a real
router, a driver that steers by the simulation's truth (the test's eyes only), and
the error of ``{ns}/pose`` against that truth, matched by stamp."""

from __future__ import annotations

import asyncio
import contextlib
import math
from collections.abc import AsyncIterator, Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
import pytest

from aiobt.msgs import Empty, PoseStamped, PoseWithCovarianceStamped, Twist
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings, Subscription
from aiobt.transport.keys import SIM_POSE
from aiobt_services.localization.messages import LocalizationStats
from tests.integration.services import common, up

Spawn = Callable[[Sequence[str]], ServiceProcess]
START = (2.0, 9.75, 0.0)  # the office world's start


async def start_stack(
    spawn: Spawn, bus: Bus, settings: BusSettings, *, speed: float, seed: int = 1,
    localization: Sequence[str] = ("--params-file", "sim_robot"),
    start: tuple[float, float, float] = START,
) -> tuple[ServiceProcess, ServiceProcess]:  # fmt: skip
    robot = spawn(["-m", "aiobt_services.robot", "--world", "office", "--speed", str(speed),
                   "--pose-source", "none", "--seed", str(seed),
                   "--start", *(str(v) for v in start), *common(settings)])  # fmt: skip
    await up(bus, "robot", robot)
    loc = spawn(["-m", "aiobt_services.localization", *localization, *common(settings)])
    await up(bus, "localization", loc)
    return robot, loc


async def set_initial_pose(bus: Bus, x: float, y: float, yaw: float) -> None:
    """The short form, as a user types it; waits until amcl_pose answers near it."""
    amcl = bus.subscribe("amcl_pose", PoseWithCovarianceStamped, queue_size=4)
    pub = bus.publisher("initialpose", PoseWithCovarianceStamped)
    assert await pub.wait_for_subscribers(10.0), "localization does not read initialpose"
    pub.put(PoseWithCovarianceStamped.model_validate({"x": x, "y": y, "yaw": yaw}))
    async with _within(20.0, "no amcl_pose near the initial pose"):
        async for msg in amcl:
            if math.hypot(msg.x - x, msg.y - y) < 0.3:
                break
    amcl.close()


@dataclass
class Tracking:
    """Pairs of (estimate, truth) at the same stamps."""

    estimates: dict[float, tuple[float, float, float]] = field(default_factory=dict)
    truths: dict[float, tuple[float, float, float]] = field(default_factory=dict)

    def errors(self, since: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        stamps = sorted(s for s in self.estimates.keys() & self.truths.keys() if s >= since)
        if not stamps:
            return np.zeros(0), np.zeros(0)
        est = np.array([self.estimates[s] for s in stamps])
        tru = np.array([self.truths[s] for s in stamps])
        dist = np.hypot(est[:, 0] - tru[:, 0], est[:, 1] - tru[:, 1])
        heading = np.abs((est[:, 2] - tru[:, 2] + np.pi) % (2 * np.pi) - np.pi)
        return dist, heading

    def on_estimate(self, msg: PoseStamped) -> None:
        self.estimates[round(msg.header.stamp, 6)] = (msg.x, msg.y, msg.yaw)

    def on_truth(self, msg: PoseStamped) -> None:
        self.truths[round(msg.header.stamp, 6)] = (msg.x, msg.y, msg.yaw)


def track(bus: Bus) -> Tracking:
    tracking = Tracking()
    bus.subscribe("pose", PoseStamped, callback=tracking.on_estimate, queue_size=200)
    bus.subscribe(SIM_POSE, PoseStamped, callback=tracking.on_truth, queue_size=200)
    return tracking


async def drive(bus: Bus, route: Sequence[tuple[float, float]], within: float) -> PoseStamped:
    """Steer through ``route`` by the truth (0.5 m/s, turning on the spot first);
    one command per truth message, so at the simulation's pace at any speed-up."""
    truth: Subscription[PoseStamped] = bus.subscribe(SIM_POSE, PoseStamped, queue_size=1)
    cmd = bus.publisher("cmd_vel", Twist)
    remaining = list(route)
    try:
        async with _within(within, f"route not driven: left {remaining}"):
            async for pose in truth:
                if math.hypot(remaining[0][0] - pose.x, remaining[0][1] - pose.y) < 0.25:
                    remaining.pop(0)
                    if not remaining:
                        return pose
                gx, gy = remaining[0]
                err = math.remainder(math.atan2(gy - pose.y, gx - pose.x) - pose.yaw, math.tau)
                cmd.put(
                    Twist.planar(0.5 if abs(err) < 0.4 else 0.0, max(-1.2, min(1.2, 2.5 * err)))
                )
    finally:
        cmd.put(Twist.planar(0.0, 0.0))
        truth.close()
    raise AssertionError("unreachable")


async def spin(bus: Bus, turns: float, rate: float = 1.0) -> None:
    """Turn on the spot ``turns`` full turns, counted on the truth."""
    truth: Subscription[PoseStamped] = bus.subscribe(SIM_POSE, PoseStamped, queue_size=1)
    cmd = bus.publisher("cmd_vel", Twist)
    turned, last = 0.0, None
    try:
        async with _within(60.0, "spin not done"):
            async for pose in truth:
                if last is not None:
                    turned += abs(math.remainder(pose.yaw - last, math.tau))
                last = pose.yaw
                if turned >= turns * math.tau:
                    return
                cmd.put(Twist.planar(0.0, rate))
    finally:
        cmd.put(Twist.planar(0.0, 0.0))
        truth.close()


async def stats(bus: Bus) -> LocalizationStats:
    return await bus.call("localization/stats", Empty(), LocalizationStats, timeout=5.0)


@contextlib.asynccontextmanager
async def _within(seconds: float, what: str) -> AsyncIterator[None]:
    """A bounded wait: the test fails naming ``what`` after ``seconds``."""
    try:
        async with asyncio.timeout(seconds):
            yield
    except TimeoutError:
        pytest.fail(f"{what} within {seconds} s")
