"""What the service commands share: argument types, the ``python -m`` entry, the run loop.

Each service's ``main`` module keeps its own options and wiring; this module
holds the parts that were the same in all of them.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import logging
import math
from collections.abc import AsyncIterator, Callable, Coroutine
from typing import Any, TypeVar

from aiobt.system.signals import stop_on_signals as stop_on_signals  # for the services
from aiobt.transport import Bus, BusConfigError, BusSettings, BusUnavailable, open_bus
from aiobt_services.realtime import RealtimePriorityError

T = TypeVar("T")


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
