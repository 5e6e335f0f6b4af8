"""The stepped simulation on the small shipped world (a 5 x 5 m room, robot at 0,0)."""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest
from PIL import Image

from aiobt.geometry import Pose2D
from aiobt_services.robot.drive import DriveLimits
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.obstacles import Motion, ObstacleError, ObstacleSpec
from aiobt_services.robot.sensors import BatteryConfig, LidarConfig, NoiseConfig
from aiobt_services.robot.sim import PoseError, SimConfig, Simulation
from aiobt_services.robot.snapshot import render_png
from aiobt_services.robot.worlds import SMALL

INNER_EAST_WALL = 2.5 - 0.15


@pytest.fixture
def sim() -> Iterator[Simulation]:
    with Simulation(load_map(SMALL)) as simulation:
        yield simulation


def drive(sim: Simulation, linear: float, angular: float, seconds: float) -> list[object]:
    """Send the command every step (as a controller would) for ``seconds``."""
    events: list[object] = []
    for _ in range(round(seconds / sim.config.dt)):
        sim.command(linear, angular)
        events += sim.step()
    return events


def test_forward_command_moves_expected_distance(sim: Simulation) -> None:
    drive(sim, 0.5, 0.0, 2.0)
    drive(sim, 0.0, 0.0, 1.0)
    pose = sim.true_pose
    # accel ramp and decel ramp cancel: 0.5 m/s * 2 s
    assert pose.x == pytest.approx(1.0, abs=0.03)
    assert pose.y == pytest.approx(0.0, abs=0.01)
    assert sim.odometry.pose.x == pytest.approx(pose.x, abs=0.03)
    assert sim.odometry.linear == 0.0


def test_turn_command_turns(sim: Simulation) -> None:
    drive(sim, 0.0, 1.0, 1.5)
    drive(sim, 0.0, 0.0, 1.0)
    assert sim.true_pose.yaw == pytest.approx(1.5, abs=0.05)
    assert math.hypot(sim.true_pose.x, sim.true_pose.y) < 0.01


def test_stop_command_stops_and_silence_times_out(sim: Simulation) -> None:
    drive(sim, 0.8, 0.0, 0.5)
    drive(sim, 0.0, 0.0, 0.5)
    here = sim.true_pose
    sim.run_for(1.0)
    assert sim.true_pose.distance_to(here) < 1e-3
    sim.command(0.5, 0.0)  # one command only: the base stops after cmd_timeout
    sim.run_for(2.0)
    travelled = sim.true_pose.distance_to(here)
    assert 0.1 < travelled < 0.35


def test_wall_stops_robot_and_fires_bumper(sim: Simulation) -> None:
    events = drive(sim, 0.8, 0.0, 5.0)
    radius = sim.config.robot.radius
    assert sim.true_pose.x == pytest.approx(INNER_EAST_WALL - radius, abs=0.03)
    ahead = int(np.argmin(np.abs(sim.config.lidar.angles())))
    assert sim.scan().ranges[ahead] == pytest.approx(radius, abs=0.03)  # flush: still a return
    pressed = [e for e in events if e.pressed and e.other == "wall"]  # type: ignore[attr-defined]
    assert len(pressed) == 1
    assert abs(pressed[0].angle) < 0.1  # type: ignore[attr-defined]
    assert sim.in_contact == ["wall"]
    # the motors stalled against the wall: odometry stands where the body stands
    assert sim.odometry.pose.x == pytest.approx(sim.true_pose.x, abs=0.05)
    events = drive(sim, -0.5, 0.0, 1.0)
    assert [e.pressed for e in events] == [False]  # type: ignore[attr-defined]


def test_nonfinite_commands_are_dropped_and_excess_clamped(sim: Simulation) -> None:
    assert not sim.command(math.nan, 0.0).accepted
    sim.run_for(0.5)
    assert sim.true_pose.distance_to(Pose2D()) < 1e-6
    verdict = sim.command(50.0, 0.0)
    assert verdict.clamped
    assert verdict.linear == sim.config.limits.max_linear


