"""Robot time.

Every node and service takes time from one injected :class:`Clock`, never from
``time.time()`` or ``asyncio.sleep()`` directly, so the same code runs on the
wall clock, on simulation time published by the robot, faster than real time,
or under a test that advances a :class:`ManualClock` by hand.
"""

from __future__ import annotations

import asyncio
import heapq
import itertools
import time
from typing import Protocol, runtime_checkable


@runtime_checkable
class Clock(Protocol):
    """The clock protocol: seconds as floats, on one monotonic time line."""

    def now(self) -> float:
        """Current time in seconds."""
        ...

    async def sleep(self, seconds: float) -> None:
        """Sleep ``seconds`` of this clock's time (returns at once for <= 0)."""
        ...


class SystemClock:
    """Wall time: ``time.monotonic()`` and ``asyncio.sleep()``."""

    __slots__ = ()

    def now(self) -> float:
        return time.monotonic()

    async def sleep(self, seconds: float) -> None:
        await asyncio.sleep(max(0.0, seconds))


SYSTEM_CLOCK = SystemClock()
"""The wall clock trees get when none is given (one instance, so they share tickers)."""


class ScaledClock:
    """Wall time running ``factor`` times faster (``factor`` > 0)."""

    __slots__ = ("_factor", "_origin", "_start")

    def __init__(self, factor: float, start: float = 0.0) -> None:
        if not factor > 0.0:
            raise ValueError(f"ScaledClock factor must be > 0, got {factor!r}")
        self._factor = factor
        self._origin = time.monotonic()
        self._start = start

    @property
    def factor(self) -> float:
        return self._factor

    def now(self) -> float:
        return self._start + (time.monotonic() - self._origin) * self._factor

    async def sleep(self, seconds: float) -> None:
        await asyncio.sleep(max(0.0, seconds) / self._factor)


class ManualClock:
    """A clock that moves only when told to.

    Tests advance it with :meth:`advance` or :meth:`forward`; a simulation-time
    follower calls :meth:`set` with each time stamp it receives. Sleepers wake
    in deadline order once the time reaches their deadline.
    """

    __slots__ = ("_now", "_seq", "_sleepers")

    def __init__(self, start: float = 0.0) -> None:
        self._now = start
        self._sleepers: list[tuple[float, int, asyncio.Future[None]]] = []
        self._seq = itertools.count()

    def now(self) -> float:
        return self._now

    async def sleep(self, seconds: float) -> None:
        if seconds <= 0.0:
            await asyncio.sleep(0)
            return
        future: asyncio.Future[None] = asyncio.get_running_loop().create_future()
        heapq.heappush(self._sleepers, (self._now + seconds, next(self._seq), future))
        await future

    @property
    def pending_sleepers(self) -> int:
        """How many sleepers wait for a deadline not reached yet."""
        return sum(1 for _, _, future in self._sleepers if not future.done())

    def next_deadline(self) -> float | None:
        """Earliest deadline among the waiting sleepers, if any."""
        while self._sleepers and self._sleepers[0][2].done():
            heapq.heappop(self._sleepers)
        return self._sleepers[0][0] if self._sleepers else None

    def set(self, now: float) -> None:
        """Jump to ``now`` (never backwards) and wake every sleeper now due."""
        if now < self._now:
            return
        self._now = now
        while self._sleepers and self._sleepers[0][0] <= now:
            _, _, future = heapq.heappop(self._sleepers)
            if not future.done():
                future.set_result(None)

    def advance(self, seconds: float) -> None:
        """Move time forward by ``seconds`` and wake every sleeper now due."""
        self.set(self._now + seconds)

    async def forward(self, seconds: float, step: float = 0.01) -> None:
        """Advance ``seconds`` in steps of ``step``, letting the loop run between.

        Sleepers woken at one step run (and may sleep again) before the next
        step, as they would in real time, so a test can say "ten seconds pass".
        """
        end = self._now + seconds
        while self._now < end:
            self.set(min(end, self._now + step))
            for _ in range(3):
                await asyncio.sleep(0)
