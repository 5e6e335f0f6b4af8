"""A :class:`ManualClock` fed from another thread, woken only when a sleeper is due,
listening to the simulation only while something needs its time.

The simulation publishes its time at 100 Hz of sim time, at a speed-up once per
wake-up of its loop: 250 stamps a wall second at a speed-up of 10. Setting a clock
in the event loop for each of them costs a service that sleeps once per control
period (or not at all, idle) a loop wake-up per stamp. :class:`SimTime` lets the
receiving thread record the newest stamp (:meth:`receive`, one float) and says when
the loop must look: only when the stamp reaches the earliest sleeper's deadline.
Readers of :meth:`now` in the loop see the newest stamp received, as promptly as
before.

Receiving the stamps at all still costs Zenoh's threads a few % of a core. Bound
to a :class:`ClockSource` (:meth:`SimTime.bind`), the clock is listened to only
while it is *held*: by a sleeper (from its call to its wake-up), or by a user of
:meth:`held` (an action goal, a service call). ``linger`` wall seconds after the
last hold ends the source is detached; time then stands at the last stamp
received. The next hold attaches it again and :meth:`wait_fresh` waits for a
stamp sent after that, so the first ``now()`` of a goal, and every sleep's start,
is the robot's time again. Time never runs backwards.
"""

from __future__ import annotations

import asyncio
import contextlib
import heapq
import logging
import math
from collections.abc import AsyncIterator
from typing import Protocol

from aiobt.core.clock import Clock, ManualClock

log = logging.getLogger("aiobt.transport.simtime")
LINGER = 1.0  # wall s the source stays attached after the last hold ended
FRESH_TIMEOUT = 2.0  # wall s an action goal waits for the clock before it starts anyway


class ClockSource(Protocol):
    """Where the stamps come from: ``attach`` starts :meth:`SimTime.receive` calls
    (and :meth:`SimTime.arrived` at the first stamp), ``detach`` stops them."""

    def attach(self) -> None: ...

    def detach(self) -> None: ...


