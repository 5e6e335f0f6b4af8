"""``aiobt behaviors``: the behavior server on Zenoh.

Serves the actions ``spin``, ``backup``, ``drive_on_heading``, ``wait`` and
``assisted_teleop`` (teleop input on ``{ns}/cmd_vel_teleop``, ended early by
``{ns}/preempt_teleop``); publishes ``{ns}/cmd_vel``; reads ``{ns}/odom``,
``{ns}/pose`` and ``{ns}/scan`` (the local costmap for collision checks, kept in
``odom`` as Nav2's behavior server's ``local_frame``: a relocalization does not
move it).
"""

from __future__ import annotations

import argparse
import logging

from aiobt.core.clock import Clock
from aiobt.system.robot_flags import (
    add_command_argument,
    add_local_costmap_arguments,
    add_pose_timeout_argument,
    local_costmap_from,
)
from aiobt.system.service import add_clock_arguments, positive, run_service, serve_on_clock
from aiobt.transport import Bus, add_bus_arguments

from .base import Safety
from .service import BehaviorOptions, BehaviorService

log = logging.getLogger("aiobt_services.behaviors.main")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    add_clock_arguments(parser)
    group = parser.add_argument_group("behaviors")
    add = group.add_argument
    add("--rate", type=positive, default=20.0, help="cycle rate, Hz (default: %(default)s)")
    add(
        "--simulate-ahead-time",
        type=positive,
        default=2.0,
        help="collision look-ahead, s (default: %(default)s)",
    )
    add_pose_timeout_argument(group)
    add_local_costmap_arguments(group)
    add_command_argument(group)


async def serve(args: argparse.Namespace) -> None:
    def start(bus: Bus, clock: Clock) -> None:
        safety = Safety(
            simulate_ahead_time=args.simulate_ahead_time, pose_timeout=args.pose_timeout
        )
        options = BehaviorOptions(
            cycle_period=1.0 / args.rate,
            clock_timeout=args.clock_timeout,
            safety=safety,
            robot_time=args.sim_time,
            cmd_vel_topic=args.cmd_vel_topic,
        )
        BehaviorService(bus, clock, local_costmap_from(args), options).start()

    await serve_on_clock(args, "behaviors", start, logger=log)


def run(args: argparse.Namespace) -> int:
    return run_service(serve(args), log, "behaviors")
