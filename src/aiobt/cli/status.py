"""``aiobt status``: which services are up, in which namespaces, at which version.

    aiobt status                   # every namespace on the router
    aiobt status robot r2          # these robots only

The first line names the router asked. Liveliness tokens
``{ns}/nodes/<service>`` say who is up (``web``: a web view, with its address);
each then answers ``{ns}/srv/info/<service>`` with its version, process, host
and clock.
Exit status: 0 when at least one service is up, 1 when none is, 2 when the
router cannot be reached.
"""

from __future__ import annotations

import argparse
import asyncio
import sys
from dataclasses import dataclass

from aiobt.cli.failure import failure
from aiobt.cli.navigate import CONNECT_TIMEOUT
from aiobt.msgs import Empty
from aiobt.msgs.system import ServiceInfo
from aiobt.transport import (
    Bus,
    BusConfigError,
    BusSettings,
    BusUnavailable,
    ServiceError,
    ServiceUnavailable,
    add_bus_arguments,
    open_bus,
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    parser.add_argument(
        "namespaces", nargs="*", metavar="NAMESPACE", help="only these (default: every one)"
    )
    parser.set_defaults(connect_timeout=CONNECT_TIMEOUT)


@dataclass(slots=True, frozen=True)
class ServiceRow:
    namespace: str
    service: str
    info: ServiceInfo | None
    problem: str = ""


def parse_token(key: str) -> tuple[str, str] | None:
    """``fleet/r1/nodes/planner`` -> (``fleet/r1``, ``planner``)."""
    namespace, sep, service = key.rpartition("/nodes/")
    return (namespace, service) if sep and namespace and "/" not in service else None


async def survey(bus: Bus, namespaces: list[str]) -> list[ServiceRow]:
    """Every service up in ``namespaces`` (all of them when empty), with what it says."""
    patterns = [f"{ns}/nodes/*" for ns in namespaces] or ["**/nodes/*"]
    keys = [key for pattern in patterns for key in await bus.tokens(pattern)]
    found = [t for t in map(parse_token, keys) if t is not None]
    return list(await asyncio.gather(*(_ask(bus, ns, name) for ns, name in found)))


async def _ask(bus: Bus, namespace: str, service: str) -> ServiceRow:
    try:
        info = await bus.call(f"info/{service}", Empty(), ServiceInfo, 2.0, namespace=namespace)
    except (ServiceUnavailable, ServiceError) as exc:
        return ServiceRow(namespace, service, None, f"up, but says nothing ({exc})")
    return ServiceRow(namespace, service, info)


@dataclass(slots=True, frozen=True)
class Survey:
    router: str  # the endpoint(s) asked and the router's Zenoh id
    rows: list[ServiceRow]


def render(rows: list[ServiceRow], router: str = "") -> str:
    lines = [f"router {router}"] if router else []
    lines.append(f"{'NAMESPACE':<14} {'SERVICE':<11} {'VERSION':<9} {'CLOCK':<5} {'PID':>7}  HOST")
    for row in rows:
        info = row.info
        if info is None:
            lines.append(f"{row.namespace:<14} {row.service:<11} {row.problem}")
            continue
        clock = "sim" if info.sim_time else "wall"
        lines.append(
            f"{row.namespace:<14} {row.service:<11} {info.version:<9} {clock:<5} "
            f"{info.pid:>7}  {info.host}" + (f"  {info.url}" if info.url else "")
        )
    return "\n".join(lines)


async def status(args: argparse.Namespace) -> Survey:
    settings = BusSettings.from_args(args)
    async with open_bus(settings) as bus:
        zids = ", ".join(bus.routers()) or "none"
        router = f"{', '.join(settings.connect) or 'found by scouting'} (Zenoh id {zids})"
        return Survey(router, await survey(bus, args.namespaces))


def run(args: argparse.Namespace) -> int:
    try:
        found = asyncio.run(status(args))
    except (BusUnavailable, BusConfigError) as exc:
        print(failure("status", exc), file=sys.stderr)
        return 2
    if not found.rows:
        print(f"router {found.router}: no aiobt service is up on it", file=sys.stderr)
        return 1
    print(render(found.rows, found.router))
    return 0
