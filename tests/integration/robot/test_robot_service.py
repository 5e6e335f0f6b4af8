"""The robot service process on a real Zenoh router (loopback), driven over the wire."""

from __future__ import annotations

import asyncio
import math
import time
from collections.abc import Callable, Sequence

import pytest

from aiobt.msgs import (
    BatteryState,
    Clock,
    LaserScan,
    OccupancyGrid,
    Odometry,
    PoseStamped,
    Twist,
    Vector3,
)
from aiobt.msgs.sim import (
    Ack,
    BumperEvent,
    RemoveObstacle,
    Snapshot,
    SnapshotRequest,
    SpawnObstacle,
    StepReply,
    StepRequest,
)
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings, ServiceError
from aiobt.transport.keys import sim_namespace

pytestmark = [pytest.mark.integration, pytest.mark.e2e]

Spawn = Callable[[Sequence[str]], ServiceProcess]
AHEAD = 180  # the beam at angle 0 of the default 360-beam lidar
INNER_EAST_WALL = 2.35  # small world: inner face of the east wall


async def start_robot(spawn: Spawn, bus: Bus, settings: BusSettings, *extra: str) -> ServiceProcess:
    # the robot's own pose in map (a perfect localization): these tests read {ns}/pose
    args = ["-m", "aiobt_services.robot", "--world", "small", "--pose-source", "truth",
            "--connect", settings.connect[0]]  # fmt: skip
    proc = spawn([*args, "--namespace", settings.namespace, *extra])
    if not await bus.presence(bus.keys.topic("nodes/robot")).wait(20.0):
        pytest.fail(f"robot did not come up:\n{proc.output()}")
    return proc


