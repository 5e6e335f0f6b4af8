"""``aiobt web``: the robot in a browser: map, costmap, robot, scan, plans, goals, tree.

    aiobt web                          # http://127.0.0.1:8080/ for namespace robot
    aiobt web --port 8000 -n r2        # another robot
    aiobt web --host 0.0.0.0           # other machines too (logged as a warning)

A click on the map puts a goal on ``{ns}/goal_pose``. Runs until Ctrl-C
(``aiobt up`` runs the same view on --web-port; see docs/web.md). Exit status
2 when the router cannot be reached or the port cannot be listened on.
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import sys
from typing import Any

from aiobt.cli.failure import failure
from aiobt.cli.navigate import CONNECT_TIMEOUT
from aiobt.costmap.inflation import InflationParams
from aiobt.system.service import non_negative, positive
from aiobt.system.signals import stop_on_signals
from aiobt.transport import BusConfigError, BusSettings, BusUnavailable, add_bus_arguments, open_bus
from aiobt.transport.announce import announce
from aiobt.web import WebOptions, serve_web

log = logging.getLogger("aiobt.cli.web")
DEFAULT_PORT = 8080


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    parser.set_defaults(connect_timeout=CONNECT_TIMEOUT)
    add_web_arguments(parser)


def add_web_arguments(parser: argparse.ArgumentParser, prefix: str = "") -> None:
    """The view's own flags (``--host``, ``--port``...; ``prefix="web-"`` for ``aiobt up``)."""
    add = parser.add_argument
    add(
        f"--{prefix}host",
        default="127.0.0.1",
        help="address to listen on; 0.0.0.0 opens it to other machines (default: %(default)s)",
    )
    add(f"--{prefix}port", type=int, default=DEFAULT_PORT, help="HTTP port (default: %(default)s)")
    add(
        f"--{prefix}rate",
        type=positive,
        default=20.0,
        help="updates per second pushed to a browser, at most (default: %(default)s)",
    )
    add(
        f"--{prefix}robot-radius",
        type=non_negative,
        default=0.22,
        help="the robot's inscribed radius, m, as the planner's (default: %(default)s)",
    )
    add(
        f"--{prefix}inflation-radius",
        type=non_negative,
        default=0.55,
        help="the costmap's inflation radius, m, as the planner's (default: %(default)s)",
    )


def web_options(args: argparse.Namespace, prefix: str = "") -> WebOptions:
    """The :class:`WebOptions` of :func:`add_web_arguments`'s flags (ValueError if bad)."""

    def get(name: str) -> Any:
        return getattr(args, prefix.replace("-", "_") + name)

    inflation = InflationParams(
        inscribed_radius=float(get("robot_radius")),
        inflation_radius=max(float(get("inflation_radius")), float(get("robot_radius"))),
    )
    return WebOptions(
        host=str(get("host")), port=int(get("port")), rate=float(get("rate")), inflation=inflation
    )


async def serve(args: argparse.Namespace) -> int:
    options = web_options(args)
    stop = stop_on_signals()
    async with open_bus(BusSettings.from_args(args)) as bus, serve_web(bus, options) as view:
        announce(bus, "web", sim_time=False, url=view.url)  # aiobt status lists it
        await stop.wait()
    return 0


def run(args: argparse.Namespace) -> int:
    try:
        return asyncio.run(serve(args))
    except (BusUnavailable, BusConfigError, OSError, ValueError) as exc:
        print(failure("web", exc), file=sys.stderr)
        return 2
