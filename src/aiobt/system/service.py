"""What the service programs share: argument types, the clock flags, the ``python -m``
entry, opening the bus, the run loop.

Each service's ``main`` module keeps its own options and wiring; this module
holds the parts that are the same in all of them (see docs/architecture.md).
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import logging
import math
from collections.abc import AsyncIterator, Callable, Coroutine, Sequence
from dataclasses import dataclass
from typing import Any, TypeVar

from aiobt.core.clock import Clock, SystemClock
from aiobt.msgs import Odometry
from aiobt.system.heap import settle
from aiobt.system.odometry_tap import OdometryTap
from aiobt.system.realtime import RealtimePriorityError, realtime_if_asked
from aiobt.system.signals import stop_on_signals as stop_on_signals  # for the services
from aiobt.transport import (
    Bus,
    BusConfigError,
    BusSettings,
    BusUnavailable,
    SimClockFollower,
    open_bus,
)
from aiobt.transport.announce import announce

T = TypeVar("T")
log = logging.getLogger("aiobt.system.service")


def positive(text: str) -> float:
    """argparse type: a finite float > 0."""
    value = float(text)
    if not (math.isfinite(value) and value > 0.0):
        raise argparse.ArgumentTypeError(f"must be a finite number > 0, got {text}")
    return value


def non_negative(text: str) -> float:
    """argparse type: a finite float >= 0."""
    value = float(text)
    if not (math.isfinite(value) and value >= 0.0):
        raise argparse.ArgumentTypeError(f"must be a finite number >= 0, got {text}")
    return value


def module_main(
    prog: str,
    description: str | None,
    add_arguments: Callable[[argparse.ArgumentParser], None],
    run: Callable[[argparse.Namespace], int],
    argv: list[str] | None = None,
) -> int:
    """``python -m aiobt_services.<name>``: the service's options plus ``-v``, logging set up."""
    parser = argparse.ArgumentParser(prog=prog, description=description)
    parser.add_argument("-v", "--verbose", action="count", default=0, help="more logging")
    add_arguments(parser)
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=logging.DEBUG if args.verbose > 1 else logging.INFO,
        format="%(asctime)s %(levelname).1s %(name)s: %(message)s",
    )
    return run(args)


async def unless_stopped(work: Coroutine[Any, Any, T], stopper: asyncio.Task[Any]) -> T | None:
    """``work``'s result, or None (``work`` cancelled) if ``stopper`` finishes first."""
    task = asyncio.create_task(work)
    await asyncio.wait({task, stopper}, return_when=asyncio.FIRST_COMPLETED)
    if not task.done():
        task.cancel()
        return None
    return task.result()


@contextlib.asynccontextmanager
async def open_bus_unless_stopped(
    settings: BusSettings, stop: asyncio.Event
) -> AsyncIterator[Bus | None]:
    """The service's bus, or None if ``stop`` (SIGINT/SIGTERM) comes while it is still
    opening: a service waiting for its router stops when asked to."""
    async with contextlib.AsyncExitStack() as stack:
        stopper = asyncio.ensure_future(stop.wait())
        try:
            bus = await unless_stopped(stack.enter_async_context(open_bus(settings)), stopper)
        finally:
            stopper.cancel()
        yield bus


def run_service(main: Coroutine[Any, Any, None], log: logging.Logger, name: str) -> int:
    """Run ``main`` to its end: 0, or 1 (logged on ``log``) when the bus cannot be opened
    or the real-time priority asked for cannot be had."""
    try:
        asyncio.run(main)
    except KeyboardInterrupt:
        pass
    except (BusUnavailable, BusConfigError, RealtimePriorityError) as exc:
        log.error("%s: %s", name, exc)
        return 1
    return 0


def add_clock_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--sim-time",
        action="store_true",
        help="run on the simulation's time from {ns}/clock instead of the wall clock",
    )
    parser.add_argument(
        "--clock-timeout",
        type=float,
        default=2.0,
        metavar="SECONDS",
        help="wall seconds without clock progress before a goal fails (default: %(default)s)",
    )


@dataclass(frozen=True, slots=True)
class Component:
    """One service as its process starts it: ``start(bus, clock)`` wires it, then the
    token ``nodes/{name}`` says it is up. Several run in one process on one bus
    (:mod:`aiobt.system.compose`, Nav2's composition); ``odometry``: its clock on sim
    time may come from that topic's stamps (see :func:`make_clock`, :func:`time_sources`);
    ``odometry_tap``: the messages of those stamps handed on, when they are its clock's
    (:mod:`aiobt.system.odometry_tap`)."""

    name: str
    start: Callable[[Bus, Clock], None]
    detail: str = ""
    odometry: str | None = None
    odometry_tap: OdometryTap | None = None


async def serve_on_clock(
    args: argparse.Namespace,
    name: str,
    start: Callable[[Bus, Clock], None],
    detail: str = "",
    logger: logging.Logger = log,
    realtime: int | None = None,
    odometry: str | None = None,
) -> None:
    """:func:`serve_components` for one."""
    await serve_components(args, [Component(name, start, detail, odometry)], logger, realtime)