async def test_publishes_map_odom_pose_scan_battery(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    grid = bus.subscribe("map", OccupancyGrid, latched=True)
    odom, pose = bus.subscribe("odom", Odometry), bus.subscribe("pose", PoseStamped)
    scan, battery = bus.subscribe("scan", LaserScan), bus.subscribe("battery", BatteryState)
    await start_robot(spawn, bus, bus_settings, "--speed", "5")
    the_map = await grid.wait_latest(10.0)
    assert (the_map.info.width, the_map.info.height) == (100, 100)
    assert the_map.info.origin.position.x == pytest.approx(-2.5)
    assert int(the_map.array[50, 99]) == 100  # east wall, row 0 at the bottom
    assert (await odom.wait_latest(5.0)).header.frame_id == "odom"
    assert (await pose.wait_latest(5.0)).header.frame_id == "map"
    first = await scan.wait_latest(5.0)
    assert first.ranges[AHEAD] == pytest.approx(INNER_EAST_WALL, abs=0.02)
    assert 0.0 < (await battery.wait_latest(5.0)).percentage <= 1.0


async def test_speed_5_clock_runs_five_times_wall_time(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    clock = bus.subscribe("clock", Clock)
    await start_robot(spawn, bus, bus_settings, "--speed", "5")
    start_sim = (await clock.wait_latest(5.0)).clock
    start_wall = time.monotonic()
    await asyncio.sleep(2.0)
    latest = clock.latest
    assert latest is not None
    ratio = (latest.clock - start_sim) / (time.monotonic() - start_wall)
    assert 4.0 < ratio < 5.5


async def test_drive_into_wall_stops_and_bumps(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    bumps = bus.subscribe("bumper", BumperEvent)
    pose = bus.subscribe("pose", PoseStamped)
    await start_robot(spawn, bus, bus_settings, "--speed", "4")
    cmd = bus.publisher("cmd_vel", Twist)
    assert await cmd.wait_for_subscribers(5.0)
    forward = Twist(linear=Vector3(x=0.8))

    async def drive() -> BumperEvent:
        while True:
            cmd.put(forward)
            await asyncio.sleep(0.02)

    driver = asyncio.create_task(drive())
    try:
        bump = await bumps.next(timeout=10.0)
    finally:
        driver.cancel()
    assert bump.pressed
    assert bump.other == "wall"
    assert abs(bump.angle) < 0.2
    await asyncio.sleep(0.3)
    here = pose.latest
    assert here is not None
    assert here.x == pytest.approx(INNER_EAST_WALL - 0.22, abs=0.05)


async def test_obstacles_seen_by_lidar_and_bad_requests_answered(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    scan = bus.subscribe("scan", LaserScan)
    proc = await start_robot(spawn, bus, bus_settings, "--speed", "2")
    req = SpawnObstacle(id="can", shape="cylinder", x=1.0, y=0.0, radius=0.2)
    sim = sim_namespace(bus.namespace)  # the simulation's services
    assert (await bus.call("obstacles/spawn", req, Ack, timeout=5.0, namespace=sim)).ok
    deadline = time.monotonic() + 5.0
    while time.monotonic() < deadline:
        latest = await scan.next(timeout=2.0)
        if math.isclose(latest.ranges[AHEAD], 0.8, abs_tol=0.02):
            break
    else:
        pytest.fail("the lidar never saw the spawned obstacle")
    outside = await bus.call("obstacles/spawn", SpawnObstacle(x=30.0, y=0.0), Ack, namespace=sim)
    assert not outside.ok
    assert "outside the world" in outside.message
    cone = SpawnObstacle.model_construct(x=0.0, y=1.0, shape="cone")  # type: ignore[arg-type]
    with pytest.raises(ServiceError, match="shape"):
        await bus.call("obstacles/spawn", cone, Ack, namespace=sim)
    assert (await bus.call("obstacles/remove", RemoveObstacle(id="can"), Ack, namespace=sim)).ok
    snap = await bus.call("snapshot", SnapshotRequest(scale=1), Snapshot, 5.0, namespace=sim)
    assert snap.png.startswith(b"\x89PNG")
    assert proc.running


async def test_nan_command_dropped_robot_keeps_running(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    pose = bus.subscribe("pose", PoseStamped)
    proc = await start_robot(spawn, bus, bus_settings, "--speed", "4")
    key = bus.keys.topic("cmd_vel")
    await pose.wait_latest(5.0)
    for _ in range(20):
        bus.session.put(key, b'{"linear": {"x": NaN}, "angular": {"z": 0.0}}')
        await asyncio.sleep(0.02)
    await asyncio.sleep(0.3)
    here = await pose.next(timeout=2.0)
    assert math.hypot(here.x, here.y) < 1e-3
    assert proc.running
    assert "cmd_vel" in proc.output()


async def test_stepped_mode_moves_only_on_request(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    clock, pose = bus.subscribe("clock", Clock), bus.subscribe("pose", PoseStamped)
    await start_robot(spawn, bus, bus_settings, "--stepped")
    sim = sim_namespace(bus.namespace)  # the simulation's services
    reply = await bus.call("step", StepRequest(seconds=1.0), StepReply, timeout=5.0, namespace=sim)
    assert reply.time == pytest.approx(1.0)
    assert reply.steps == 100
    await asyncio.sleep(0.3)  # wall time passes, sim time does not
    latest = clock.latest
    assert latest is not None
    assert latest.clock == pytest.approx(1.0)
    cmd = bus.publisher("cmd_vel", Twist)
    assert await cmd.wait_for_subscribers(5.0)
    cmd.put(Twist(linear=Vector3(x=0.5)))
    await asyncio.sleep(0.3)
    await bus.call("step", StepRequest(seconds=1.0), StepReply, timeout=5.0, namespace=sim)
    await asyncio.sleep(0.2)
    here = pose.latest
    assert here is not None
    # one command, then the 0.5 s command timeout: ramp 0.05 + cruise 0.15 + brake 0.05 m
    assert here.x == pytest.approx(0.25, abs=0.02)
    there = PoseStamped.from_xy_yaw(-1.0, -1.0, 0.5)
    reset = await bus.call("reset_pose", there, Ack, namespace=sim)
    assert reset.ok
    refused = await bus.call("reset_pose", PoseStamped.from_xy_yaw(2.4, 0.0), Ack, namespace=sim)
    assert not refused.ok
    await bus.call("step", StepRequest(seconds=0.1), StepReply, namespace=sim)
    await asyncio.sleep(0.2)
    moved = pose.latest
    assert moved is not None
    assert (moved.x, moved.y, moved.yaw) == pytest.approx((-1.0, -1.0, 0.5), abs=1e-3)
    initial = bus.publisher("initialpose", PoseStamped)
    assert await initial.wait_for_subscribers(5.0)
    initial.put(PoseStamped.from_xy_yaw(1.0, 1.0))
    await asyncio.sleep(0.3)
    await bus.call("step", StepRequest(seconds=0.1), StepReply, namespace=sim)
    await asyncio.sleep(0.2)
    moved = pose.latest
    assert moved is not None
    assert (moved.x, moved.y) == pytest.approx((1.0, 1.0), abs=1e-3)
