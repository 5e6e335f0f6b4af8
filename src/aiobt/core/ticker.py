"""One shared ticker per (event loop, clock, period): the timed half of a tree's wait.

A tree ticking with :meth:`~aiobt.core.tree.Tree.tick_while_running` waits,
between two ticks, for a wake-up or for ``period`` of clock time, whichever
comes first. Giving each wait its own sleeping task (and an ``asyncio.wait``
over two tasks) makes the scheduling cost many times the tick of a Nav2-sized
tree, so that a few hundred trees in one loop already fall behind.

Here each wait is one future. Every waiter of one (loop, clock, period) joins
one queue; as each deadline is ``clock.now() + period`` taken when it joins,
the queue is in deadline order without sorting. One task per queue sleeps on
the clock until the oldest deadline and then resolves every waiter that is
due, so waiters whose deadlines have passed together cost one sleep between
them. A waiter woken early (its future already resolved or cancelled) is
skipped; the task ends when its queue is empty and starts again with the
next waiter.
"""

from __future__ import annotations

import asyncio
import logging
import weakref
from collections import deque

from aiobt.core.clock import SYSTEM_CLOCK, Clock, SystemClock

log = logging.getLogger("aiobt.core.ticker")

_TICKERS: weakref.WeakKeyDictionary[asyncio.AbstractEventLoop, dict[tuple[int, float], Ticker]]
_TICKERS = weakref.WeakKeyDictionary()


class Ticker:
    """Resolves queued futures at their clock deadlines, oldest first."""

    __slots__ = ("_clock", "_key", "_loop", "_period", "_queue", "_task")

    def __init__(self, loop: asyncio.AbstractEventLoop, clock: Clock, period: float) -> None:
        self._loop = loop
        self._clock = clock
        self._period = period
        self._key = (id(clock), period)
        self._queue: deque[tuple[float, asyncio.Future[None]]] = deque()
        self._task: asyncio.Task[None] | None = None

    @property
    def waiting(self) -> int:
        """How many waiters are queued (including ones already woken early)."""
        return len(self._queue)

    def add(self, waiter: asyncio.Future[None]) -> None:
        """Resolve ``waiter`` once ``period`` of clock time has passed (unless done before)."""
        self._queue.append((self._clock.now() + self._period, waiter))
        if self._task is None:
            self._task = self._loop.create_task(self._run(), name=f"aiobt ticker {self._period}")

    async def _run(self) -> None:
        queue, clock = self._queue, self._clock
        try:
            while queue:
                if queue[0][1].done():  # woken early: nothing to wait for
                    queue.popleft()
                    continue
                delay = queue[0][0] - clock.now()
                if delay > 0.0:
                    await clock.sleep(delay)
                now = clock.now()
                while queue and queue[0][0] <= now:
                    waiter = queue.popleft()[1]
                    if not waiter.done():
                        waiter.set_result(None)
        except asyncio.CancelledError as exc:  # the loop is closing
            self._fail(exc)
            raise
        except Exception as exc:
            log.error("ticker of period %g: the clock's sleep failed: %r", self._period, exc)
            self._fail(exc)
        finally:
            self._task = None
            tickers = _TICKERS.get(self._loop)
            if tickers is not None and tickers.get(self._key) is self:
                del tickers[self._key]

    def _fail(self, exc: BaseException) -> None:
        """The clock's sleep failed: every queued waiter gets the error, none hangs."""
        while self._queue:
            waiter = self._queue.popleft()[1]
            if waiter.done():
                continue
            if isinstance(exc, asyncio.CancelledError):
                waiter.cancel()
            else:
                waiter.set_exception(exc)


def ticker_for(clock: Clock, period: float) -> Ticker:
    """The running loop's ticker for ``clock`` and ``period`` (made on first use)."""
    if not period >= 0.0:  # also NaN
        raise ValueError(f"a tick period must be a number of seconds >= 0, got {period!r}")
    if type(clock) is SystemClock:  # stateless: every instance is the same clock
        clock = SYSTEM_CLOCK
    loop = asyncio.get_running_loop()
    tickers = _TICKERS.get(loop)
    if tickers is None:
        tickers = _TICKERS[loop] = {}
    key = (id(clock), period)
    ticker = tickers.get(key)
    if ticker is None:
        ticker = tickers[key] = Ticker(loop, clock, period)
    return ticker
