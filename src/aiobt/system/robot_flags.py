"""The flags the controller and the behaviors share: when a pose is stale, their local
costmap's, and the key they command the base on."""

from __future__ import annotations

import argparse

from aiobt.costmap.local import LocalCostmap, LocalCostmapParams
from aiobt.system.service import positive


def add_local_costmap_arguments(group: argparse._ArgumentGroup) -> None:
    """The local costmap's options (controller and behaviors)."""
    add = group.add_argument
    add("--robot-radius", type=positive, default=0.22, help="m (default: %(default)s)")
    add("--inflation-radius", type=positive, default=0.55, help="m (default: %(default)s)")
    add(
        "--costmap-size",
        type=positive,
        default=5.0,
        help="local window side, m (default: %(default)s)",
    )
    add(
        "--costmap-update-frequency",
        type=positive,
        default=5.0,
        metavar="HZ",
        help="local costmap updates from the lidar per robot second, as Nav2's "
        "update_frequency (default: %(default)s)",
    )


def add_command_argument(group: argparse._ArgumentGroup) -> None:
    """Where the base command goes (controller and behaviors)."""
    group.add_argument(
        "--cmd-vel-topic",
        default="cmd_vel",
        metavar="KEY",
        help="publish the base command on {ns}/KEY; cmd_vel_nav puts the velocity smoother "
        "and the collision monitor in between (default: %(default)s)",
    )


def local_costmap_from(args: argparse.Namespace) -> LocalCostmap:
    return LocalCostmap(
        LocalCostmapParams(
            size=args.costmap_size,
            robot_radius=args.robot_radius,
            inflation_radius=max(args.inflation_radius, args.robot_radius),
            update_frequency=args.costmap_update_frequency,
        )
    )


def add_pose_timeout_argument(group: argparse._ArgumentGroup) -> None:
    """``--pose-timeout``: :mod:`aiobt.robot.freshness`'s rule."""
    group.add_argument(
        "--pose-timeout",
        type=positive,
        default=0.5,
        help="a pose not renewed for this long (wall s) while the robot's own time "
        "moved on as long, or the robot sent nothing, is stale, s (default: %(default)s)",
    )
