"""The robot gives what hardware gives: odometry with slip and scale error, a lidar
with noise and dropouts, by default on the command line; the truth only on
``{ns}/sim/pose``, and ``{ns}/pose`` only as the localization stand-in."""

from __future__ import annotations

import argparse
import math

import numpy as np

from aiobt.geometry import Pose2D
from aiobt.msgs import Msg, PoseStamped
from aiobt.transport.keys import SIM_POSE
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.obstacles import ObstacleSpec
from aiobt_services.robot.options import add_robot_arguments, sim_config
from aiobt_services.robot.runner import SimRunner
from aiobt_services.robot.sensors import LidarConfig, lidar_ranges
from aiobt_services.robot.sim import Simulation
from aiobt_services.robot.worlds import SMALL


class Recorder:
    def __init__(self) -> None:
        self.messages: list[tuple[str, Msg]] = []

    def publish(self, topic: str, msg: Msg) -> None:
        self.messages.append((topic, msg))

    def of(self, topic: str) -> list[Msg]:
        return [m for t, m in self.messages if t == topic]


def _defaults() -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    add_robot_arguments(parser)
    return parser.parse_args([])


def test_the_command_line_defaults_give_odometry_and_lidar_error() -> None:
    cfg = sim_config(_defaults())
    assert cfg.noise.slip > 0
    assert cfg.noise.odom_angular_scale != 0
    assert cfg.noise.odom_linear > 0
    assert cfg.lidar.noise > 0
    assert cfg.lidar.dropout > 0
    assert _defaults().pose_source == "none"  # no pose in map: localization's


def test_odometry_drifts_from_the_truth_by_slip_and_turn_scale() -> None:
    cfg = sim_config(_defaults())
    with Simulation(load_map(SMALL), cfg) as sim:
        for _ in range(400):  # 4 s: forward, turning
            sim.command(0.5, 0.5)
            sim.step()
        start, odom, truth = load_map(SMALL).start, sim.odometry.pose, sim.true_pose
        travelled = math.hypot(truth.x - start[0], truth.y - start[1])
        turned = truth.yaw - start[2]
        assert travelled > 0.5
        # odometry overstates the turn by about the scale error (2 %), up to the white noise
        assert abs(odom.yaw / turned - 1.02) < 0.01


def test_against_an_obstacle_the_wheels_stall_and_the_odometry_stands_too() -> None:
    cfg = sim_config(_defaults())
    with Simulation(load_map(SMALL), cfg) as sim:
        sim.spawn(ObstacleSpec("wall", "box", Pose2D(0.8, 0.0)))  # low enough: bumped, not seen
        for _ in range(300):  # 3 s at 0.5 m/s: into the box after about 1 s
            sim.command(0.5, 0.0)
            sim.step()
        assert sim.in_contact == ["wall"]
        pushed_from = sim.odometry.pose.x
        for _ in range(300):  # 3 s more, pushing
            sim.command(0.5, 0.0)
            sim.step()
        assert sim.in_contact == ["wall"]
        # wheels spinning in place would add 1.5 m; stalled ones, what the body moved
        assert abs(sim.odometry.pose.x - pushed_from) < 0.05
        assert sim.odometry.pose.x < sim.true_pose.x + 0.1  # short of the box: slip only


def test_dropouts_remove_the_given_share_of_returns() -> None:
    cfg = LidarConfig(rays=10000, dropout=0.1, noise=0.01)
    ranges = lidar_ranges(np.full(10000, 3.0), cfg, np.random.default_rng(0))
    assert abs(np.mean(~np.isfinite(ranges)) - 0.1) < 0.01
    assert abs(np.std(ranges[np.isfinite(ranges)]) - 0.01) < 0.001


def _run(publish_pose: bool) -> tuple[Recorder, Simulation]:
    out = Recorder()
    with Simulation(load_map(SMALL)) as sim:
        runner = SimRunner(sim, out, publish_pose=publish_pose)
        for _ in range(10):
            runner.tick()
    return out, sim


def test_the_truth_goes_on_sim_pose_and_pose_only_as_the_stand_in() -> None:
    stand_in, _ = _run(publish_pose=True)
    hardware, sim = _run(publish_pose=False)
    assert len(stand_in.of("pose")) == len(stand_in.of(SIM_POSE)) == 5
    assert hardware.of("pose") == []
    assert len(hardware.of(SIM_POSE)) == 5
    truth = hardware.of(SIM_POSE)[-1]
    assert isinstance(truth, PoseStamped)
    assert truth.header.frame_id == "map"
    assert (truth.x, truth.y) == (sim.true_pose.x, sim.true_pose.y)
