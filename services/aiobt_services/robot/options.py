"""Command-line options of the robot service and the simulation config they make."""

from __future__ import annotations

import argparse
import math

from aiobt.system.catalog import realtime_priority
from aiobt.system.realtime import add_realtime_argument
from aiobt.system.service import non_negative, positive

from .drive import DriveLimits
from .pacing import parse_speed
from .runner import MAX_LAG
from .sensors import BatteryConfig, LidarConfig, NoiseConfig
from .sim import SimConfig


def add_robot_arguments(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("robot simulation")
    add = group.add_argument
    add(
        "--world",
        default="office",
        help="shipped world (office, small) or a Nav2 map YAML path (default: %(default)s)",
    )
    add(
        "--speed",
        type=_speed,
        default=1.0,
        help="sim time runs this many times faster than wall time, or 'max': as fast as "
        "the machine allows (default: %(default)s)",
    )
    add(
        "--stepped",
        action="store_true",
        help="deterministic: sim time moves only on {ns}/sim/srv/step requests",
    )
    add("--dt", type=positive, default=0.01, help="physics step, s (default: %(default)s)")
    add("--gui", action="store_true", help="open the pybullet GUI (needs a display)")
    add(
        "--start",
        type=float,
        nargs=3,
        metavar=("X", "Y", "YAW"),
        help="start pose in map (default: the world's)",
    )
    add(
        "--initialpose",
        choices=("teleport", "localize"),
        default="teleport",
        help="{ns}/initialpose moves the robot, or only re-seats localization",
    )
    add("--max-linear", type=positive, default=1.0, help="m/s (default: %(default)s)")
    add("--max-angular", type=positive, default=2.0, help="rad/s (default: %(default)s)")
    add(
        "--cmd-timeout",
        type=positive,
        default=0.5,
        help="stop when no cmd_vel for this long, s of sim time (default: %(default)s)",
    )
    add(
        "--max-lag",
        type=positive,
        default=MAX_LAG,
        metavar="SECONDS",
        help="when the machine cannot keep up and the sim falls more than this many wall "
        "seconds behind its --speed, give that sim time up instead of catching it up in a "
        "burst of steps no client can act in (default: %(default)s)",
    )
    add(
        "--command-wait",
        type=non_negative,
        default=0.5,
        metavar="SECONDS",
        help="when a client driving the base sends its next cmd_vel late (a stalled "
        "process on a loaded machine), wait for it up to this many wall seconds instead "
        "of driving on blind; 0: never wait (default: %(default)s)",
    )
    add_realtime_argument(group, realtime_priority("robot"))
    add("--scan-hz", type=positive, default=10.0, help="lidar rate (default: %(default)s)")
    add("--odom-hz", type=positive, default=50.0, help="odom and pose rate (default: %(default)s)")
    add(
        "--clock-hz",
        type=positive,
        default=100.0,
        help="sim-time stamps on {ns}/clock per sim second, as gazebo_ros_init's "
        "publish_rate (default: %(default)s)",
    )
    add("--lidar-rays", type=int, default=360, help="beams per scan (default: %(default)s)")
    add("--lidar-range", type=positive, default=12.0, help="m (default: %(default)s)")
    add(
        "--odom-noise",
        type=float,
        default=0.05,
        help="relative std of the wheel speed error, each step (default: %(default)s)",
    )
    add(
        "--slip",
        type=float,
        default=0.02,
        help="fraction of wheel motion lost to slip: odometry overstates distance "
        "(default: %(default)s)",
    )
    add(
        "--odom-turn-scale",
        type=float,
        default=0.02,
        help="relative error of the odometry's turn rate, as from a wrong wheel base "
        "(default: %(default)s)",
    )
    add(
        "--lidar-noise",
        type=float,
        default=0.01,
        help="std of range noise, m (default: %(default)s)",
    )
    add(
        "--lidar-dropout",
        type=float,
        default=0.01,
        help="share of beams that return nothing (default: %(default)s)",
    )
    add(
        "--pose-source",
        choices=("truth", "none"),
        default="none",
        help="none: publish no pose in map, as a real base, and leave {ns}/pose, "
        "initialpose and reinitialize_global_localization to the localization service; "
        "truth: publish {ns}/pose from the simulation's truth (a perfect localization, for "
        "tests of one service) and take those two (default: %(default)s)",
    )
    add("--pose-noise", type=float, default=0.0, help="std of localization error, m")
    add("--pose-noise-yaw", type=float, default=0.0, help="std of localization error, rad")
    add("--seed", type=int, default=0, help="noise seed (default: %(default)s)")
    add("--battery", type=_fraction, default=1.0, metavar="FRACTION",
        help="the battery's charge at the start, 0..1 (default: %(default)s)")  # fmt: skip
    add("--snapshot-on-exit", metavar="PNG", default=None, help="write a top-down PNG at exit")


def sim_config(args: argparse.Namespace) -> SimConfig:
    """The :class:`SimConfig` the flags describe (``ValueError`` names a bad one)."""
    return SimConfig(
        dt=args.dt,
        limits=DriveLimits(
            max_linear=args.max_linear, max_angular=args.max_angular, cmd_timeout=args.cmd_timeout
        ),
        noise=NoiseConfig(
            odom_linear=args.odom_noise,
            odom_angular=args.odom_noise,
            slip=args.slip,
            odom_angular_scale=args.odom_turn_scale,
            pose_xy=args.pose_noise,
            pose_yaw=args.pose_noise_yaw,
            seed=args.seed,
        ),
        lidar=LidarConfig(
            rays=args.lidar_rays,
            range_max=args.lidar_range,
            angle_max=_angle_max(args.lidar_rays),
            noise=args.lidar_noise,
            dropout=args.lidar_dropout,
        ),
        battery=BatteryConfig(initial_percentage=args.battery),
        gui=args.gui,
    )


def _speed(text: str) -> float:
    try:
        return parse_speed(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _fraction(text: str) -> float:
    value = float(text)
    if not 0.0 <= value <= 1.0:
        raise argparse.ArgumentTypeError(f"must be within 0..1, got {text}")
    return value


def _angle_max(rays: int) -> float:
    return math.pi * (1.0 - 2.0 / max(1, rays))
