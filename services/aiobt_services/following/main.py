"""``aiobt following``: Nav2's following server on Zenoh.

Serves the action ``follow_object`` (Nav2's ``FollowObject``): follows the pose
stream of a detected object on ``{ns}/{pose_topic}`` (the goal's; a tracker's
``PoseStamped`` in the robot's frame, ``odom`` or ``map``), keeping
``desired_distance`` from it, searching when it is lost. Reads ``{ns}/odom`` and
``{ns}/pose``; publishes ``{ns}/cmd_vel`` and the filtered object pose
``{ns}/filtered_dynamic_pose``; holds ``{ns}/nodes/following``. See README.md.
"""

from __future__ import annotations

import argparse
import logging

from aiobt.core.clock import Clock
from aiobt.system.robot_flags import add_command_argument
from aiobt.system.service import add_clock_arguments, run_service, serve_on_clock
from aiobt.transport import Bus, add_bus_arguments

from .options import add_following_arguments, following_params
from .service import FollowingService

log = logging.getLogger("aiobt_services.following.main")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    add_clock_arguments(parser)
    group = parser.add_argument_group("following server", description=__doc__.split("\n\n")[1])
    add_following_arguments(group)
    add_command_argument(group)


async def serve(args: argparse.Namespace) -> None:
    params = following_params(args)  # a bad parameter stops the start, named

    def start(bus: Bus, clock: Clock) -> None:
        FollowingService(bus, clock, params, args.cmd_vel_topic).start()

    await serve_on_clock(args, "following", start, logger=log)


def run(args: argparse.Namespace) -> int:
    try:
        following_params(args)
    except ValueError as exc:
        log.error("following: %s", exc)
        return 2
    return run_service(serve(args), log, "following")
