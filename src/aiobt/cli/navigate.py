"""``aiobt navigate``: send a navigation goal to the navigator and follow it live.

    aiobt navigate 1.5 -0.5 [YAW]                  # navigate_to_pose
    aiobt navigate --through 1,0 2,1.5 3,0,1.57    # navigate_through_poses (X,Y[,YAW])

Feedback (distance remaining, time, recoveries) is shown while the robot
drives. Exit status: 0 when the goal SUCCEEDED, 1 when it was ABORTED or
CANCELED (Nav2's error code and message are printed), 2 for bad input or no
navigator within ``--server-timeout``. Ctrl-C cancels the goal. A service that
goes away meanwhile (killed, restarted by ``aiobt up``) and comes back is
shown on a line of its own.
"""

from __future__ import annotations

import argparse
import asyncio
import re
import sys

from aiobt.cli.failure import failure
from aiobt.cli.feedback_line import FeedbackLine
from aiobt.cli.service_watch import watch_services
from aiobt.embed import NavigationOutcome, RobotClient, connect
from aiobt.transport import (
    BusConfigError,
    BusSettings,
    BusUnavailable,
    GoalLost,
    GoalRejected,
    ServerUnavailable,
    add_bus_arguments,
)

NEGATIVE_POSE = re.compile(r"^-\d*\.?\d+(,-?\d*\.?\d+){0,2}$")
CONNECT_TIMEOUT = 5.0  # s: a command line tool reports a missing router instead of waiting


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("pose", nargs="*", type=float, metavar="X Y [YAW]", help="the goal")
    parser.add_argument(
        "--through", nargs="+", type=pose_text, metavar="X,Y[,YAW]",
        help="navigate through these poses, in order",
    )  # fmt: skip
    parser.add_argument("--tree", default="", metavar="FILE|ID", help="the navigator's tree")
    # "-1.5,1.9" is a pose, not a flag: argparse (3.11) takes only "-1.5" for a number
    parser._negative_number_matcher = NEGATIVE_POSE
    add_client_arguments(parser)


def add_client_arguments(parser: argparse.ArgumentParser) -> None:
    """The bus flags and ``--server-timeout`` (``navigate``, ``goal``)."""
    add_bus_arguments(parser)
    parser.set_defaults(connect_timeout=CONNECT_TIMEOUT)
    parser.add_argument(
        "--server-timeout", type=float, default=10.0, metavar="SECONDS",
        help="wait this long for the navigator (default: %(default)s)",
    )  # fmt: skip


def pose_text(text: str) -> tuple[float, ...]:
    """argparse type: ``X,Y`` or ``X,Y,YAW``."""
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) not in (2, 3):
        raise argparse.ArgumentTypeError(f"expected X,Y or X,Y,YAW, got {text!r}")
    return values


async def navigate(args: argparse.Namespace, show: FeedbackLine) -> NavigationOutcome:
    settings = BusSettings.from_args(args)
    async with connect(settings=settings, server_timeout=args.server_timeout) as robot:
        news = watch_services(robot.bus, show.note)
        try:
            return await _send(robot, args, show)
        finally:
            show.end()
            if news.gone:  # went away during the navigation and not back by its end
                print(f"{', '.join(sorted(news.gone))} not back yet", file=show.out)


async def _send(
    robot: RobotClient, args: argparse.Namespace, show: FeedbackLine
) -> NavigationOutcome:
    if args.through:
        return await robot.navigate_through(args.through, behavior_tree=args.tree, on_feedback=show)
    x, y, *yaw = args.pose
    return await robot.navigate_to(x, y, *yaw, behavior_tree=args.tree, on_feedback=show)


def run(args: argparse.Namespace) -> int:
    if bool(args.through) == bool(args.pose) or (args.pose and len(args.pose) not in (2, 3)):
        print("aiobt navigate: give X Y [YAW], or --through X,Y[,YAW] ...", file=sys.stderr)
        return 2
    show = FeedbackLine(sys.stdout, args.through or ())
    try:
        outcome = asyncio.run(navigate(args, show))
    except KeyboardInterrupt:
        print("aiobt navigate: interrupted, goal canceled", file=sys.stderr)
        return 130
    except (ServerUnavailable, GoalRejected, GoalLost, BusUnavailable, BusConfigError) as exc:
        print(failure("navigate", exc), file=sys.stderr)
        return 2
    except ValueError as exc:
        print(f"aiobt navigate: {exc}", file=sys.stderr)
        return 2
    if outcome.succeeded:
        x, y = (args.through[-1] if args.through else args.pose)[:2]
        off = show.distance_to(x, y)
        print("goal reached" + ("" if off is None else f", {off:.2f} m from the goal pose"))
        return 0
    print(f"navigation {outcome.state.name}: error {outcome.error_code} {outcome.error_msg}")
    return 1
