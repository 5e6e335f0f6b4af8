"""A 10,000 messages/s flood on a topic the robot subscribes to, from another process:
the robot's memory stays flat, its sim keeps its speed-up and its services answer.

Each test measures the same robot unflooded and then flooded, in the same run, and
compares: figures are printed (``-s``) and the bounds are generous (the machine is
shared), yet far from what the unbounded code did (memory grew ~13 MiB per second
of flood, the sim ran at 0.03x and services went unanswered for seconds).
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence

import pytest

from aiobt.msgs import Clock, Empty, Header, IsPathValid, PoseStamped
from aiobt.msgs import Path as Path_
from aiobt.msgs.sim import ObstacleList
from aiobt.testing.bus import ServiceProcess
from aiobt.testing.flood import (
    FLOOD_RATE,
    FLOOD_SECONDS,
    MIB,
    Call,
    Figures,
    Flood,
)
from aiobt.testing.flood import flood_and_measure as _flood_and_measure
from aiobt.transport import Bus, BusSettings, Subscription
from aiobt.transport.keys import sim_namespace

pytestmark = [pytest.mark.integration, pytest.mark.e2e]

Spawn = Callable[[Sequence[str]], ServiceProcess]
SPEED = 4.0


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
    calm, flooded, sent = await _flood_and_measure(spawn, settings, Flood(*flood), call, clock, pid)
    topic = flood[0]
    print(f"{topic}: calm {calm}\n{topic}: flooded {flooded}, {sent} sent", file=sys.stderr)
    return calm, flooded, sent


def assert_unharmed(calm: Figures, flooded: Figures, sent: int) -> None:
    assert sent >= 0.9 * FLOOD_RATE * FLOOD_SECONDS  # the flood really was 10 k/s
    assert flooded.rss_growth < 25 * MIB, "the memory grew under the flood"
    assert flooded.speed >= 0.7 * calm.speed, "the sim slowed under the flood"
    assert flooded.reply_median < max(3 * calm.reply_median, calm.reply_median + 0.02)
    assert flooded.reply_max < 2.0  # the unbounded code: 8 s


async def robot_under_flood(
    spawn: Spawn, bus: Bus, settings: BusSettings, flood: tuple[str, str, str], *extra: str
) -> None:
    pid = await start(
        spawn, bus, settings, "robot", "--world", "small", "--speed", str(SPEED), *extra
    )
    clock = bus.subscribe("clock", Clock, queue_size=1)

    async def call() -> object:
        sim = sim_namespace(bus.namespace)  # the simulation's services
        return await bus.call("obstacles/list", Empty(), ObstacleList, timeout=20.0, namespace=sim)

    assert_unharmed(*await flood_and_measure(spawn, settings, flood, call, clock, pid))


@pytest.mark.timeout(180)
async def test_initialpose_flood(spawn: Spawn, bus: Bus, bus_settings: BusSettings) -> None:
    pose = '{"x": 0.0, "y": 0.0, "yaw": 0.0}'
    # the robot reads initialpose only as the localization's stand-in (--pose-source truth)
    flood = ("initialpose", "PoseStamped", pose)
    await robot_under_flood(spawn, bus, bus_settings, flood, "--pose-source", "truth")


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
