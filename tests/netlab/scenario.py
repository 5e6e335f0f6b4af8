"""What a test runs inside a host of the lab, reporting in JSON lines on stdout.

The test process lives outside the lab's namespaces, so it cannot open a Zenoh
session there; it runs this instead, with an identity of the deployment:

    python -m tests.netlab.scenario --connect tls/198.18.0.5:7447 \\
        --config certs/laptop.json5 navigate 3.0 9.75 0.0 --timeout 90

- ``navigate X Y YAW [--or X Y YAW]``: a NavigateToPose goal (of two, the one farther
  from the robot); events ``accepted``, ``moving`` (the
  robot left its start), ``result`` (state, error code, where the robot is);
- ``map``: the latched map arrives; event ``map`` with its size (and the robot's pose
  too, with ``--pose``: the base host has what its planner needs);
- ``reach X Y``: the robot comes within ``--tolerance`` m of (X, Y); event ``reached``
  (or ``not-reached`` on timeout), with where it is;
- ``goals N``: N seeded NavigateToPose goals near the start, one after the other (each
  preempts the one before); event ``goals`` with how many were accepted, then the last
  one's ``result``;
- ``presence KEY``: until SIGTERM, ``alive`` / ``gone`` as the liveliness token KEY
  comes and goes, with ``t``, this machine's ``time.monotonic()``;
- ``rates SECONDS``: how many messages of each of the robot's streams arrived in that
  time (and the latched map's count); event ``rates``;
- ``through``, ``blocked``: tests/e2e's through-poses and blocked-corridor scenarios;
  ``goal-watch``: every action goal's statuses (:mod:`tests.netlab.scenes`);
- ``drive-watch``: on the robot's host, until SIGTERM: how long the robot drove (its
  odometry moving) after the last ``cmd_vel`` it was given; event ``drive`` with the
  longest such stretch and the longest gap between two commands (:func:`drive_figures`).
"""

from __future__ import annotations

import argparse
import asyncio
import bisect
import itertools
import json
import math
import random
import signal
import time
from collections.abc import Callable
from typing import Any

from aiobt.msgs import LaserScan, Msg, NavigateToPose, OccupancyGrid, Odometry, PoseStamped, Twist
from aiobt.testing.navwatch import RobotTrack, start_navigation
from aiobt.transport import Bus, BusSettings, add_bus_arguments, open_bus
from tests.netlab import scenes

MOVING = 0.3  # m from the start: the robot is under way
DRIVING = 0.02  # m/s in the odometry: the base is moving
ORDER_GRACE = 0.25  # s a command may come in after the first motion it caused


def say(event: str, **fields: Any) -> None:
    print(json.dumps({"event": event, **fields}), flush=True)


async def navigate(
    bus: Bus,
    x: float,
    y: float,
    yaw: float,
    timeout: float,  # noqa: ASYNC109
    other: list[float] | None,
) -> None:
    track = RobotTrack(bus)
    start = await track.wait_for(lambda s: True, 30.0)
    say("pose", x=None if start is None else start.x, y=None if start is None else start.y)
    if (
        other
        and start is not None
        and math.hypot(start.x - x, start.y - y)
        < math.hypot(start.x - other[0], start.y - other[1])
    ):
        x, y, yaw = other  # the farther of the two: a goal the robot must drive to
    say("goal", x=x, y=y)
    client = bus.action_client("navigate_to_pose", NavigateToPose)
    running = await start_navigation(client, PoseStamped.from_xy_yaw(x, y, yaw))
    say("accepted")
    if start is not None:
        moved = await track.wait_for(
            lambda s: math.hypot(s.x - start.x, s.y - start.y) > MOVING, timeout
        )
        say("moving", ok=moved is not None)
    done = await running.end(timeout)
    at = track.latest
    say(
        "result",
        state=done.state.name,
        error_code=done.result.error_code,
        error_msg=done.result.error_msg,
        x=None if at is None else at.x,
        y=None if at is None else at.y,
    )
    track.close()


async def goals(bus: Bus, count: int, seed: int, timeout: float) -> None:  # noqa: ASYNC109
    rng = random.Random(seed)
    client = bus.action_client("navigate_to_pose", NavigateToPose)
    accepted = 0
    running = None
    for _ in range(count):
        x, y = rng.uniform(2.5, 6.5), rng.uniform(9.5, 10.0)
        try:
            running = await start_navigation(client, PoseStamped.from_xy_yaw(x, y, 0.0))
            accepted += 1
        except Exception as exc:  # a rejected or unanswered goal is what is counted
            say("goal-failed", error=f"{type(exc).__name__}: {exc}")
    say("goals", sent=count, accepted=accepted)
    if running is not None:
        done = await running.end(timeout)
        say("result", state=done.state.name, error_code=done.result.error_code)


async def presence(bus: Bus, key: str, stop: asyncio.Event) -> None:
    token = bus.presence(key)
    token.add_listener(lambda alive: say("alive" if alive else "gone", t=time.monotonic()))
    say("watching", alive=token.present)
    await stop.wait()
    token.close()