def test_lidar_sees_wall_at_right_range_and_spawned_obstacle(sim: Simulation) -> None:
    scan = sim.scan()
    angles = scan.config.angles()
    ahead = int(np.argmin(np.abs(angles)))
    behind = int(np.argmin(np.abs(np.abs(angles) - math.pi)))
    assert scan.ranges[ahead] == pytest.approx(INNER_EAST_WALL, abs=0.01)
    assert scan.ranges[behind] == pytest.approx(INNER_EAST_WALL, abs=0.03)
    sim.spawn(ObstacleSpec("can", "cylinder", Pose2D(1.0, 0.0), radius=0.2))
    assert sim.scan().ranges[ahead] == pytest.approx(0.8, abs=0.01)
    sim.remove("can")
    assert sim.scan().ranges[ahead] == pytest.approx(INNER_EAST_WALL, abs=0.01)


def test_lidar_no_return_is_out_of_range() -> None:
    cfg = SimConfig(lidar=LidarConfig(range_max=1.0))
    with Simulation(load_map(SMALL), cfg) as short_sim:
        assert np.all(np.isinf(short_sim.scan().ranges))


def test_obstacle_requests_are_checked(sim: Simulation) -> None:
    with pytest.raises(ObstacleError, match="outside the world"):
        sim.spawn(ObstacleSpec("far", "box", Pose2D(10.0, 0.0)))
    with pytest.raises(ObstacleError, match="overlap the robot"):
        sim.spawn(ObstacleSpec("on", "box", Pose2D(0.2, 0.0)))
    # a long thin box whose bounding circle reaches the robot, its side 0.3 m clear: allowed
    sim.spawn(ObstacleSpec("thin", "box", Pose2D(0.0, 0.6), size_x=1.2, size_y=0.1))
    with pytest.raises(ObstacleError, match="overlap the robot"):  # its side touching: refused
        sim.spawn(ObstacleSpec("near", "box", Pose2D(0.0, -0.2), size_x=1.2, size_y=0.1))
    sim.remove("thin")
    sim.spawn(ObstacleSpec("b", "box", Pose2D(1.0, 1.0)))
    with pytest.raises(ObstacleError, match="already exists"):
        sim.spawn(ObstacleSpec("b", "box", Pose2D(1.0, -1.0)))
    with pytest.raises(ObstacleError, match=r"no obstacle 'x' \(known: b\)"):
        sim.remove("x")
    sim.move("b", Pose2D(-1.0, 1.0, 0.5))
    assert sim.obstacle_pose("b") == Pose2D(-1.0, 1.0, 0.5)


def test_dynamic_obstacle_moves_and_blocks(sim: Simulation) -> None:
    sim.spawn(
        ObstacleSpec(
            "walker", "cylinder", Pose2D(1.0, 1.5), radius=0.2, motion=Motion(1.0, -1.5, 1.0)
        )
    )
    sim.run_for(1.5)
    assert sim.obstacle_pose("walker").y == pytest.approx(0.0, abs=1e-6)
    ahead = int(np.argmin(np.abs(sim.config.lidar.angles())))
    assert sim.scan().ranges[ahead] == pytest.approx(0.8, abs=0.02)


def test_teleport_and_localization(sim: Simulation) -> None:
    with pytest.raises(PoseError, match="overlaps a wall"):
        sim.teleport(Pose2D(-1.5, 1.0))
    with pytest.raises(PoseError, match="outside the world"):
        sim.teleport(Pose2D(9.0, 0.0))
    sim.teleport(Pose2D(-1.0, 0.5, math.pi))
    sim.step()
    assert sim.true_pose.distance_to(Pose2D(-1.0, 0.5)) < 1e-3
    sim.set_localization(Pose2D(0.0, 0.0, 0.0))
    est = sim.localized_pose()
    assert (est.x, est.y, est.yaw) == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
    sim.reinitialize_localization()
    assert sim.localized_pose().distance_to(sim.true_pose) < 1e-9


