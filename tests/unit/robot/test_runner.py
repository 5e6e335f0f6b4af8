"""The pacing runner and the control surface, without Zenoh (a list as the sink)."""

from __future__ import annotations

import asyncio
import io
import math
from collections.abc import Iterator
from pathlib import Path

import pytest
from PIL import Image

from aiobt.core.clock import ManualClock
from aiobt.msgs import Clock as ClockMsg
from aiobt.msgs import Empty, LaserScan, Msg, OccupancyGrid, PoseStamped, Twist, Vector3
from aiobt.msgs.sim import (
    BumperEvent,
    MoveObstacle,
    RemoveObstacle,
    SnapshotRequest,
    SpawnObstacle,
)
from aiobt.transport.keys import SIM_POSE
from aiobt_services.robot import convert
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.runner import JOINT_STATES, Rates, SimRunner
from aiobt_services.robot.sensors import LidarConfig, NoiseConfig
from aiobt_services.robot.service import RobotService
from aiobt_services.robot.sim import SimConfig, Simulation
from aiobt_services.robot.worlds import SMALL


class Recorder:
    def __init__(self) -> None:
        self.messages: list[tuple[str, Msg]] = []

    def publish(self, topic: str, msg: Msg) -> None:
        self.messages.append((topic, msg))

    def of(self, topic: str) -> list[Msg]:
        return [m for t, m in self.messages if t == topic]


@pytest.fixture
def sim() -> Iterator[Simulation]:
    with Simulation(load_map(SMALL)) as simulation:
        yield simulation


def test_rates_follow_sim_time(sim: Simulation) -> None:
    out = Recorder()
    runner = SimRunner(sim, out)
    for _ in range(100):  # one second of sim time
        runner.tick()
    assert len(out.of("odom")) == 50
    assert len(out.of("pose")) == 50
    assert len(out.of("scan")) == 10
    assert len(out.of("battery")) == 1
    assert len(out.of("clock")) == 100
    last_clock = out.of("clock")[-1]
    assert isinstance(last_clock, ClockMsg)
    assert last_clock.clock == pytest.approx(1.0)


def test_scan_message_marks_no_return_beyond_range_max(sim: Simulation) -> None:
    msg = convert.laser_scan(sim.scan())
    assert isinstance(msg, LaserScan)
    assert len(msg.ranges) == 360
    assert msg.ranges[180] == pytest.approx(2.35, abs=0.01)  # the angle-0 beam hits the wall
    assert all(math.isfinite(r) for r in msg.ranges)
    LaserScan.from_json(msg.to_json())  # valid on the wire


async def test_speed_5_runs_sim_five_times_faster_than_the_wall_clock(sim: Simulation) -> None:
    wall = ManualClock()
    out = Recorder()
    runner = SimRunner(sim, out, speed=5.0, wall=wall)
    stop = asyncio.Event()
    task = asyncio.create_task(runner.run(stop))
    await wall.forward(2.0, step=0.005)
    stop.set()
    await wall.forward(0.05, step=0.005)
    await asyncio.wait_for(task, 1.0)
    assert sim.time == pytest.approx(10.0, abs=0.3)
    clocks = out.of("clock")
    assert isinstance(clocks[-1], ClockMsg)
    assert clocks[-1].clock == pytest.approx(sim.time, abs=0.011)


def test_bumper_is_published(sim: Simulation) -> None:
    out = Recorder()
    runner = SimRunner(sim, out, rates=Rates(scan=1.0))
    service = RobotService(sim)
    for _ in range(500):
        service.on_cmd_vel(Twist(linear=Vector3(x=0.8)))
        runner.tick()
    bumps = out.of("bumper")
    assert len(bumps) == 1
    assert isinstance(bumps[0], BumperEvent)
    assert bumps[0].pressed
    assert bumps[0].other == "wall"


def test_map_message_matches_world(sim: Simulation) -> None:
    msg = OccupancyGrid.from_json(convert.occupancy_grid(sim.world).to_json())
    assert msg.info.width == 100
    assert msg.info.resolution == pytest.approx(0.05)
    assert msg.info.origin.position.x == pytest.approx(-2.5)
    assert (msg.array == sim.world.grid).all()


