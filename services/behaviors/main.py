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
import math
import signal

from aiobt.transport import BusConfigError, BusSettings, BusUnavailable, add_bus_arguments, open_bus
from aiobt_services.controller.local_costmap import LocalCostmap, LocalCostmapParams
from aiobt_services.controller.robot_io import add_clock_arguments, make_clock

from .base import Safety
from .service import BehaviorOptions, BehaviorService

log = logging.getLogger("aiobt_services.behaviors.main")


def _positive(text: str) -> float:
    value = float(text)
    if not (math.isfinite(value) and value > 0.0):
        raise argparse.ArgumentTypeError(f"must be a finite number > 0, got {text}")
    return value


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    add_clock_arguments(parser)
    group = parser.add_argument_group("behaviors")
    add = group.add_argument
    add("--rate", type=_positive, default=20.0, help="cycle rate, Hz (default: %(default)s)")
    add(
        "--simulate-ahead-time",
        type=_positive,
        default=2.0,
        help="collision look-ahead, s (default: %(default)s)",
    )
    add(
        "--pose-timeout",
        type=_positive,
        default=0.5,
        help="stale odometry, s (default: %(default)s)",
    )
    add("--robot-radius", type=_positive, default=0.22, help="m (default: %(default)s)")
    add(
        "--costmap-size",
        type=_positive,
        default=5.0,
        help="local window side, m (default: %(default)s)",
    )


async def serve(args: argparse.Namespace) -> None:
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    async with open_bus(BusSettings.from_args(args)) as bus:
        clock_task = asyncio.create_task(make_clock(bus, args.sim_time))
        stopper = asyncio.create_task(stop.wait())
        await asyncio.wait({clock_task, stopper}, return_when=asyncio.FIRST_COMPLETED)
        if not clock_task.done():
            clock_task.cancel()
            return
        clock, _ = clock_task.result()
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
    try:
        asyncio.run(serve(args))
    except KeyboardInterrupt:
        pass
    except (BusUnavailable, BusConfigError) as exc:
        log.error("behaviors: %s", exc)
        return 1
    return 0