def test_same_seed_same_noisy_run() -> None:
    cfg = SimConfig(noise=NoiseConfig(odom_linear=0.05, pose_xy=0.02, seed=3))
    poses = []
    for _ in range(2):
        with Simulation(load_map(SMALL), cfg) as run:
            drive(run, 0.5, 0.3, 1.0)
            poses.append((run.odometry.pose, run.localized_pose(), run.true_pose))
    assert poses[0] == poses[1]


def test_snapshot_png(sim: Simulation, tmp_path: object) -> None:
    import io

    sim.spawn(ObstacleSpec("b", "box", Pose2D(1.0, 1.0)))
    image = Image.open(io.BytesIO(render_png(sim, scale=2)))
    assert image.size == (200, 200)
    # the robot is drawn in blue at the centre
    r, _g, b = image.getpixel((100, 95))  # type: ignore[misc]
    assert b > 150
    assert r < 100


def test_battery_drains_driving_charges_on_dock_and_empty_stops() -> None:
    cfg = SimConfig(battery=BatteryConfig(capacity_wh=0.05, initial_percentage=0.5))
    with Simulation(load_map(SMALL), cfg) as run:
        level = run.battery.percentage
        drive(run, 0.5, 0.0, 1.0)
        assert run.battery.percentage < level
        dock = run.world.dock
        assert dock is not None
        run.teleport(Pose2D(dock.x + 0.05, dock.y, dock.yaw))  # 5 cm short of the contacts
        run.run_for(1.0)
        assert not run.battery.charging
        run.teleport(Pose2D(dock.x, dock.y, dock.yaw))
        level = run.battery.percentage
        run.run_for(1.0)
        assert run.battery.charging
        assert run.battery.percentage > level
        run.teleport(Pose2D(0.0, 0.0))
        drive(run, 1.0, 0.0, 20.0)  # 0.05 Wh lasts seconds at full speed
        assert run.battery.depleted
        here = run.true_pose
        drive(run, 1.0, 0.0, 1.0)
        assert run.true_pose.distance_to(here) < 1e-6


def test_fast_base_with_long_steps_does_not_tunnel_through_walls() -> None:
    limits = DriveLimits(max_linear=10.0, max_linear_accel=100.0)
    with Simulation(load_map(SMALL), SimConfig(dt=0.05, limits=limits)) as fast:
        drive(fast, 10.0, 0.0, 2.0)
        assert fast.true_pose.x < INNER_EAST_WALL


def test_slip_makes_the_body_lag_the_wheel_odometry() -> None:
    with Simulation(load_map(SMALL), SimConfig(noise=NoiseConfig(slip=0.2))) as slippy:
        drive(slippy, 0.5, 0.0, 2.0)
        drive(slippy, 0.0, 0.0, 1.0)
        wheels, body = slippy.odometry.pose.x, slippy.true_pose.x
    assert wheels == pytest.approx(1.0, abs=0.03)
    assert body == pytest.approx(0.8 * wheels, abs=0.02)


def test_bumping_an_obstacle_names_it_and_move_outside_is_refused(sim: Simulation) -> None:
    sim.spawn(ObstacleSpec("crate", "box", Pose2D(1.0, 0.0), size_x=0.4, size_y=0.8))
    events = drive(sim, 0.5, 0.0, 4.0)
    pressed = [e for e in events if e.pressed]  # type: ignore[attr-defined]
    assert [e.other for e in pressed] == ["crate"]  # type: ignore[attr-defined]
    assert sim.true_pose.x == pytest.approx(0.8 - sim.config.robot.radius, abs=0.03)
    with pytest.raises(ObstacleError, match="outside the world"):
        sim.move("crate", Pose2D(2.6, 0.0))
    with pytest.raises(ObstacleError, match="overlap the robot"):
        sim.move("crate", Pose2D(sim.true_pose.x + 0.1, 0.0))
    assert sim.obstacle_pose("crate") == Pose2D(1.0, 0.0)  # a refused move changes nothing