def test_service_obstacles_and_poses(sim: Simulation) -> None:
    service = RobotService(sim)
    ack = service.spawn(SpawnObstacle(shape="cylinder", x=1.0, y=0.0, radius=0.2))
    assert ack.ok
    assert ack.id == "obstacle_1"
    refused = service.spawn(SpawnObstacle(x=30.0, y=0.0))
    assert not refused.ok
    assert "outside the world" in refused.message
    assert service.move(MoveObstacle(id="obstacle_1", x=1.0, y=1.0)).ok
    assert not service.move(MoveObstacle(id="ghost", x=1.0, y=1.0)).ok
    listed = service.list_obstacles(Empty())
    assert [(o.id, o.y) for o in listed.obstacles] == [("obstacle_1", 1.0)]
    assert service.remove(RemoveObstacle(id="obstacle_1")).ok
    assert not service.reset_pose(PoseStamped.from_xy_yaw(9.0, 0.0)).ok
    assert not service.reset_pose(PoseStamped.from_xy_yaw(0.0, 0.0, frame_id="odom")).ok
    assert service.reset_pose(PoseStamped.from_xy_yaw(-1.0, -1.0, 0.3)).ok
    assert sim.true_pose.x == pytest.approx(-1.0)


def test_initialpose_modes(sim: Simulation) -> None:
    RobotService(sim, initialpose="localize").on_initialpose(PoseStamped.from_xy_yaw(1.0, 1.0))
    assert sim.true_pose.x == pytest.approx(0.0)
    assert sim.localized_pose().x == pytest.approx(1.0)
    service = RobotService(sim)
    assert service.reinitialize_localization(Empty()).ok
    service.on_initialpose(PoseStamped.from_xy_yaw(1.0, 1.0))
    assert sim.true_pose.x == pytest.approx(1.0)
    assert sim.localized_pose().x == pytest.approx(1.0)


def test_snapshot_service_writes_png(sim: Simulation, tmp_path: Path) -> None:
    target = tmp_path / "snap.png"
    reply = RobotService(sim).snapshot(SnapshotRequest(scale=1, path=str(target)))
    assert reply.ok
    assert Image.open(io.BytesIO(reply.png)).size == (100, 100)
    assert target.read_bytes() == reply.png
    bad = RobotService(sim).snapshot(SnapshotRequest(path=str(tmp_path / "no" / "x.png")))
    assert not bad.ok
    assert "cannot write" in bad.message


def test_truth_and_wheels_only_while_wanted(sim: Simulation) -> None:
    """The truth and the wheels are built only while a reader listens; the streams the
    stack reads, and the noise drawn for them, are the same either way."""
    listening: set[str] = set()
    out = Recorder()
    runner = SimRunner(sim, out, wanted=lambda topic: topic in listening)
    sim.command(0.3, 0.2)
    for _ in range(50):
        runner.tick()
    assert out.of(SIM_POSE) == []
    assert out.of(JOINT_STATES) == []
    listening.update({SIM_POSE, JOINT_STATES})
    for _ in range(50):
        runner.tick()
    assert len(out.of(SIM_POSE)) == len(out.of(JOINT_STATES)) == 25
    assert len(out.of("odom")) == 50
    assert len(out.of("scan")) == 10


def test_unread_streams_leave_the_noise_alone() -> None:
    """Skipping the unread truth changes no scan or odometry a noisy robot sends."""
    config = SimConfig(
        noise=NoiseConfig(odom_linear=0.05, odom_angular=0.05, seed=3),
        lidar=LidarConfig(noise=0.01, dropout=0.1),
    )
    sent: list[list[tuple[str, Msg]]] = []
    for wanted in (True, False):
        with Simulation(load_map(SMALL), config) as noisy:
            out = Recorder()
            listened = {SIM_POSE, JOINT_STATES} if wanted else set()
            runner = SimRunner(noisy, out, wanted=listened.__contains__)
            noisy.command(0.3, 0.2)
            for _ in range(60):
                runner.tick()
            sent.append([(t, m) for t, m in out.messages if t in ("odom", "scan")])
    assert sent[0] == sent[1]
    assert len(sent[0]) == 36


def test_the_clock_at_a_lower_rate_stamps_fewer_steps(sim: Simulation) -> None:
    out = Recorder()
    runner = SimRunner(sim, out, rates=Rates(clock=50.0))  # the robot's --clock-hz 50
    for _ in range(100):
        runner.tick()
    stamps = [m.clock for m in out.of("clock") if isinstance(m, ClockMsg)]
    assert len(stamps) == 50
    assert stamps[0] == pytest.approx(0.02)
    assert len(out.of("odom")) == 50  # the rest as before