class SimTime(ManualClock):
    """Time from stamps received on any thread; sleepers wake in the loop.

    ``receive(stamp)`` (any thread) records a stamp and returns True when a sleeper
    is due: then the loop must call :meth:`catch_up`. ``now()`` and ``sleep()``
    (in the loop) catch up first. Time never runs backwards: an earlier stamp (a
    restarted simulation) is ignored until the stamps pass the newest one seen.
    Unbound (no :meth:`bind`), the stamps are taken as always flowing.
    """

    __slots__ = ("_fresh", "_frozen", "_holds", "_idle_since", "_received", "_source",
                 "_timer", "due", "linger")  # fmt: skip

    def __init__(self, start: float = 0.0, *, linger: float = LINGER) -> None:
        if not (math.isfinite(linger) and linger >= 0.0):
            raise ValueError(f"SimTime linger must be finite and >= 0 wall s, got {linger!r}")
        super().__init__(start)
        self._received = start
        self._frozen = False  # time already moved in this turn of the loop
        self.due = math.inf  # earliest sleeper's deadline (inf: nobody waits)
        self.linger = linger
        self._source: ClockSource | None = None  # None: always listening
        self._fresh: asyncio.Event | None = None  # set at the first stamp since attaching
        self._holds = 0
        self._idle_since = 0.0
        self._timer: asyncio.TimerHandle | None = None

    # -- stamps ------------------------------------------------------------------------------
    def receive(self, stamp: float) -> bool:
        """Any thread: note ``stamp``; True if the loop should :meth:`catch_up` now."""
        if stamp > self._received:
            self._received = stamp
        return stamp >= self.due

    def catch_up(self) -> None:
        """In the loop: move to the newest stamp received, wake every sleeper now due."""
        self.set(self._received)
        deadline = self.next_deadline()
        self.due = math.inf if deadline is None else deadline
        if not self._frozen:
            self._frozen = True
            asyncio.get_running_loop().call_soon(self._thaw)

    def _thaw(self) -> None:
        self._frozen = False

    def now(self) -> float:
        """The newest stamp received, read once per turn of the loop: within one turn
        (a woken sleeper's work up to its next ``sleep``) time stands still, as it
        did when each stamp was a loop callback, so a loop sleeping ``period`` after
        its work keeps its period whatever the work took. While detached, the last
        stamp received (see :meth:`held` for the robot's time now)."""
        if self._received > self._now and not self._frozen:
            self.catch_up()
        return self._now

    async def sleep(self, seconds: float) -> None:
        """Sleep ``seconds`` of robot time, counted from a fresh stamp (the clock is
        held, so listened to, from the call to the wake-up)."""
        if seconds <= 0.0:
            await asyncio.sleep(0)
            return
        self.hold()
        try:
            if not self.fresh:
                await self._fresh_event().wait()
            deadline = self.now() + seconds
            future: asyncio.Future[None] = asyncio.get_running_loop().create_future()
            heapq.heappush(self._sleepers, (deadline, next(self._seq), future))
            if deadline < self.due:  # read by the receiving thread: wake the loop by then
                self.due = deadline
            await future
        finally:
            self.release()

    # -- listening on demand -----------------------------------------------------------------
    def bind(self, source: ClockSource) -> None:
        """Listen through ``source`` (attached now) only while held from here on."""
        self._source = source
        self._fresh = asyncio.Event()  # attached; fresh at its first stamp
        if self._holds == 0:
            self._idle()

    @property
    def listening(self) -> bool:
        """Whether stamps are being received (always, unbound)."""
        return self._source is None or self._fresh is not None

    @property
    def fresh(self) -> bool:
        """Whether a stamp arrived since the source was (last) attached."""
        return self._source is None or (self._fresh is not None and self._fresh.is_set())

    def arrived(self) -> None:
        """In the loop: the first stamp since attaching has been received."""
        self.catch_up()
        if self._fresh is not None:  # None: a stamp still in flight when it detached
            self._fresh.set()

    def _fresh_event(self) -> asyncio.Event:
        if self._fresh is None:  # detached (or never attached since bind)
            self._fresh = asyncio.Event()
            if self._source is not None:
                self._source.attach()
                log.debug("clock attached")
        return self._fresh

    def hold(self) -> None:
        """One user more: listen (attach if detached) until the matching :meth:`release`."""
        self._holds += 1
        if self._source is not None:
            self._fresh_event()

    def release(self) -> None:
        """One user fewer; the last lets the source go ``linger`` wall s later."""
        self._holds -= 1
        if self._holds == 0 and self._source is not None:
            self._idle()

    def _idle(self) -> None:
        """Nobody holds the clock: let the source go ``linger`` wall s from now."""
        loop = asyncio.get_running_loop()
        self._idle_since = loop.time()
        if self._timer is None:
            self._timer = loop.call_later(self.linger, self._detach_if_idle)

    def _detach_if_idle(self) -> None:
        self._timer = None
        if self._holds > 0 or self._source is None or self._fresh is None:
            return
        loop = asyncio.get_running_loop()
        left = self._idle_since + self.linger - loop.time()
        if left > 0.0:
            self._timer = loop.call_later(left, self._detach_if_idle)
            return
        self._fresh = None
        self._source.detach()
        log.debug("clock detached (time stands at %.3f)", self._received)

    async def wait_fresh(self, timeout: float | None) -> bool:  # noqa: ASYNC109
        """Listen and wait (at most ``timeout`` wall s) for a stamp newer than the
        last attach; True once there is one."""
        if self.fresh:
            return True
        self.hold()
        try:
            async with asyncio.timeout(timeout):
                await self._fresh_event().wait()
        except TimeoutError:
            return False
        finally:
            self.release()
        return True

    @contextlib.asynccontextmanager
    async def held(self, timeout: float | None) -> AsyncIterator[bool]:  # noqa: ASYNC109
        """Hold the clock for the block, entered once it is fresh (or after ``timeout``
        wall s without a stamp: yields False, ``now()`` then is the last one known)."""
        self.hold()
        try:
            fresh = await self.wait_fresh(timeout)
            if not fresh:
                log.warning("no clock stamp within %.1f s of listening", timeout)
            yield fresh
        finally:
            self.release()

    def unbind(self) -> None:
        """Stop managing the source (it is closed): nothing attaches it again."""
        if self._timer is not None:
            self._timer.cancel()
            self._timer = None
        self._source = None


@contextlib.asynccontextmanager
async def clock_held(clock: Clock, timeout: float | None) -> AsyncIterator[bool]:  # noqa: ASYNC109
    """``clock.held(timeout)`` for a :class:`SimTime`; any other clock is always fresh."""
    if not isinstance(clock, SimTime):
        yield True
        return
    async with clock.held(timeout) as fresh:
        yield fresh
