"""``aiobt foxglove`` as a process between a real robot and a Foxglove ws-protocol client."""

from __future__ import annotations

import asyncio
import contextlib
import socket
from collections.abc import AsyncIterator, Callable, Sequence
from pathlib import Path
from typing import Any

import pytest

from aiobt.msgs import PoseStamped, Twist, Vector3
from aiobt.testing.bus import ServiceProcess, free_port, wait_port
from aiobt.transport import Bus, BusSettings

from .wsclient import FoxgloveClient

pytestmark = [pytest.mark.integration]

Spawn = Callable[[Sequence[str]], ServiceProcess]


def start_bridge(spawn: Spawn, settings: BusSettings, *extra: str) -> ServiceProcess:
    args = ["-m", "aiobt.cli.main", "foxglove", "--connect", settings.connect[0]]
    return spawn([*args, "--namespace", settings.namespace, *extra])


async def serving_bridge(spawn: Spawn, settings: BusSettings) -> tuple[ServiceProcess, int]:
    port = free_port()
    proc = start_bridge(spawn, settings, "--port", str(port))
    if not await asyncio.to_thread(wait_port, port, 30.0) or not proc.running:
        pytest.fail(f"the bridge did not listen on {port}:\n{proc.output()}")
    return proc, port


@contextlib.asynccontextmanager
async def client(port: int) -> AsyncIterator[FoxgloveClient]:
    fox = await FoxgloveClient.connect(f"ws://127.0.0.1:{port}")
    try:
        yield fox
    finally:
        await fox.close()


async def drive(bus: Bus, stop: asyncio.Event) -> None:
    cmd = bus.publisher("cmd_vel", Twist, reliable=True)
    forward = Twist(linear=Vector3(x=0.15), angular=Vector3(z=0.3))
    while not stop.is_set():
        cmd.put(forward)
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(stop.wait(), 0.1)


@pytest.mark.e2e
@pytest.mark.timeout(150)
async def test_client_receives_scan_and_moving_pose(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    robot_args = ["-m", "aiobt_services.robot", "--world", "small", "--speed", "2"]
    robot = spawn([*robot_args, "--connect", bus_settings.connect[0],
                   "--namespace", bus_settings.namespace])  # fmt: skip
    bridge, port = await serving_bridge(spawn, bus_settings)
    if not await bus.presence(bus.keys.topic("nodes/robot")).wait(60.0):
        pytest.fail(f"robot did not come up:\n{robot.output()}")
    stop = asyncio.Event()
    driving = asyncio.create_task(drive(bus, stop))
    try:
        async with client(port) as fox:
            await fox.wait_advertised({"/scan", "/pose", "/tf", "/map"}, 20.0)
            assert fox.channels["/scan"]["schemaName"] == "foxglove.LaserScan"
            assert fox.channels["/pose"]["schemaName"] == "foxglove.PoseInFrame"
            await fox.subscribe("/scan", "/pose", "/tf")
            scans: list[Any] = []
            xs: list[float] = []
            frames: set[tuple[str, str]] = set()
            async with asyncio.timeout(60.0):
                while not (scans and len(xs) > 1 and abs(xs[-1] - xs[0]) > 0.05):
                    got = await fox.receive()
                    if got.topic == "/scan":
                        scans.append(got.message)
                    elif got.topic == "/pose":
                        xs.append(got.message.pose.position.x)
                    else:
                        frames |= {(t.parent_frame_id, t.child_frame_id)
                                   for t in got.message.transforms}  # fmt: skip
    finally:
        stop.set()
        await driving
    assert scans[0].frame_id == "base_scan"
    assert len(scans[0].ranges) == 360
    assert 0.0 < min(scans[0].ranges) < 5.0
    assert abs(xs[-1] - xs[0]) > 0.05  # the robot drove between two poses
    assert {("map", "odom"), ("odom", "base_link")} <= frames, frames
    assert bridge.running, bridge.output()


@pytest.mark.timeout(90)
async def test_goal_published_from_foxglove_reaches_goal_pose(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    goals = bus.subscribe("goal_pose", PoseStamped)
    bridge, port = await serving_bridge(spawn, bus_settings)
    goal = {"header": {"stamp": {"sec": 0, "nsec": 0}, "frame_id": "map"},
            "pose": {"position": {"x": 1.5, "y": -0.5, "z": 0.0},
                     "orientation": {"x": 0.0, "y": 0.0, "z": 0.0, "w": 1.0}}}  # fmt: skip
    async with client(port) as fox:
        await fox.wait_advertised({"/goal"}, 20.0)
        assert "clientPublish" in fox.server_info["capabilities"]
        await fox.advertise(7, "/goal_pose", "geometry_msgs/PoseStamped")
        await fox.publish(7, {"pose": "not a pose"})  # refused: logged, nothing forwarded
        received = None
        async with asyncio.timeout(30.0):
            while received is None:  # the bridge's publisher may not be routed at once
                await fox.publish(7, goal)
                with contextlib.suppress(TimeoutError):
                    received = await goals.wait_latest(1.0)
    assert received.header.frame_id == "map"
    assert (received.pose.position.x, received.pose.position.y) == (1.5, -0.5)
    refusal = "goal on /goal_pose refused: goal: PoseStamped field 'pose'"
    assert bridge.wait_for_output(refusal, 10.0), bridge.output()
    assert "W aiobt.foxglove.bridge: goal on /goal_pose refused" in bridge.output()


@pytest.mark.timeout(90)
async def test_a_taken_port_is_named_and_every_interface_is_warned_about(
    spawn: Spawn, bus_settings: BusSettings
) -> None:
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        refused = start_bridge(spawn, bus_settings, "--port", str(port))
        code = await asyncio.to_thread(refused.popen.wait, 60.0)
    assert code == 2, refused.output()
    assert "aiobt foxglove: " in refused.output()
    assert str(port) in refused.output().split("aiobt foxglove: ")[-1]
    wide = start_bridge(spawn, bus_settings, "--host", "0.0.0.0", "--port", "0")
    warned = await asyncio.to_thread(wide.wait_for_output, "bound to 0.0.0.0", 60.0)
    assert warned, wide.output()
    assert "W aiobt.foxglove.server" in wide.output()


@pytest.mark.timeout(60)
async def test_an_unwritable_recording_is_named(
    spawn: Spawn, bus_settings: BusSettings, tmp_path: Path
) -> None:
    where = tmp_path / "missing" / "run.mcap"
    bridge = start_bridge(spawn, bus_settings, "--no-server", "--mcap", str(where))
    code = await asyncio.to_thread(bridge.popen.wait, 50.0)
    assert code == 2, bridge.output()
    assert f"aiobt foxglove: --mcap {where}: cannot record: " in bridge.output()
