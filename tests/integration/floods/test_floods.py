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
from collections.abc import Awaitable, Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import pytest

from aiobt.msgs import Clock, Empty, Header, IsPathValid, PoseStamped
from aiobt.msgs import Path as Path_
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
    speed: float  # sim seconds per wall second (0 if no clock was watched)
    reply_median: float  # s, of the service called
    reply_max: float
    rss_growth: int  # bytes, from the start of the phase to its largest sample
    replies: int


Call = Callable[[], Awaitable[object]]


async def measure(
    call: Call, clock: Subscription[Clock] | None, pid: int, seconds: float,
    running: Callable[[], bool],
) -> Figures:  # fmt: skip
    """Call a service back to back for ``seconds`` (or while ``running()``), watching the
    sim clock (if given) and the process's RSS."""
    rss0 = peak = rss_bytes(pid)
    sim0 = (await clock.wait_latest(5.0)).clock if clock is not None else 0.0
    wall0 = time.monotonic()
    replies: list[float] = []
    while time.monotonic() - wall0 < seconds and running():
        sent = time.monotonic()
        await call()
        replies.append(time.monotonic() - sent)
        peak = max(peak, rss_bytes(pid))
    speed = 0.0
    if clock is not None and clock.latest is not None:
        speed = (clock.latest.clock - sim0) / (time.monotonic() - wall0)
    return Figures(speed, statistics.median(replies), max(replies), peak - rss0, len(replies))


async def start(spawn: Spawn, bus: Bus, settings: BusSettings, service: str, *extra: str) -> int:
    """Start ``aiobt_services.{service}``; its PID once its liveliness token is up."""
    where = ["--connect", settings.connect[0], "--namespace", settings.namespace]
    proc = spawn(["-m", f"aiobt_services.{service}", *where, *extra])
    if not await bus.presence(bus.keys.topic(f"nodes/{service}")).wait(60.0):
        pytest.fail(f"{service} did not come up:\n{proc.output()}")
    return proc.pid


async def flood_and_measure(
    spawn: Spawn, settings: BusSettings, flood: tuple[str, str, str],
    call: Call, clock: Subscription[Clock] | None, pid: int,
) -> tuple[Figures, Figures, int]:  # fmt: skip
    """Figures of process ``pid`` unflooded, then flooded with ``flood`` (topic, model
    name, JSON payload); and the number of messages sent."""
    topic, model, payload = flood
    await measure(call, clock, pid, 1.0, lambda: True)  # warm up
    calm = await measure(call, clock, pid, FLOOD_SECONDS, lambda: True)
    flooder = spawn(
        [
            "-m", "tests.integration.floods.flood_proc",
            "--connect", settings.connect[0], "--namespace", settings.namespace,
            "--topic", topic, "--model", model, "--json", payload,
            "--rate", str(FLOOD_RATE), "--seconds", str(FLOOD_SECONDS),
        ]
    )  # fmt: skip
    assert await asyncio.to_thread(flooder.wait_for_output, "flooding", 30.0), flooder.output()
    flooded = await measure(call, clock, pid, FLOOD_SECONDS, lambda: "sent" not in flooder.output())
    assert await asyncio.to_thread(flooder.wait_for_output, "sent", 30.0), flooder.output()
    sent = int(flooder.output().split("sent")[-1].split()[0])
    print(f"{topic}: calm {calm}\n{topic}: flooded {flooded}, {sent} sent", file=sys.stderr)
    return calm, flooded, sent


def assert_unharmed(calm: Figures, flooded: Figures, sent: int) -> None:
    assert sent >= 0.9 * FLOOD_RATE * FLOOD_SECONDS  # the flood really was 10 k/s
    assert flooded.rss_growth < 25 * MIB, "the memory grew under the flood"
    assert flooded.speed >= 0.7 * calm.speed, "the sim slowed under the flood"
    assert flooded.reply_median < max(3 * calm.reply_median, calm.reply_median + 0.02)
    assert flooded.reply_max < 2.0  # the unbounded code: 8 s


async def robot_under_flood(
    spawn: Spawn, bus: Bus, settings: BusSettings, flood: tuple[str, str, str]
) -> None:
    pid = await start(spawn, bus, settings, "robot", "--world", "small", "--speed", str(SPEED))
    clock = bus.subscribe("clock", Clock, queue_size=1)

    async def call() -> object:
        return await bus.call("obstacles/list", Empty(), ObstacleList, timeout=20.0)

    assert_unharmed(*await flood_and_measure(spawn, settings, flood, call, clock, pid))


@pytest.mark.timeout(180)
async def test_initialpose_flood(spawn: Spawn, bus: Bus, bus_settings: BusSettings) -> None:
    pose = '{"x": 0.0, "y": 0.0, "yaw": 0.0}'
    await robot_under_flood(spawn, bus, bus_settings, ("initialpose", "PoseStamped", pose))


@pytest.mark.timeout(180)
async def test_cmd_vel_flood(spawn: Spawn, bus: Bus, bus_settings: BusSettings) -> None:
    await robot_under_flood(spawn, bus, bus_settings, ("cmd_vel", "Twist", "{}"))


@pytest.mark.timeout(240)
async def test_planner_pose_flood(spawn: Spawn, bus: Bus, bus_settings: BusSettings) -> None:
    """The planner's pose subscription flooded: its is_path_valid keeps answering."""
    await start(spawn, bus, bus_settings, "robot", "--world", "small", "--speed", "1")
    pid = await start(spawn, bus, bus_settings, "planner")
    path = Path_(header=Header(frame_id="map"), poses=[
        PoseStamped.from_xy_yaw(0.0, 0.0, 0.0), PoseStamped.from_xy_yaw(1.0, 0.5, 0.0)
    ])  # fmt: skip
    request = IsPathValid.Request(path=path)

    async def call() -> object:
        return await bus.call(IsPathValid.service_name, request, IsPathValid.Response, timeout=20.0)

    pose = '{"x": 0.5, "y": 0.5, "yaw": 0.0}'
    figures = await flood_and_measure(
        spawn, bus_settings, ("pose", "PoseStamped", pose), call, None, pid
    )
    assert_unharmed(*figures)
