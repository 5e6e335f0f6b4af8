"""``aiobt behaviors``: the behavior server on Zenoh.

Serves the actions ``spin``, ``backup``, ``drive_on_heading``, ``wait`` and
``assisted_teleop`` (teleop input on ``{ns}/cmd_vel_teleop``, ended early by
``{ns}/preempt_teleop``); publishes ``{ns}/cmd_vel``; reads ``{ns}/odom``,
``{ns}/pose`` and ``{ns}/scan`` (local costmap for collision checks).
"""

from __future__ import annotations

import argparse
import asyncio
import logging

from aiobt.transport import BusSettings, add_bus_arguments, open_bus
from aiobt_services._cli import positive, run_service, stop_on_signals, unless_stopped
from aiobt_services.controller.local_costmap import LocalCostmap, LocalCostmapParams
from aiobt_services.controller.robot_io import add_clock_arguments, make_clock

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
    add(
        "--pose-timeout",
        type=positive,
        default=0.5,
        help="stale odometry, s (default: %(default)s)",
    )
    add("--robot-radius", type=positive, default=0.22, help="m (default: %(default)s)")
    add(
        "--costmap-size",
        type=positive,
        default=5.0,
        help="local window side, m (default: %(default)s)",
    )


async def serve(args: argparse.Namespace) -> None:
    stop = stop_on_signals()
    async with open_bus(BusSettings.from_args(args)) as bus:
        stopper = asyncio.create_task(stop.wait())
        made = await unless_stopped(make_clock(bus, args.sim_time), stopper)
        if made is None:
            return
        clock, _ = made
        costmap = LocalCostmap(
            LocalCostmapParams(
                size=args.costmap_size,
                robot_radius=args.robot_radius,
                inflation_radius=max(0.55, args.robot_radius),
            )
        )
        options = BehaviorOptions(
            cycle_period=1.0 / args.rate,
            clock_timeout=args.clock_timeout,
            safety=Safety(
                simulate_ahead_time=args.simulate_ahead_time, pose_timeout=args.pose_timeout
            ),
        )
        BehaviorService(bus, clock, costmap, options).start()
        bus.declare_token("nodes/behaviors")
        log.info(
            "behaviors up on namespace '%s' (%s time)",
            bus.namespace,
            "sim" if args.sim_time else "wall",
        )
        await stopper


def run(args: argparse.Namespace) -> int:
    return run_service(serve(args), log, "behaviors")
