"""Subscriptions held only while something needs them: the robot's streams, say.

At a sim speed-up of 10 the robot publishes about 1,100 pose, odometry and scan
messages a wall second; a controller, behavior server or navigator with no goal
has no use for them. :class:`OnDemand` subscribes when the first user comes
(a goal starts), waits (bounded) for a first message on the streams that must
be fresh, and lets go ``linger`` robot seconds after the last user left (a tree
sending goal after goal keeps the streams). What was received before is
forgotten on each attach: a goal never starts on a pose from before.

A :class:`SimTime` clock listening on demand is held from each ``acquire`` to its
``release`` (and, by its sleeper, through the ``linger``); the streams are
attached once its time is fresh, so the first poses are stamped on it.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections.abc import AsyncIterator, Callable, Sequence
from typing import Protocol

from aiobt.core.clock import Clock
from aiobt.transport.simtime import SimTime

log = logging.getLogger("aiobt.transport.on_demand")
LINGER = 5.0  # robot s the streams stay after the last goal (the next is often near)


class Stream(Protocol):
    """What the feed needs of a subscription."""

    async def wait_latest(self, timeout: float | None = None) -> object: ...  # noqa: ASYNC109

    def close(self) -> None: ...


class OnDemand:
    """Attach on the first user, detach ``linger`` robot seconds after the last.

    ``attach()`` subscribes and returns the streams to close on detach, the first
    ``waited`` of them to be waited for (e.g. pose and odometry, not the lidar);
    ``forget()`` drops what was received before; ``released()`` (if given) is
    called after a detach closed the streams. ``wait_on_attach_only``: a user
    arriving while the streams are attached does not wait (a silent publisher
    costs only the user that attached a wait); one arriving during that wait waits
    for its end, and waits in its place if that user left before it was over (its
    goal cancelled), so no user is told the streams are fresh before they are.
    """

    def __init__(
        self,
        attach: Callable[[], Sequence[Stream]],
        forget: Callable[[], None],
        clock: Clock,
        *,
        linger: float = LINGER,
        waited: int = 2,
        released: Callable[[], None] | None = None,
        wait_on_attach_only: bool = False,
    ) -> None:
        if not linger >= 0.0:
            raise ValueError(f"on-demand subscriptions: linger must be >= 0 s, got {linger!r}")
        self._attach = attach
        self._forget = forget
        self._clock = clock
        self._linger = linger
        self._waited = waited
        self._released = released
        self._wait_on_attach_only = wait_on_attach_only  # attached: take what came, if any
        self._settled = asyncio.Event()  # the attaching user's wait ended
        self._settled.set()
        self._wait_over = False  # ...with a first message on each, or its timeout
        self._streams: Sequence[Stream] = ()
        self._users = 0
        self._detacher: asyncio.Task[None] | None = None

    @property
    def attached(self) -> bool:
        return bool(self._streams)

    async def acquire(self, timeout: float) -> bool:  # noqa: ASYNC109
        """Attach if detached; True once the waited streams each had a message
        (False after ``timeout`` wall s: the goal then sees no fresh pose)."""
        self._users += 1
        if self._detacher is not None:
            self._detacher.cancel()
            self._detacher = None
        sim_time = self._clock if isinstance(self._clock, SimTime) else None
        if sim_time is not None:
            sim_time.hold()
        try:
            async with asyncio.timeout(timeout):
                if sim_time is not None:
                    await sim_time.wait_fresh(None)
                if self._streams and self._wait_on_attach_only:
                    await self._settled.wait()  # a user attaching meanwhile: its wait
                    if self._wait_over:
                        return True
                    # that user left (its goal cancelled) before its wait was over: the
                    # streams may have nothing yet, so this one waits in its place
                if not self._streams:
                    self._forget()
                    self._streams = tuple(self._attach())
                    log.debug("streams attached")
                self._wait_over = False
                self._settled.clear()
                try:
                    await asyncio.gather(*(s.wait_latest() for s in self._streams[: self._waited]))
                    self._wait_over = True
                finally:
                    self._settled.set()
        except TimeoutError:
            self._wait_over = True  # silent streams: the users after do not wait on them
            log.warning("no first message within %.1f s of attaching", timeout)
            return False
        return True

    def release(self) -> None:
        """One user fewer; the last schedules the detach after ``linger``."""
        self._users -= 1
        if isinstance(self._clock, SimTime):
            self._clock.release()
        if self._users == 0 and self._streams and self._detacher is None:
            self._detacher = asyncio.ensure_future(self._detach_later())

    @contextlib.asynccontextmanager
    async def active(self, timeout: float) -> AsyncIterator[bool]:  # noqa: ASYNC109
        """``acquire`` ... ``release`` around a goal; yields whether samples came."""
        try:
            yield await self.acquire(timeout)
        finally:
            self.release()

    async def _detach_later(self) -> None:
        await self._clock.sleep(self._linger)
        self._detacher = None
        if self._users == 0:
            self.detach()

    def detach(self) -> None:
        """Close the streams now (also when the service stops)."""
        if self._detacher is not None:
            self._detacher.cancel()
            self._detacher = None
        streams, self._streams = self._streams, ()
        for stream in streams:
            stream.close()
        if streams:
            if self._released is not None:
                self._released()
            log.debug("streams detached")
