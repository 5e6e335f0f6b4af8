"""Zenoh callbacks (on Zenoh threads) into the asyncio loop, and payload checks.

Callbacks are registered with ``indirect=False`` (no extra Python thread) and only
queue work for the loop (at most one ``call_soon_threadsafe`` per burst): nothing
blocks a Zenoh thread.
"""

from __future__ import annotations

import asyncio
import logging
from collections import deque
from collections.abc import Callable
from typing import Any, TypeVar

import zenoh

T = TypeVar("T")
JSON = zenoh.Encoding.APPLICATION_JSON
log = logging.getLogger("aiobt.transport")


class PayloadTooLarge(ValueError):
    """A payload above the bus's ``max_payload``, refused on send and on receipt."""

    def __init__(self, key: str, size: int, limit: int) -> None:
        super().__init__(f"{key}: payload of {size} bytes exceeds the limit of {limit} bytes")
        self.key = key
        self.size = size
        self.limit = limit


class LoopBridge:
    """Hands work from Zenoh threads to one event loop; silent once the loop is gone.

    Calls queue up and one loop callback runs every call queued so far, so a
    burst of samples (or a goal's acceptance and result) wakes the loop once.
    """

    __slots__ = ("_pending", "_scheduled", "closed", "loop", "max_payload")

    def __init__(self, loop: asyncio.AbstractEventLoop, max_payload: int) -> None:
        self.loop = loop
        self.max_payload = max_payload
        self.closed = False
        self._pending: deque[tuple[Callable[..., Any], tuple[Any, ...]]] = deque()
        self._scheduled = False

    def call(self, fn: Callable[..., Any], *args: Any) -> None:
        """Run ``fn(*args)`` in the loop soon (from any thread), in call order."""
        if self.closed:
            return
        self._pending.append((fn, args))
        if self._scheduled:  # a drain that has not started yet will run this call
            return
        self._scheduled = True
        try:
            self.loop.call_soon_threadsafe(self._drain)
        except RuntimeError:  # the loop closed under us: the process is ending
            self.closed = True

    def _drain(self) -> None:
        """In the loop: run the calls queued so far (later ones schedule another drain)."""
        self._scheduled = False  # before popping: a call appended from now on reschedules
        pending = self._pending
        for _ in range(len(pending)):
            fn, args = pending.popleft()
            try:
                fn(*args)
            except Exception:
                log.exception("%s failed in the event loop", getattr(fn, "__qualname__", fn))

    def check_size(self, key: str, payload: bytes) -> None:
        if len(payload) > self.max_payload:
            raise PayloadTooLarge(key, len(payload), self.max_payload)


def callback(
    fn: Callable[[T], None], on_drop: Callable[[], None] | None = None
) -> zenoh.handlers.Callback[T]:
    """A direct Zenoh callback handler (runs on the Zenoh thread; keep ``fn`` tiny)."""
    return zenoh.handlers.Callback(fn, on_drop, indirect=False)
