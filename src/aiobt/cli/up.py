"""``aiobt up``: the whole system on this machine, until Ctrl-C or SIGTERM.

    aiobt up                                  # router, robot, planner, controller,
    aiobt up --config system.yaml             # behaviors, navigator; defaults below
    aiobt up --speed 5 --world small          # flags override the file
    aiobt up --foxglove --mcap run.mcap       # + Foxglove on ws://127.0.0.1:8765, recorded
    aiobt up --web-port 8000                  # the web view elsewhere (--no-web: none)

A Zenoh router, then every service as its own process with the commands
docker-compose.yml uses; output prefixed by service; a crashed service is
restarted with back-off; health from the liveliness tokens
``{ns}/nodes/<service>``. See :mod:`aiobt.system.config` for the file. The
web view (docs/web.md) runs in this process on http://127.0.0.1:8080/ unless
``--no-web``; a port it cannot listen on is reported and the system runs without it.

Exit status: 0 after a clean stop, 1 when a service cannot be kept running or
the router is not there, 2 for a bad config.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import logging
import sys
from collections.abc import AsyncIterator
from pathlib import Path

from aiobt.cli.web import add_web_arguments, web_options
from aiobt.system import ConfigError, ConsoleSink, Fatal, SystemConfig, load_config, run_system
from aiobt.system.console import wants_colour
from aiobt.system.foxglove import FoxgloveOptions, start_foxglove, stop_foxglove
from aiobt.system.supervisor import on_signals
from aiobt.transport import Bus
from aiobt.transport.announce import announce
from aiobt.web import WebOptions, serve_web

log = logging.getLogger("aiobt.cli.up")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_system_arguments(parser)
    parser.add_argument(
        "--health-timeout", type=float, default=60.0, metavar="SECONDS",
        help="report the services not up after this long (default: %(default)s)",
    )  # fmt: skip
    add_foxglove_arguments(parser)
    parser.add_argument("--no-web", action="store_true", help="no web view")
    add_web_arguments(parser, prefix="web-")


def add_system_arguments(parser: argparse.ArgumentParser) -> None:
    """``--config`` and the settings a flag may override (``up`` and ``demo``)."""
    add = parser.add_argument
    add("--config", metavar="YAML", help="system settings (see aiobt.system.config)")
    add("-n", "--namespace", help="robot namespace (default: robot)")
    add("--world", help="shipped world (office, small) or a Nav2 map YAML (default: office)")
    add("--speed", type=float, help="sim speed-up; sim time everywhere when != 1 (default: 1)")
    add("--listen", dest="router_listen", metavar="ENDPOINT", help="the router's endpoint")
    add("--colour", "--color", choices=("auto", "always", "never"), default="auto")


def add_foxglove_arguments(parser: argparse.ArgumentParser) -> None:
    """``--foxglove [PORT]``, ``--mcap FILE`` (docs/foxglove.md)."""
    add = parser.add_argument
    add(
        "--foxglove",
        nargs="?",
        type=int,
        const=8765,
        metavar="PORT",
        help="run the Foxglove bridge on ws://127.0.0.1:PORT (default PORT: %(const)s)",
    )
    add(
        "--foxglove-host",
        default="127.0.0.1",
        metavar="ADDRESS",
        help="address the Foxglove server binds (default: %(default)s)",
    )
    add("--mcap", type=Path, metavar="FILE", help="record the Foxglove channels to FILE")


def foxglove_from_args(args: argparse.Namespace) -> FoxgloveOptions:
    if args.foxglove is not None and not 0 <= args.foxglove <= 65535:
        raise ConfigError(f"--foxglove: port {args.foxglove} is not in 0..65535")
    return FoxgloveOptions(port=args.foxglove, mcap=args.mcap, host=args.foxglove_host)


def config_from_args(args: argparse.Namespace) -> SystemConfig:
    router = {"listen": args.router_listen} if args.router_listen else None
    overrides = {
        "namespace": args.namespace, "world": args.world, "speed": args.speed, "router": router
    }  # fmt: skip
    return load_config(args.config, overrides)


@contextlib.asynccontextmanager
async def web_view(
    bus: Bus | None, options: WebOptions | None, sink: ConsoleSink
) -> AsyncIterator[None]:
    """The web view on ``bus`` while the system runs; one that cannot start is reported."""
    if bus is None or options is None:
        yield
        return
    async with contextlib.AsyncExitStack() as stack:
        try:
            view = await stack.enter_async_context(serve_web(bus, options))
        except OSError as exc:
            sink.event("web", f"not started: {exc} (--web-port PORT, or --no-web)")
        else:
            sink.event("web", f"web view on {view.url}")
            announce(bus, "web", sim_time=False, url=view.url)  # aiobt status lists it
        yield


async def up(
    config: SystemConfig,
    sink: ConsoleSink,
    health_timeout: float,
    web: WebOptions | None = None,
    foxglove: FoxgloveOptions | None = None,
) -> int:
    stop = asyncio.Event()
    on_signals(stop.set)
    async with run_system(config, sink) as system, web_view(system.bus, web, sink):
        if foxglove is not None and foxglove.wanted:
            await start_foxglove(system, foxglove)
        down = await system.wait_healthy(health_timeout)
        if down:
            sink.event("up", f"not up after {health_timeout:g} s: {', '.join(down)}")
        else:
            clock = f"sim time x{config.speed:g}" if config.uses_sim_time else "wall time"
            names = ", ".join(system.services)
            sink.event("up", f"{names} up on namespace '{config.namespace}' ({clock})")
        failure = await system.stopped(stop)
        sink.event("up", "stopping" if failure is None else f"stopping: {failure}")
        if foxglove is not None and foxglove.wanted:
            await stop_foxglove(system)  # first, with time to close its recording
    if failure is not None:
        raise Fatal(failure)
    return 0


def run(args: argparse.Namespace) -> int:
    # up's own session only watches tokens: where it connects is not the user's concern
    # (each service logs where it listens), and its failures reach stderr in one line
    logging.getLogger("aiobt.transport.session").setLevel(logging.WARNING)
    # the web view's start is one line of up's own output (its warnings still reach stderr)
    logging.getLogger("aiobt.web").setLevel(logging.WARNING)
    try:
        config = config_from_args(args)
        web = None if args.no_web else web_options(args, prefix="web-")
        foxglove = foxglove_from_args(args)
    except (ConfigError, ValueError) as exc:
        print(f"aiobt up: {exc}", file=sys.stderr)
        return 2
    sink = ConsoleSink(sys.stdout, colour=wants_colour(sys.stdout, args.colour))
    try:
        return asyncio.run(up(config, sink, args.health_timeout, web, foxglove))
    except Fatal as exc:
        print(f"aiobt up: {exc}", file=sys.stderr)
        return 1