async def rates(bus: Bus, seconds: float) -> None:
    counts = dict.fromkeys(("odom", "pose", "scan", "cmd_vel", "map"), 0)
    models: dict[str, type[Msg]] = {
        "odom": Odometry, "pose": PoseStamped, "scan": LaserScan, "cmd_vel": Twist,
    }  # fmt: skip

    def counter(name: str) -> Callable[[Msg], None]:
        def count(_: Msg) -> None:
            counts[name] += 1

        return count

    for name, model in models.items():
        bus.subscribe(name, model, callback=counter(name))
    bus.subscribe("map", OccupancyGrid, latched=True, callback=counter("map"))
    say("watching")
    await asyncio.sleep(seconds)
    say("rates", seconds=seconds, **counts)


async def reach(bus: Bus, x: float, y: float, tolerance: float, timeout: float) -> None:  # noqa: ASYNC109
    track = RobotTrack(bus)
    say("watching")
    there = await track.wait_for(lambda s: math.hypot(s.x - x, s.y - y) < tolerance, timeout)
    at = track.latest
    say(
        "reached" if there is not None else "not-reached",
        x=None if at is None else at.x,
        y=None if at is None else at.y,
    )
    track.close()


async def wait_map(bus: Bus, timeout: float, pose: bool) -> None:  # noqa: ASYNC109
    sub = bus.subscribe("map", OccupancyGrid, latched=True, queue_size=1)
    grid = await sub.next(timeout)
    if pose:
        poses = bus.subscribe("pose", PoseStamped, queue_size=1)
        await poses.next(timeout)
        poses.close()
    say("map", width=grid.info.width, height=grid.info.height)
    sub.close()


async def drive_watch(bus: Bus, stop: asyncio.Event) -> None:
    commands: list[float] = []
    moving: list[float] = []

    def on_odom(odom: Odometry) -> None:
        if abs(odom.twist.linear.x) > DRIVING or abs(odom.twist.angular.z) > 2 * DRIVING:
            moving.append(time.monotonic())

    bus.subscribe("cmd_vel", Twist, callback=lambda _: commands.append(time.monotonic()))
    bus.subscribe("odom", Odometry, callback=on_odom)
    say("watching")
    await stop.wait()
    say("drive", **drive_figures(commands, moving))


def drive_figures(commands: list[float], moving: list[float]) -> dict[str, float]:
    """The longest the base was seen moving since the last command before it, and the
    longest gap between commands (arrival times, s). A motion followed within
    ``ORDER_GRACE`` by a command is the start of a new stream of commands, seen out of
    order: the robot's odometry and the controller's command reach this process by
    different routes, so the first motion can come in before the command that made it."""
    stale = 0.0
    for t in moving:
        i = bisect.bisect_right(commands, t)
        if i == 0 or (i < len(commands) and commands[i] - t <= ORDER_GRACE):
            continue
        stale = max(stale, t - commands[i - 1])
    gaps = [b - a for a, b in itertools.pairwise(commands)]
    return {"stale_drive": stale, "cmd_gap": max(gaps, default=0.0), "commands": len(commands)}


async def main_async(args: argparse.Namespace) -> None:
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    async with open_bus(BusSettings.from_args(args)) as bus:
        say("connected")
        if args.what == "navigate":
            await navigate(bus, args.x, args.y, args.yaw, args.timeout, args.other)
        elif args.what == "goals":
            await goals(bus, args.count, args.seed, args.timeout)
        elif args.what == "presence":
            await presence(bus, args.key, stop)
        elif args.what == "rates":
            await rates(bus, args.seconds)
        elif args.what == "reach":
            await reach(bus, args.x, args.y, args.tolerance, args.timeout)
        elif args.what == "map":
            await wait_map(bus, args.timeout, args.pose)
        elif args.what == "goal-watch":
            await scenes.goal_watch(bus, say, stop)
        elif args.what in ("through", "blocked"):
            scene = scenes.through if args.what == "through" else scenes.blocked
            await scene(bus, say, args.timeout)
        else:
            await drive_watch(bus, stop)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_bus_arguments(parser)
    sub = parser.add_subparsers(dest="what", required=True)
    nav = sub.add_parser("navigate")
    for name in ("x", "y", "yaw"):
        nav.add_argument(name, type=float)
    nav.add_argument("--timeout", type=float, default=90.0)
    nav.add_argument(
        "--or", dest="other", type=float, nargs=3, metavar=("X", "Y", "YAW"),
        help="another goal: the one farther from the robot is taken",
    )  # fmt: skip
    many = sub.add_parser("goals")
    many.add_argument("count", type=int)
    many.add_argument("--seed", type=int, default=1)
    many.add_argument("--timeout", type=float, default=90.0)
    sub.add_parser("presence").add_argument("key")
    sub.add_parser("rates").add_argument("seconds", type=float)
    there = sub.add_parser("reach")
    there.add_argument("x", type=float)
    there.add_argument("y", type=float)
    there.add_argument("--tolerance", type=float, default=0.5)
    there.add_argument("--timeout", type=float, default=90.0)
    grid = sub.add_parser("map")
    grid.add_argument("--timeout", type=float, default=30.0)
    grid.add_argument("--pose", action="store_true")
    for scene in ("through", "blocked"):
        sub.add_parser(scene).add_argument("--timeout", type=float, default=150.0)
    sub.add_parser("drive-watch")
    sub.add_parser("goal-watch")
    asyncio.run(main_async(parser.parse_args()))


if __name__ == "__main__":
    main()
