"""``python -m aiobt_services.velocity_smoother``: Nav2's velocity smoother on Zenoh.

Reads ``{ns}/cmd_vel_nav`` (the controller's and behaviors' command), publishes
``{ns}/cmd_vel_smoothed`` at ``--smoothing-frequency`` of robot time (``--sim-time``:
the simulation's clock at any speed-up); with ``--feedback CLOSED_LOOP`` reads
``{ns}/odom``. Parameters are Nav2's (see the README); a bad one is refused at start
with a message naming it.
"""

from __future__ import annotations

import argparse
import logging

from aiobt.core.clock import Clock
from aiobt.system.catalog import realtime_priority
from aiobt.system.realtime import add_realtime_argument
from aiobt.system.service import (
    Component,
    add_clock_arguments,
    run_service,
    serve_components,
)
from aiobt.transport import Bus, add_bus_arguments

from .params import SmootherConfigError, SmootherParams
from .service import SmootherService, Topics
from .smoother import VelocitySmoother

log = logging.getLogger("aiobt_services.velocity_smoother.main")
_DEFAULT = SmootherParams()


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    add_clock_arguments(parser)
    group = parser.add_argument_group("velocity smoother (Nav2's parameters)")
    add_realtime_argument(group, realtime_priority("velocity_smoother"))
    add = group.add_argument
    add(
        "--smoothing-frequency",
        type=float,
        default=_DEFAULT.smoothing_frequency,
        metavar="HZ",
        help="output rate (default: %(default)s)",
    )
    add(
        "--feedback",
        default=_DEFAULT.feedback,
        help="OPEN_LOOP (from the last output) or CLOSED_LOOP (from odometry)",
    )
    add(
        "--scale-velocities",
        action="store_true",
        help="scale all axes alike when one is limited (keeps the command's direction)",
    )
    for name in ("max_velocity", "min_velocity", "max_accel", "max_decel", "deadband_velocity"):
        add(
            f"--{name.replace('_', '-')}",
            type=float,
            nargs="+",
            metavar="X Y THETA",
            default=list(getattr(_DEFAULT, name)),
            help="(default: %(default)s)",
        )
    add(
        "--velocity-timeout",
        type=float,
        default=_DEFAULT.velocity_timeout,
        metavar="S",
        help="a command older than this is ramped down to zero (default: %(default)s)",
    )
    add(
        "--odom-duration",
        type=float,
        default=_DEFAULT.odom_duration,
        metavar="S",
        help="CLOSED_LOOP: odometry averaged over this long (default: %(default)s)",
    )
    add("--odom-topic", default=_DEFAULT.odom_topic, help="(default: %(default)s)")
    add("--cmd-vel-in", default=Topics().cmd_in, help="input key (default: %(default)s)")
    add("--cmd-vel-out", default=Topics().cmd_out, help="output key (default: %(default)s)")


def params_from(args: argparse.Namespace) -> SmootherParams:
    """The parameters the flags give; :class:`SmootherConfigError` names a bad one."""
    vectors = {
        name: tuple(getattr(args, name))
        for name in ("max_velocity", "min_velocity", "max_accel", "max_decel", "deadband_velocity")
    }
    return SmootherParams(
        smoothing_frequency=args.smoothing_frequency,
        feedback=args.feedback,
        scale_velocities=args.scale_velocities,
        velocity_timeout=args.velocity_timeout,
        odom_duration=args.odom_duration,
        odom_topic=args.odom_topic,
        **vectors,  # lengths checked by SmootherParams
    )


def component(args: argparse.Namespace) -> Component:
    """The smoother as its process starts it (alone, or composed: :mod:`aiobt.system.compose`);
    :class:`SmootherConfigError` names a bad parameter."""
    params = params_from(args)
    topics = Topics(args.cmd_vel_in, args.cmd_vel_out)

    def start(bus: Bus, clock: Clock) -> None:
        SmootherService(bus, clock, VelocitySmoother(params), topics).start()

    detail = f": {topics.cmd_in} -> {topics.cmd_out} at {params.smoothing_frequency:g} Hz"
    return Component("velocity_smoother", start, detail)


def run(args: argparse.Namespace) -> int:
    try:
        made = component(args)
    except SmootherConfigError as exc:
        log.error("%s", exc)
        return 2
    serving = serve_components(args, [made], log, args.realtime_priority)
    return run_service(serving, log, "velocity_smoother")
