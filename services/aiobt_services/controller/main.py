"""``aiobt controller``: the controller service on Zenoh.

Serves the ``follow_path`` action (controller ids ``FollowPath`` = regulated
pure pursuit, ``DWB`` = sampling; goal checkers ``general_goal_checker``,
``precise_goal_checker``; progress checker ``progress_checker``) and
``{ns}/srv/local_costmap/clear_{entirely,except,around}_local_costmap``;
publishes ``{ns}/cmd_vel``, ``{ns}/tracking_feedback``, and while observed
``{ns}/local_plan`` and ``{ns}/local_costmap/costmap``; reads
``{ns}/odom``, ``{ns}/pose``, ``{ns}/scan`` and ``{ns}/speed_limit`` (Nav2's
``SpeedLimit``: every controller's top speed, as ``setSpeedLimit``).
"""

from __future__ import annotations

import argparse
import logging
from dataclasses import replace

from aiobt.core.clock import Clock
from aiobt.system.catalog import realtime_priority
from aiobt.system.realtime import add_realtime_argument
from aiobt.system.robot_flags import (
    add_command_argument,
    add_local_costmap_arguments,
    add_pose_timeout_argument,
    local_costmap_from,
)
from aiobt.system.service import (
    add_clock_arguments,
    non_negative,
    positive,
    run_service,
    serve_on_clock,
)
from aiobt.transport import Bus, add_bus_arguments

from .dwb import DWBController, DWBParams
from .rpp import RegulatedPurePursuit, RPPParams
from .service import ControllerService, ServiceOptions
from .session import ControllerConfig

log = logging.getLogger("aiobt_services.controller.main")
costmap_from = local_costmap_from  # the local costmap these options describe
ODOMETRY = "odom"  # the topic the tracker reads the odometry on (its stamps: the time)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    add_clock_arguments(parser)
    group = parser.add_argument_group("controller")
    add = group.add_argument
    add("--rate", type=positive, default=20.0, help="control rate, Hz (default: %(default)s)")
    add(
        "--max-speed",
        type=positive,
        default=0.5,
        help="top speed (RPP desired, DWB max), m/s (default: %(default)s)",
    )
    add_pose_timeout_argument(group)
    add(
        "--failure-tolerance",
        type=non_negative,
        default=0.3,
        help="no valid control: stand still this long, then PATIENCE_EXCEEDED; "
        "0: NO_VALID_CONTROL at once, s (default: %(default)s)",
    )
    add(
        "--time-allowance",
        type=non_negative,
        default=0.0,
        help="CONTROLLER_TIMED_OUT after this long, s; 0: no limit (default: %(default)s)",
    )
    add_local_costmap_arguments(group)
    add_command_argument(group)
    add(
        "--no-obstacle-layer",
        dest="obstacle_layer",
        action="store_false",
        help="the local costmap does not read the lidar (tests of the collision monitor)",
    )
    add(
        "--speed-limit-topic",
        default="speed_limit",
        help="Nav2's speed_limit_topic: SpeedLimit messages every controller obeys "
        "(default: %(default)s)",
    )
    add_realtime_argument(group, realtime_priority("controller"))


def config_from(args: argparse.Namespace) -> ControllerConfig:
    rpp = RPPParams(desired_linear_vel=args.max_speed, inscribed_radius=args.robot_radius)
    config = ControllerConfig(
        control_period=1.0 / args.rate,
        pose_timeout=args.pose_timeout,
        failure_tolerance=args.failure_tolerance,
        time_allowance=args.time_allowance,
    )
    dwb = DWBParams(max_vel_x=args.max_speed)
    config.controllers["FollowPath"] = lambda: RegulatedPurePursuit(replace(rpp))
    config.controllers["DWB"] = lambda: DWBController(replace(dwb))
    return config


async def serve(args: argparse.Namespace) -> None:
    def start(bus: Bus, clock: Clock) -> None:
        options = ServiceOptions(
            args.clock_timeout,
            robot_time=args.sim_time,
            cmd_vel_topic=args.cmd_vel_topic,
            obstacle_layer=args.obstacle_layer,
            speed_limit_topic=args.speed_limit_topic,
        )
        ControllerService(bus, clock, config_from(args), costmap_from(args), options).start()

    detail = f" at {args.rate:g} Hz"
    # on sim time, the odometry's stamps (it reads them while driving) for the time: the
    # 100 Hz clock is not received as well; its loop's absolute schedule keeps the rate
    await serve_on_clock(
        args, "controller", start, detail, log, args.realtime_priority, odometry=ODOMETRY
    )


def run(args: argparse.Namespace) -> int:
    return run_service(serve(args), log, "controller")
