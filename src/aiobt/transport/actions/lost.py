"""Goals a client gave up for lost while their server was out of reach: canceled when
the server is back.

A goal is lost when its server's session goes: the process was killed, hung, or cut
off (a router-to-router link that dropped). A killed server's goals died with it, but
a cut-off server runs its goal on, unwatched: Zenoh tells a queryable nothing when the
route back to its querier goes, and sends no query again when the link heals. So when
the server's liveliness token comes back, the client cancels every goal it judged lost
since. A server that restarted meanwhile does not know them and cancels nothing.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections import deque
from collections.abc import Awaitable, Callable

from aiobt.transport.services import ServiceError

log = logging.getLogger("aiobt.transport.actions")
KEEP = 32  # lost goals remembered per client (one runs at a time, one waits)
ATTEMPTS = 5  # a back server's cancel queryable may be routed a moment after its token
RETRY_PAUSE = 0.5  # s between attempts
CANCEL_TIMEOUT = 2.0  # s for each attempt's answer

Cancel = Callable[[str, float], Awaitable[list[str]]]


class LostGoals:
    """The ids of goals lost to their server's absence; canceled by :meth:`server_back`."""

    def __init__(self, server: str, cancel: Cancel) -> None:
        self._server = server
        self._cancel = cancel
        self._ids: deque[str] = deque(maxlen=KEEP)
        self._tasks: set[asyncio.Task[None]] = set()

    def add(self, goal_id: str) -> None:
        self._ids.append(goal_id)

    def server_back(self) -> None:
        """The server's token is back: cancel the lost goals (in a task of this loop)."""
        if not self._ids:
            return
        ids = list(self._ids)
        self._ids.clear()
        task = asyncio.get_running_loop().create_task(self._cancel_each(ids))
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)

    async def _cancel_each(self, ids: list[str]) -> None:
        for goal_id in ids:
            canceling = await self._cancel_one(goal_id)
            if canceling is None:
                log.warning(
                    "action %s: could not cancel goal %s, lost while the server was out of "
                    "reach (no answer to %d cancel requests): it may still run",
                    self._server,
                    goal_id,
                    ATTEMPTS,
                )
            elif canceling:
                log.warning(
                    "action %s: goal %s, lost while the server was out of reach, was still "
                    "running there: canceled it",
                    self._server,
                    goal_id,
                )

    async def _cancel_one(self, goal_id: str) -> list[str] | None:
        for attempt in range(ATTEMPTS):
            with contextlib.suppress(ServiceError, TimeoutError):
                return await self._cancel(goal_id, CANCEL_TIMEOUT)
            if attempt + 1 < ATTEMPTS:
                await asyncio.sleep(RETRY_PAUSE)
        return None

    async def settled(self) -> None:
        """Wait for the cancels under way."""
        await asyncio.gather(*self._tasks)

    def close(self) -> None:
        for task in list(self._tasks):
            task.cancel()
