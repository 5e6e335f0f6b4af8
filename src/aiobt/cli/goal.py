"""``aiobt goal X Y [YAW]``: put a goal on ``{ns}/goal_pose`` and return.

The navigator starts a navigation (or updates the running one, as Nav2's
goal topic does). The goal is sent once a subscriber matches (a put before
that could be lost), within ``--server-timeout``; exit 2 if none does. Then
the command waits (``--server-timeout``) for the navigator's answer: exit 0
once it drives to the goal, 1 with its reason when it refuses the goal.
Follow the navigation with ``aiobt monitor``. The zenoh command line does the
same: ``zenoh put -k robot/goal_pose -v '{"x": 1.5, "y": -0.5, "yaw": 0.0}'``.
"""

from __future__ import annotations

import argparse
import asyncio
import sys

from aiobt.cli.failure import failure
from aiobt.cli.goal_answer import GoalAnswerWatch, Verdict
from aiobt.cli.navigate import add_client_arguments
from aiobt.embed import connect
from aiobt.msgs import GoalState
from aiobt.transport import BusConfigError, BusSettings, BusUnavailable


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("x", type=float)
    parser.add_argument("y", type=float)
    parser.add_argument("yaw", type=float, nargs="?", default=0.0)
    add_client_arguments(parser)


async def publish(args: argparse.Namespace) -> Verdict | None:
    """Put the goal; the navigator's verdict on it (None: none within the timeout)."""
    settings = BusSettings.from_args(args)
    async with connect(settings=settings, server_timeout=args.server_timeout) as robot:
        watch = GoalAnswerWatch(robot.bus)
        try:
            await robot.publish_goal(args.x, args.y, args.yaw, before_put=watch.answer.expect)
            return await watch.wait(args.server_timeout)
        finally:
            watch.close()


def run(args: argparse.Namespace) -> int:
    try:
        verdict = asyncio.run(publish(args))
    except (TimeoutError, ValueError, BusUnavailable, BusConfigError) as exc:
        print(failure("goal", exc), file=sys.stderr)
        return 2
    goal = f"goal ({args.x:g}, {args.y:g}, yaw {args.yaw:g})"
    if verdict is None:
        print(f"{goal} sent on {args.namespace}/goal_pose; the navigator has not started it "
              f"within {args.server_timeout:g} s (see `aiobt monitor`)")  # fmt: skip
        return 0
    if verdict.running:
        print(f"{goal} sent: the navigator is driving to it (follow it: aiobt monitor)")
        return 0
    if verdict.state is GoalState.SUCCEEDED:
        print(f"{goal} sent: already reached")
        return 0
    print(f"aiobt goal: the navigator refused {goal}: {verdict.reason}", file=sys.stderr)
    return 1
