"""A :class:`ManualClock` fed from another thread, woken only when a sleeper is due.

The simulation publishes its time at 100 Hz of sim time: 1,000 stamps a wall second
at a speed-up of 10. Setting a clock in the event loop for each of them costs a
service that sleeps once per control period (or not at all, idle) a loop wake-up
per stamp. :class:`SimTime` lets the receiving thread record the newest stamp
(:meth:`receive`, one float) and says when the loop must look: only when the
stamp reaches the earliest sleeper's deadline. Readers of :meth:`now` in the loop
see the newest stamp received, as promptly as before.
"""

from __future__ import annotations

import asyncio
import heapq
import math

from aiobt.core.clock import ManualClock


class SimTime(ManualClock):
    """Time from stamps received on any thread; sleepers wake in the loop.

    ``receive(stamp)`` (any thread) records a stamp and returns True when a sleeper
    is due: then the loop must call :meth:`catch_up`. ``now()`` and ``sleep()``
    (in the loop) catch up first. Time never runs backwards: an earlier stamp (a
    restarted simulation) is ignored until the stamps pass the newest one seen.
    """

    __slots__ = ("_frozen", "_received", "due")

    def __init__(self, start: float = 0.0) -> None:
        super().__init__(start)
        self._received = start
        self._frozen = False  # time already moved in this turn of the loop
        self.due = math.inf  # earliest sleeper's deadline (inf: nobody waits)

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
        its work keeps its period whatever the work took."""
        if self._received > self._now and not self._frozen:
            self.catch_up()
        return self._now

    async def sleep(self, seconds: float) -> None:
        start = self.now()
        if seconds <= 0.0:
            await asyncio.sleep(0)
            return
        deadline = start + seconds
        future: asyncio.Future[None] = asyncio.get_running_loop().create_future()
        heapq.heappush(self._sleepers, (deadline, next(self._seq), future))
        if deadline < self.due:  # read by the receiving thread: wake the loop by then
            self.due = deadline
        await future
