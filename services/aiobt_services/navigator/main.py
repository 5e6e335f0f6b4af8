"""``aiobt navigator``: Nav2's bt_navigator on Zenoh.

Serves ``navigate_to_pose`` and ``navigate_through_poses``, takes goals from
``{ns}/goal_pose``, ticks a Nav2 tree per goal with Nav2's nodes, and publishes
the tree status stream on ``{ns}/bt/tree``, ``{ns}/bt/transitions`` and
``{ns}/bt/snapshot`` (see docs/navigator.md). With ``--groot2 [PORT]`` Groot2
attaches live on 127.0.0.1:PORT to the tree of the current navigation (one
publisher for the process life, shown each new navigation's tree).
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import logging
from functools import partial
from pathlib import Path

from aiobt.core.clock import Clock
from aiobt.factory import BehaviorTreeFactory
from aiobt.loggers.groot2 import DEFAULT_PORT, Groot2Publisher, port_argument
from aiobt.nav import register_nav2_nodes
from aiobt.system.catalog import realtime_priority
from aiobt.system.heap import settle
from aiobt.system.realtime import add_realtime_argument, realtime_if_asked
from aiobt.system.service import (
    add_clock_arguments,
    make_clock,
    open_bus_unless_stopped,
    positive,
    run_service,
    stop_on_signals,
    unless_stopped,
)
from aiobt.transport import Bus, BusSettings, add_bus_arguments
from aiobt.transport.announce import announce
from aiobt_services.navigator.navigator import Navigator, NavigatorOptions
from aiobt_services.navigator.service import BusStatusSink, NavigatorService, NavRobotState
from aiobt_services.navigator.status import TreeStatusStream
from aiobt_services.navigator.trees import (
    DEFAULT_THROUGH_POSES_TREE,
    DEFAULT_TO_POSE_TREE,
    TREES_DIR,
    TreeLibrary,
    TreeLoadFailure,
)

log = logging.getLogger("aiobt_services.navigator.main")
# s; more than the nodes' own default: a busy or just-started service (numpy warming
# up, a 2-core machine) took over a second to accept its first goal
SERVER_TIMEOUT = 5.0


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    add_clock_arguments(parser)
    group = parser.add_argument_group("navigator")
    add = group.add_argument
    add(
        "--default-tree",
        default=str(DEFAULT_TO_POSE_TREE),
        metavar="FILE|ID",
        help="navigate_to_pose's tree when a goal names none (default: Nav2's "
        "navigate_to_pose_w_replanning_and_recovery)",
    )
    add(
        "--default-through-tree",
        default=str(DEFAULT_THROUGH_POSES_TREE),
        metavar="FILE|ID",
        help="navigate_through_poses's tree when a goal names none (default: "
        "navigate_through_poses_w_replanning_and_recovery)",
    )
    add(
        "--tree-dir",
        action="append",
        type=Path,
        metavar="DIR",
        help=f"register every tree of DIR by ID, repeatable (default: {TREES_DIR})",
    )
    add(
        "--bt-loop-duration",
        type=positive,
        default=0.01,
        metavar="SECONDS",
        help="tick period (default: %(default)s, as Nav2)",
    )
    add(
        "--server-timeout",
        type=positive,
        default=SERVER_TIMEOUT,
        metavar="SECONDS",
        help="how long an action leaf waits for its server to accept a goal, when the "
        "tree does not say (default: %(default)s; a server that is gone is noticed "
        "sooner, by its liveliness token)",
    )
    add(
        "--snapshot-period",
        type=positive,
        default=1.0,
        metavar="SECONDS",
        help="period of {ns}/bt/snapshot (default: %(default)s)",
    )
    add(
        "--pose-timeout",
        type=positive,
        default=2.0,
        metavar="SECONDS",
        help="wall seconds a goal waits for a first robot pose before it fails with "
        "TF_ERROR (default: %(default)s)",
    )
    add("--btlog-dir", type=Path, metavar="DIR", help="write a .btlog per navigation in DIR")
    add(
        "--mcap-dir",
        type=Path,
        metavar="DIR",
        help="record each navigation to an MCAP in DIR (the channels of `aiobt foxglove`, "
        "to open in Foxglove)",
    )
    add(
        "--groot2",
        type=port_argument,
        nargs="?",
        const=DEFAULT_PORT,
        default=None,
        metavar="PORT",
        help="let Groot2 attach live to the current navigation's tree (ZeroMQ on "
        f"127.0.0.1, PORT and PORT+1, default {DEFAULT_PORT})",
    )
    add_realtime_argument(group, realtime_priority("navigator"))


def build_navigator(args: argparse.Namespace, bus: Bus, clock: Clock) -> Navigator:
    """The navigator with Nav2's nodes on ``bus``; :class:`TreeLoadFailure` if a default
    tree or a tree directory is not there."""
    factory = BehaviorTreeFactory()
    nav = register_nav2_nodes(factory, bus, clock=clock, server_timeout=args.server_timeout)
    library = TreeLibrary(factory, args.tree_dir or [TREES_DIR])
    library.check(args.default_tree)
    library.check(args.default_through_tree)
    options = NavigatorOptions(
        default_to_pose_tree=args.default_tree,
        default_through_poses_tree=args.default_through_tree,
        bt_loop_duration=args.bt_loop_duration,
        clock_timeout=args.clock_timeout if args.sim_time else None,
        pose_timeout=args.pose_timeout,
        btlog_dir=args.btlog_dir,
        mcap_dir=args.mcap_dir,
    )
    stream = TreeStatusStream(BusStatusSink(bus))
    robot = NavRobotState(nav, clock, args.pose_timeout)
    navigator = Navigator(library, robot, clock, stream, options)
    if args.mcap_dir is not None:
        # inside, for start-up time: the foxglove SDK is imported only when a recording is asked
        from aiobt.foxglove.recording import McapRecording

        navigator.recorder = partial(McapRecording, bus)
    return navigator


async def serve(args: argparse.Namespace) -> int:
    stop = stop_on_signals()
    realtime = realtime_if_asked(args.realtime_priority)  # before the bus: its threads too
    async with open_bus_unless_stopped(BusSettings.from_args(args), stop) as bus:
        if bus is None:
            return 0
        stopper = asyncio.ensure_future(stop.wait())
        made = await unless_stopped(make_clock(bus, args.sim_time), stopper)
        if made is None:
            return 0
        try:
            navigator = build_navigator(args, bus, made[0])
        except TreeLoadFailure as exc:
            log.error("navigator: %s", exc)
            return 1
        async with contextlib.AsyncExitStack() as stack:
            if args.groot2 is not None and not await _groot2(args.groot2, navigator, stack):
                return 1
            robot = navigator.robot if isinstance(navigator.robot, NavRobotState) else None
            service = NavigatorService(bus, navigator, made[0], robot)
            service.start(args.snapshot_period)
            settle()  # start-up's objects (the trees' too) out of the collector's full passes
            announce(bus, "navigator", sim_time=args.sim_time)
            time = "sim" if args.sim_time else "wall"
            log.info("navigator up on namespace '%s' (%s time)%s", bus.namespace, time, realtime)
            await stopper
            await service.aclose()
    return 0


async def _groot2(port: int, navigator: Navigator, stack: contextlib.AsyncExitStack) -> bool:
    """Serve Groot2 on 127.0.0.1:``port`` for the process life, showing each navigation's
    tree; False (logged) if the port is taken."""
    try:
        groot2 = await stack.enter_async_context(Groot2Publisher(None, port))
    except OSError as exc:
        log.error("navigator: --groot2: %s", exc)
        return False
    navigator.tree_viewers.append(groot2.attach)
    return True


def run(args: argparse.Namespace) -> int:
    code = 0

    async def main() -> None:
        nonlocal code
        code = await serve(args)

    return run_service(main(), log, "navigator") or code
