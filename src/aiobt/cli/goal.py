"""``aiobt goal X Y [YAW]``: put a goal on ``{ns}/goal_pose`` and return.

The navigator starts a navigation (or updates the running one, as Nav2's
goal topic does). The goal is sent once a subscriber matches (a put before
that could be lost), within ``--server-timeout``; exit 2 if none does.
Follow the navigation with ``aiobt monitor``. The zenoh command line does the
same: ``zenoh put -k robot/goal_pose -v '{"x": 1.5, "y": -0.5, "yaw": 0.0}'``.
"""

from __future__ import annotations

import argparse
import asyncio
import sys

from aiobt.cli.navigate import add_client_arguments
from aiobt.embed import connect
from aiobt.transport import BusConfigError, BusSettings, BusUnavailable


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("x", type=float)
    parser.add_argument("y", type=float)
    parser.add_argument("yaw", type=float, nargs="?", default=0.0)
    add_client_arguments(parser)


async def publish(args: argparse.Namespace) -> None:
    settings = BusSettings.from_args(args)
    async with connect(settings=settings, server_timeout=args.server_timeout) as robot:
        await robot.publish_goal(args.x, args.y, args.yaw)


def run(args: argparse.Namespace) -> int:
    try:
        asyncio.run(publish(args))
    except (TimeoutError, ValueError, BusUnavailable, BusConfigError) as exc:
        print(f"aiobt goal: {exc}", file=sys.stderr)
        return 2
    print(f"goal ({args.x:g}, {args.y:g}, yaw {args.yaw:g}) sent on {args.namespace}/goal_pose")
    return 0
