"""``aiobt router``: a Zenoh router in this process, for local use and tests.

    aiobt router --listen tcp/127.0.0.1:7447
    aiobt router --config router.json5   # e.g. with auth; still loopback only
    aiobt router --listen tcp/0.0.0.0:7447 --config router.json5   # every interface
    aiobt router --listen tls/0.0.0.0:7447 --config certs/router-robot.json5 \
        --access-control deploy/access-control.json5   # mutual TLS and access control

Without --listen it listens where the config file says, else on 127.0.0.1:7447
(never on every interface unless asked). Sessions it refuses (wrong user or
password) are logged with the peer's address, rate-limited; so are TLS sessions
refused for their certificate, and what the access-control rules deny to whom.

Security (user/password, access control, TLS) is Zenoh configuration: pass a
config file, see docs/transport.md. Runs until SIGINT/SIGTERM.

``--realtime-priority [N]`` (default level 60) runs it under SCHED_FIFO, as the
services' option does (``aiobt.system.realtime``): every message between them
passes through it, so when they are raised on a loaded machine, it should be too.
"""

from __future__ import annotations

import argparse
import logging
import signal
import sys
import threading
from collections.abc import Callable, Sequence
from types import FrameType

import zenoh

from aiobt.system.realtime import (
    ROUTER_PRIORITY,
    RealtimePriorityError,
    add_realtime_argument,
    realtime_if_asked,
)
from aiobt.transport import _z, access_control, downsampling
from aiobt.transport.diagnose import clean
from aiobt.transport.refusals import watch_refusals
from aiobt.transport.settings import (
    DEFAULT_ROUTER,
    BusConfigError,
    BusSettings,
    listen_endpoints,
)

log = logging.getLogger("aiobt.cli.router")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "-l",
        "--listen",
        action="append",
        metavar="ENDPOINT",
        help=f"endpoint to listen on, repeatable (default: the config file's, else "
        f"{DEFAULT_ROUTER}: loopback only; tcp/0.0.0.0:7447 for every interface)",
    )
    parser.add_argument(
        "-e",
        "--connect",
        action="append",
        metavar="ENDPOINT",
        help="another router to connect to (a mesh of routers), repeatable",
    )
    parser.add_argument(
        "-c",
        "--config",
        metavar="FILE",
        default=None,
        help="Zenoh JSON5 config file (default: $ZENOH_CONFIG); the flags override it",
    )
    parser.add_argument(
        "--lease-ms",
        type=int,
        default=1000,
        help="link lease: how fast a hung peer is noticed (default: %(default)s ms)",
    )
    parser.add_argument(
        "--access-control",
        metavar="FILE",
        default=None,
        help="Zenoh access-control rules (a JSON5 access_control section, e.g. "
        "deploy/access-control.json5); denials are logged",
    )
    parser.add_argument(
        "--no-denial-log",
        action="store_true",
        help="do not log what access control denies (Zenoh's log of it writes a line per "
        "message routed: docs/deployment.md says what that costs)",
    )
    parser.add_argument(
        "--downsampling",
        metavar="FILE",
        default=None,
        help="Zenoh downsampling rules (a JSON5 downsampling section, e.g. "
        "deploy/downsampling.json5: the robot's streams thinned towards another host)",
    )
    add_realtime_argument(parser, ROUTER_PRIORITY)


def settings_from_args(args: argparse.Namespace) -> BusSettings:
    """Router settings; with neither ``--listen`` nor a config file's listen endpoints
    it listens on loopback (``DEFAULT_ROUTER``), never on every interface."""
    return BusSettings(
        mode="router",
        listen=tuple(args.listen or ()),
        connect=tuple(args.connect or ()),
        config_file=args.config,
        lease_ms=args.lease_ms,
    )


def run(args: argparse.Namespace) -> int:
    try:
        settings = settings_from_args(args)
        config = settings.zenoh_config()
        if args.access_control:
            access_control.insert_rules(config, args.access_control)
        if args.downsampling:
            downsampling.insert_rules(config, args.downsampling)
    except BusConfigError as exc:
        log.error("%s", exc)
        return 2
    where = ", ".join(listen_endpoints(config)) or "nowhere"
    try:  # before any thread starts (Zenoh's, the refusals' reader): all of them inherit it
        realtime = realtime_if_asked(args.realtime_priority)
    except RealtimePriorityError as exc:
        log.error("router: %s", exc)
        return 1
    denials = access_control.enabled(config) and not args.no_denial_log
    watch_refusals(log, access_control=denials)
    # the handlers before the session: it listens (and peers connect) before zenoh.open
    # returns, and a SIGTERM then must still close it and exit 0, not kill the process
    stop = threading.Event()
    previous = {sig: signal.signal(sig, _setter(stop)) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        try:
            session = zenoh.open(config)
        except zenoh.ZError as exc:
            log.error("cannot start the router (listen %s): %s", where, clean(str(exc)))
            return 1
        try:
            log.info("router %s listening on %s%s", session.zid(), where, realtime)
            while not stop.wait(0.5):
                pass
            log.info("router stopping")
        finally:
            _z.close(session)
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    return 0


def _setter(stop: threading.Event) -> Callable[[int, FrameType | None], None]:
    def handler(signum: int, frame: FrameType | None) -> None:
        stop.set()

    return handler


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="aiobt router", description=__doc__.splitlines()[0])
    add_arguments(parser)
    logging.basicConfig(
        level=logging.INFO, format="%(asctime)s %(levelname).1s %(name)s: %(message)s"
    )
    return run(parser.parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
