"""``aiobt foxglove``: the robot's topics in Foxglove, live and/or recorded to MCAP.

    aiobt foxglove                        # ws://127.0.0.1:8765, namespace robot
    aiobt foxglove --mcap run.mcap        # also record the same channels
    aiobt foxglove --no-server --mcap run.mcap   # record only
    aiobt foxglove --host 0.0.0.0         # reachable from other machines (warned)

Open Foxglove, "Open connection", Foxglove WebSocket, ws://127.0.0.1:8765, and
import the layout printed by ``--layout`` (docs/foxglove.md). Runs until Ctrl-C.
"""

from __future__ import annotations

import argparse
import asyncio
import sys
from pathlib import Path

from aiobt.cli.failure import failure
from aiobt.cli.navigate import CONNECT_TIMEOUT
from aiobt.foxglove import DEFAULT_PORT, LAYOUT, LOCAL_HOST, BridgeOptions, running_bridge
from aiobt.foxglove.bridge import DEFAULT_COSTMAP_PERIOD, DEFAULT_FOOTPRINT_RADIUS
from aiobt.system.signals import stop_on_signals
from aiobt.transport import BusConfigError, BusSettings, BusUnavailable, add_bus_arguments, open_bus


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    parser.set_defaults(connect_timeout=CONNECT_TIMEOUT)
    add = parser.add_argument
    add("--host", default=LOCAL_HOST, help="address the server binds (default: %(default)s)")
    add(
        "--port",
        type=_port,
        default=DEFAULT_PORT,
        help="server port, 0: any (default: %(default)s)",
    )
    add("--no-server", action="store_true", help="no WebSocket server (with --mcap: record only)")
    add(
        "--mcap",
        type=Path,
        metavar="FILE",
        help="record every channel to this MCAP file (FILE-1.mcap etc. if it exists)",
    )
    add("--overwrite", action="store_true", help="--mcap: overwrite FILE if it exists")
    add("--footprint-radius", type=float, default=DEFAULT_FOOTPRINT_RADIUS, metavar="M",
        help="robot footprint drawn on /robot (default: %(default)s)")  # fmt: skip
    add(
        "--costmap-period",
        type=float,
        default=DEFAULT_COSTMAP_PERIOD,
        metavar="SECONDS",
        help="robot-time seconds between /global_costmap updates, 0: none (default: %(default)s)",
    )
    add("--layout", action="store_true", help="print the shipped layout file's path and exit")


def _port(text: str) -> int:
    try:
        port = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"port {text!r} is not a number") from None
    if not 0 <= port <= 65535:
        raise argparse.ArgumentTypeError(f"port {port} is not in 0..65535")
    return port


def options_from_args(args: argparse.Namespace) -> BridgeOptions:
    if args.no_server and args.mcap is None:
        raise ValueError("--no-server without --mcap would bridge to nothing")
    if not args.footprint_radius > 0.0:
        raise ValueError(f"--footprint-radius must be > 0, not {args.footprint_radius}")
    if not args.costmap_period >= 0.0 or args.costmap_period == float("inf"):
        raise ValueError(f"--costmap-period must be >= 0 s, not {args.costmap_period}")
    return BridgeOptions(
        host=args.host,
        port=None if args.no_server else args.port,
        mcap=args.mcap,
        overwrite=args.overwrite,
        footprint_radius=args.footprint_radius,
        costmap_period=args.costmap_period,
    )


async def bridge(args: argparse.Namespace, options: BridgeOptions) -> int:
    stop = stop_on_signals()
    async with open_bus(BusSettings.from_args(args)) as bus, running_bridge(bus, options):
        await stop.wait()
    return 0


def run(args: argparse.Namespace) -> int:
    if args.layout:
        print(LAYOUT)
        return 0
    try:
        options = options_from_args(args)
        return asyncio.run(bridge(args, options))
    except (BusUnavailable, BusConfigError, ValueError, OSError, RuntimeError) as exc:
        print(failure("foxglove", exc), file=sys.stderr)
        return 2
