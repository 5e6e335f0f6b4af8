"""Goals that arrive while the robot's clock is not listened to wait for its time.

A service on a :class:`SimTime` listening on demand stops receiving the clock when
idle; its time then stands at the last stamp. A goal arriving then must not be
stamped (ACCEPTED, EXECUTING) or timed from that stale time: :class:`FreshGate`
holds it, in arrival order with any other, until a fresh stamp came (bounded by
``timeout`` wall s: a simulation gone silent lets the goal start on the last time
known, and the goal's own bounded waits report it). :func:`held_during` keeps the
clock listened to while a goal's ``execute`` runs.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable
from typing import Any, Generic, TypeVar

from aiobt.core.clock import Clock
from aiobt.transport.simtime import FRESH_TIMEOUT, SimTime

log = logging.getLogger("aiobt.transport.actions.fresh")
T = TypeVar("T")
E = TypeVar("E", bound=Callable[..., Awaitable[Any]])


class FreshGate(Generic[T]):
    """``gate(item)`` calls ``start(item)`` at once while the clock is fresh (or not a
    :class:`SimTime`), else once it is, keeping the arrival order."""

    def __init__(
        self, clock: Clock | None, start: Callable[[T], None], timeout: float = FRESH_TIMEOUT
    ) -> None:
        self._clock = clock if isinstance(clock, SimTime) else None
        self._start = start
        self._timeout = timeout
        self._pending: list[T] | None = None
        self._task: asyncio.Task[None] | None = None

    def __call__(self, item: T) -> None:
        if self._pending is None:
            if self._clock is None or self._clock.fresh:
                self._start(item)
                return
            self._pending = []
            self._task = asyncio.get_running_loop().create_task(self._open(self._clock))
        self._pending.append(item)

    async def _open(self, clock: SimTime) -> None:
        try:
            if not await clock.wait_fresh(self._timeout):
                log.warning("no clock stamp in %.1f s: goals start on the last", self._timeout)
        finally:
            self._flush()

    def _flush(self) -> None:
        pending, self._pending, self._task = self._pending or [], None, None
        for item in pending:
            self._start(item)

    async def aclose(self) -> None:
        """Stop waiting: the waiting items are started now (a closing server refuses them)."""
        task = self._task
        if task is not None:
            task.cancel()
            await asyncio.gather(task, return_exceptions=True)
        self._flush()  # also those of a task cancelled before it ran


def held_during(clock: Clock | None, execute: E) -> E:
    """``execute`` holding ``clock`` (a :class:`SimTime`) while it runs; else itself."""
    if not isinstance(clock, SimTime):
        return execute
    sim_time = clock

    async def held(*args: Any) -> Any:
        sim_time.hold()
        try:
            return await execute(*args)
        finally:
            sim_time.release()

    return held  # type: ignore[return-value]
