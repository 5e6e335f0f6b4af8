"""``python -m aiobt_services.collision_monitor``: Nav2's collision monitor on Zenoh.

Reads ``{ns}/cmd_vel_smoothed``, publishes ``{ns}/cmd_vel`` (the keys are parameters);
the polygons, sources and limits come from a Nav2 parameter file (``--params-file``,
default: ``default.yaml`` beside this module). A configuration that cannot run is
refused at start with a message naming the polygon or source and the parameter.
"""

from __future__ import annotations

import argparse
import logging
from dataclasses import replace
from pathlib import Path

import yaml

from aiobt.core.clock import Clock
from aiobt.system.catalog import realtime_priority
from aiobt.system.odometry_tap import OdometryTap
from aiobt.system.realtime import add_realtime_argument
from aiobt.system.service import (
    Component,
    add_clock_arguments,
    run_service,
    serve_components,
)
from aiobt.transport import Bus, add_bus_arguments

from .monitor import CollisionMonitor
from .params import MonitorConfigError, MonitorParams, load_params
from .service import ODOM_KEPT, MonitorService

log = logging.getLogger("aiobt_services.collision_monitor.main")
DEFAULT_PARAMS = Path(__file__).with_name("default.yaml")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    add_clock_arguments(parser)
    group = parser.add_argument_group("collision monitor")
    add_realtime_argument(group, realtime_priority("collision_monitor"))
    add = group.add_argument
    add(
        "--params-file",
        type=Path,
        default=DEFAULT_PARAMS,
        metavar="YAML",
        help="Nav2 collision_monitor parameters (default: the shipped default.yaml)",
    )
    add("--disabled", action="store_true", help="start disabled (Nav2's enabled: false)")


def params_from(args: argparse.Namespace) -> MonitorParams:
    """The parameters of ``--params-file``; :class:`MonitorConfigError` names a bad one."""
    path: Path = args.params_file
    try:
        config = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError) as exc:
        raise MonitorConfigError(f"{path}: cannot read the parameters: {exc}") from None
    try:
        params = load_params(config or {})
    except MonitorConfigError as exc:
        raise MonitorConfigError(f"{path}: {exc}") from None
    if args.disabled:
        params = replace(params, enabled=False)
    return params


def component(args: argparse.Namespace) -> Component:
    """The monitor as its process starts it (alone, or composed: :mod:`aiobt.system.compose`);
    :class:`MonitorConfigError` names a bad parameter."""
    params = params_from(args)
    tap = OdometryTap(ODOM_KEPT) if params.base_shift_correction else None

    def start(bus: Bus, clock: Clock) -> None:
        monitor = CollisionMonitor(params, robot_time=args.sim_time)
        MonitorService(bus, clock, monitor, tap if tap and tap.tapped else None).start()

    names = ", ".join(f"{z.name} ({z.action_type})" for z in params.polygons)
    detail = f": {params.cmd_vel_in_topic} -> {params.cmd_vel_out_topic}, polygons {names}"
    # on sim time, the robot's time from its odometry (read anyway): no clock as well,
    # and the odometry for base_shift_correction from the same subscription
    return Component("collision_monitor", start, detail, params.odom_topic, tap)


def run(args: argparse.Namespace) -> int:
    try:
        made = component(args)
    except MonitorConfigError as exc:
        log.error("%s", exc)
        return 2
    serving = serve_components(args, [made], log, args.realtime_priority)
    return run_service(serving, log, "collision_monitor")
