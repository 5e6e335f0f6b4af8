"""``aiobt foxglove`` as a process between a real robot and a Foxglove ws-protocol client."""

from __future__ import annotations

import asyncio
import contextlib
import itertools
import pathlib
import socket
from collections.abc import AsyncIterator, Callable, Sequence
from typing import Any

import pytest

from aiobt.geometry import PlanarPath
from aiobt.msgs import FollowPath, Path, PoseStamped
from aiobt.testing.bus import ServiceProcess, free_port, wait_port
from aiobt.transport import Bus, BusSettings
from tests.integration.services import TRUTH

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


async def drive(bus: Bus) -> FollowPath.Result:
    """The controller follows a left curve (the robot drives, the controller publishes its
    local plan)."""
    points = [(0.0, 0.0), (0.8, 0.0), (1.2, 0.4), (1.2, 1.2)]
    planar = PlanarPath.through(points, 0.05)
    poses = [PoseStamped.from_xy_yaw(float(x), float(y), float(a))
             for (x, y), a in zip(planar.xy, planar.yaw, strict=True)]  # fmt: skip
    client = bus.action_client("follow_path", FollowPath)
    goal = await client.send_goal(FollowPath.Goal(path=Path(poses=poses)), server_timeout=30.0)
    return await goal.result(timeout=90.0)


@pytest.mark.e2e
@pytest.mark.timeout(150)
async def test_client_receives_scan_and_moving_pose(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    robot_args = ["-m", "aiobt_services.robot", "--world", "small", "--speed", "2", *TRUTH]
    common = ["--connect", bus_settings.connect[0], "--namespace", bus_settings.namespace]
    robot = spawn([*robot_args, *common])
    controller = spawn(["-m", "aiobt_services.controller", "--sim-time", *common])
    bridge, port = await serving_bridge(spawn, bus_settings)
    for name, proc in (("robot", robot), ("controller", controller)):
        if not await bus.presence(bus.keys.topic(f"nodes/{name}")).wait(60.0):
            pytest.fail(f"{name} did not come up:\n{proc.output()}")
    driving: asyncio.Task[FollowPath.Result] | None = None
    try:
        async with client(port) as fox:
            await fox.wait_advertised({"/scan", "/pose", "/tf", "/map", "/local_plan"}, 20.0)
            assert fox.channels["/scan"]["schemaName"] == "foxglove.LaserScan"
            assert fox.channels["/pose"]["schemaName"] == "foxglove.PoseInFrame"
            assert fox.channels["/local_plan"]["schemaName"] == "foxglove.PosesInFrame"
            await fox.subscribe("/scan", "/pose", "/tf", "/local_plan")
            # the bridge subscribes at start; the controller's publisher sees it matched
            driving = asyncio.create_task(drive(bus))
            scans: list[Any] = []
            xs: list[float] = []
            local_plans: list[Any] = []
            frames: set[tuple[str, str]] = set()
            async with asyncio.timeout(60.0):
                while not (
                    scans and len(xs) > 1 and abs(xs[-1] - xs[0]) > 0.05
                    and any(len(p.poses) >= 2 for p in local_plans)
                ):  # fmt: skip
                    got = await fox.receive()
                    if got.topic == "/scan":
                        scans.append(got.message)
                    elif got.topic == "/pose":
                        xs.append(got.message.pose.position.x)
                    elif got.topic == "/local_plan":
                        local_plans.append(got.message)
                    else:
                        frames |= {(t.parent_frame_id, t.child_frame_id)
                                   for t in got.message.transforms}  # fmt: skip
        assert driving is not None
        result = await driving  # the goal ends: its robot stopped, its local plan cleared
    finally:
        if driving is not None and not driving.done():
            driving.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await driving
    assert result.error_code == 0, result
    assert scans[0].frame_id == "base_scan"
    assert len(scans[0].ranges) == 360
    assert 0.0 < min(scans[0].ranges) < 5.0
    assert abs(xs[-1] - xs[0]) > 0.05  # the robot drove between two poses
    assert {("map", "odom"), ("odom", "base_link")} <= frames, frames
    plan = next(p for p in local_plans if len(p.poses) >= 2)
    assert plan.frame_id == "map"
    ahead = [q.position for q in plan.poses]
    assert max(abs(b.x - a.x) + abs(b.y - a.y) for a, b in itertools.pairwise(ahead)) < 0.5
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
    spawn: Spawn, bus_settings: BusSettings, tmp_path: pathlib.Path
) -> None:
    where = tmp_path / "missing" / "run.mcap"
    bridge = start_bridge(spawn, bus_settings, "--no-server", "--mcap", str(where))
    code = await asyncio.to_thread(bridge.popen.wait, 50.0)
    assert code == 2, bridge.output()
    assert f"aiobt foxglove: --mcap {where}: cannot record: " in bridge.output()