async def serve_components(
    args: argparse.Namespace,
    components: Sequence[Component],
    logger: logging.Logger = log,
    realtime: int | None = None,
) -> None:
    """Raise the process to ``realtime`` priority if given (before the bus: Zenoh's
    threads too, see :mod:`aiobt.system.realtime`), open one bus, wait for each
    component's clock (``--sim-time``; one per time source, shared), start each and
    announce ``nodes/{name}`` in order, then run until SIGINT/SIGTERM; "``name`` up"
    goes to ``logger``."""
    extra = realtime_if_asked(realtime)
    stop = stop_on_signals()
    async with open_bus_unless_stopped(BusSettings.from_args(args), stop) as bus:
        if bus is None:
            return
        stopper = asyncio.create_task(stop.wait())
        sources = time_sources(components)
        clocks: dict[str | None, Clock] = {}
        for source in dict.fromkeys(sources.values()):
            taps = [c.odometry_tap for c in components if sources[c.name] == source]
            taken = make_clock(bus, args.sim_time, source, [t for t in taps if t is not None])
            made = await unless_stopped(taken, stopper)
            if made is None:
                return
            clocks[source] = made[0]
        for component in components:
            component.start(bus, clocks[sources[component.name]])
        settle()  # start-up's objects out of the collector's full passes (a cycle's tail)
        time = "sim" if args.sim_time else "wall"
        for component in components:
            announce(bus, component.name, sim_time=args.sim_time)
            logger.info(
                "%s up on namespace '%s'%s%s (%s time)",
                component.name, bus.namespace, component.detail, extra, time,
            )  # fmt: skip
        await stopper


def time_sources(components: Sequence[Component]) -> dict[str, str | None]:
    """Each component's time on sim time: the clock's (None) or the stamps of its
    ``odometry``. One that may take its time from odometry takes the clock's where
    another component of the process follows the clock anyway: the same time, at 100
    stamps a second, for no second subscription (bench/history/safety.md)."""
    on_clock = any(component.odometry is None for component in components)
    return {c.name: None if on_clock else c.odometry for c in components}


async def open_clock(bus: Bus, sim_time: bool, stop: asyncio.Event) -> Clock | None:
    """The wall clock, or (``sim_time``) the simulation's once it has started; None if
    ``stop`` (SIGINT/SIGTERM) comes first. For a service that starts itself without
    :func:`serve_on_clock`."""
    if not sim_time:
        return SystemClock()
    stopper = asyncio.create_task(stop.wait())
    try:
        made = await unless_stopped(make_clock(bus, sim_time=True), stopper)
    finally:
        stopper.cancel()
    return None if made is None else made[0]


async def make_clock(
    bus: Bus, sim_time: bool, odometry: str | None = None, taps: Sequence[OdometryTap] = ()
) -> tuple[Clock, SimClockFollower | None]:
    """The wall clock, or a clock following ``{ns}/clock`` (waits for the first stamp),
    listened to only while held: by a sleeper, a goal, a clearing call (see
    :mod:`aiobt.transport.simtime`); an idle service receives no clock.

    ``odometry``: the robot's time from the stamps of its odometry on that topic,
    listened to on demand as well, for a service that reads the odometry anyway (the
    collision monitor, which holds its clock always; the controller, while a goal
    runs): the same time as the clock's, at 50 stamps a second instead of 100
    (bench/history/safety.md, bench/history/system.md), so a sleeper wakes on a 20 ms
    grid at 1x (a loop on an absolute schedule keeps its rate: the controller's 50 ms
    cycles come 40 and 60 ms apart). The velocity smoother, whose timer ramps, keeps
    the clock. Each of ``taps`` then gets every odometry message followed (``tapped``
    set): a service keeping the odometry needs no second subscription (the tap is fed
    while the clock is held: the monitor holds it always)."""
    if not sim_time:
        return SystemClock(), None
    if odometry is None:
        follower = SimClockFollower(bus, on_demand=True)
    else:
        for tap in taps:
            tap.tapped = True
        stamp_of = _tapped_stamp(taps) if taps else _odometry_stamp
        follower = SimClockFollower(
            bus, topic=odometry, on_demand=True, model=Odometry, stamp_of=stamp_of
        )
    topic = odometry or "clock"
    while True:
        try:
            await follower.wait_started(timeout=5.0)
            return follower.clock, follower
        except TimeoutError:
            log.info("waiting for sim time on %s/%s", bus.namespace, topic)


def _odometry_stamp(odometry: Odometry) -> float:
    return odometry.header.stamp


def _tapped_stamp(taps: Sequence[OdometryTap]) -> Callable[[Odometry], float]:
    """The stamp of each odometry message, the message handed to ``taps`` (Zenoh's thread)."""

    def stamp_of(odometry: Odometry) -> float:
        for tap in taps:
            tap.put(odometry)
        return odometry.header.stamp

    return stamp_of
