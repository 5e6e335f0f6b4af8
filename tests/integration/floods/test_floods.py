"""A 10,000 messages/s flood on a topic the robot subscribes to, from another process:
the robot's memory stays flat, its sim keeps its speed-up and its services answer.

Each test measures the same robot unflooded and then flooded, in the same run, and
compares: figures are printed (``-s``) and the bounds are generous (the machine is
shared), yet far from what the unbounded code did (memory grew ~13 MiB per second
of flood, the sim ran at 0.03x and services went unanswered for seconds).
"""

from __future__ import annotations

import asyncio
import statistics
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import pytest

from aiobt.msgs import Clock, Empty
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings, Subscription
from aiobt_services.robot.messages import ObstacleList

pytestmark = [pytest.mark.integration, pytest.mark.e2e]

Spawn = Callable[[Sequence[str]], ServiceProcess]
SPEED = 4.0
FLOOD_RATE = 10_000
FLOOD_SECONDS = 5.0
MIB = 1024 * 1024


def rss_bytes(pid: int) -> int:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) * 1024
    raise AssertionError(f"no VmRSS for process {pid}")


@dataclass(frozen=True)
class Figures:
    speed: float  # sim seconds per wall second
    reply_median: float  # s, srv/obstacles/list
    reply_max: float
    rss_growth: int  # bytes, from the start of the phase to its largest sample
    replies: int


async def measure(
    bus: Bus, clock: Subscription[Clock], pid: int, seconds: float, running: Callable[[], bool]
) -> Figures:
    """Call a service back to back for ``seconds`` (or while ``running()``), watching the
    sim clock and the robot's RSS."""
    rss0 = peak = rss_bytes(pid)
    sim0 = (await clock.wait_latest(5.0)).clock
    wall0 = time.monotonic()
    replies: list[float] = []
    while time.monotonic() - wall0 < seconds and running():
        sent = time.monotonic()
        await bus.call("obstacles/list", Empty(), ObstacleList, timeout=20.0)
        replies.append(time.monotonic() - sent)
        peak = max(peak, rss_bytes(pid))
    latest = clock.latest
    assert latest is not None
    speed = (latest.clock - sim0) / (time.monotonic() - wall0)
    return Figures(speed, statistics.median(replies), max(replies), peak - rss0, len(replies))


async def flood_and_measure(
    spawn: Spawn, bus: Bus, settings: BusSettings, topic: str, model: str, payload: str
) -> tuple[Figures, Figures, int]:
    """Figures of the robot unflooded, then flooded on ``topic``; and the messages sent."""
    args = ["-m", "aiobt_services.robot", "--world", "small", "--speed", str(SPEED)]
    robot = spawn([*args, "--connect", settings.connect[0], "--namespace", settings.namespace])
    if not await bus.presence(bus.keys.topic("nodes/robot")).wait(30.0):
        pytest.fail(f"robot did not come up:\n{robot.output()}")
    clock = bus.subscribe("clock", Clock, queue_size=1)
    await measure(bus, clock, robot.pid, 1.0, lambda: True)  # warm up
    calm = await measure(bus, clock, robot.pid, FLOOD_SECONDS, lambda: True)
    flooder = spawn(
        [
            "-m", "tests.integration.floods.flood_proc",
            "--connect", settings.connect[0], "--namespace", settings.namespace,
            "--topic", topic, "--model", model, "--json", payload,
            "--rate", str(FLOOD_RATE), "--seconds", str(FLOOD_SECONDS),
        ]
    )  # fmt: skip
    assert await asyncio.to_thread(flooder.wait_for_output, "flooding", 30.0), flooder.output()
    flooded = await measure(
        bus, clock, robot.pid, FLOOD_SECONDS, lambda: "sent" not in flooder.output()
    )
    assert await asyncio.to_thread(flooder.wait_for_output, "sent", 30.0), flooder.output()
    sent = int(flooder.output().split("sent")[-1].split()[0])
    print(f"{topic}: calm {calm}\n{topic}: flooded {flooded}, {sent} sent", file=sys.stderr)
    assert robot.running, robot.output()
    return calm, flooded, sent


def assert_unharmed(calm: Figures, flooded: Figures, sent: int) -> None:
    assert sent >= 0.9 * FLOOD_RATE * FLOOD_SECONDS  # the flood really was 10 k/s
    assert flooded.rss_growth < 25 * MIB, "the robot's memory grew under the flood"
    assert flooded.speed > 0.7 * calm.speed, "the sim slowed under the flood"
    assert flooded.reply_median < max(3 * calm.reply_median, calm.reply_median + 0.02)
    assert flooded.reply_max < 1.0


@pytest.mark.timeout(180)
async def test_initialpose_flood(spawn: Spawn, bus: Bus, bus_settings: BusSettings) -> None:
    calm, flooded, sent = await flood_and_measure(
        spawn, bus, bus_settings, "initialpose", "PoseStamped", '{"x": 0.0, "y": 0.0, "yaw": 0.0}'
    )
    assert_unharmed(calm, flooded, sent)


@pytest.mark.timeout(180)
async def test_cmd_vel_flood(spawn: Spawn, bus: Bus, bus_settings: BusSettings) -> None:
    calm, flooded, sent = await flood_and_measure(
        spawn, bus, bus_settings, "cmd_vel", "Twist", "{}"
    )
    assert_unharmed(calm, flooded, sent)
