"""Throttling and coalescing for the web view: the latest value per stream, never a backlog.

Two stages, both keyed by stream name (``pose``, ``scan``, ``map``...):

- :class:`Latest` holds the newest raw message of each stream until the next
  flush drains it: a robot publishing at 500 Hz costs one conversion per flush,
  not 500.
- :class:`Hub` keeps the latest encoded (JSON) value of every stream and one
  :class:`Outbox` per websocket client. An outbox holds at most one value per
  stream: a client that reads slowly gets the newest values when it is ready,
  and its memory is bounded by the number of streams, whatever the robot's rate.
  ``publish(..., on_change=True)`` skips a value equal to the last one (maps are
  sent once, and again only when they change).
"""

from __future__ import annotations

import asyncio
import json
from typing import Generic, TypeVar

T = TypeVar("T")


class Latest(Generic[T]):
    """The newest value of each stream since the last :meth:`drain`."""

    __slots__ = ("_values", "replaced")

    def __init__(self) -> None:
        self._values: dict[str, T] = {}
        self.replaced = 0  # values overwritten before they were drained

    def set(self, stream: str, value: T) -> None:
        if stream in self._values:
            self.replaced += 1
        self._values[stream] = value

    def drain(self) -> dict[str, T]:
        """The pending values (stream -> newest), and nothing pending after."""
        values, self._values = self._values, {}
        return values

    def __len__(self) -> int:
        return len(self._values)


class Outbox:
    """What one client has not been sent yet: at most one encoded value per stream."""

    __slots__ = ("_pending", "ready")

    def __init__(self) -> None:
        self._pending: Latest[str] = Latest()
        self.ready = asyncio.Event()

    @property
    def replaced(self) -> int:
        """Values this client never got because a newer one came first."""
        return self._pending.replaced

    def put(self, stream: str, encoded: str) -> None:
        self._pending.set(stream, encoded)
        self.ready.set()

    def take(self) -> str | None:
        """One JSON object ``{stream: value, ...}`` of everything pending, or None."""
        self.ready.clear()
        pending = self._pending.drain()
        if not pending:
            return None
        return "{" + ",".join(f"{json.dumps(k)}:{v}" for k, v in pending.items()) + "}"

    def __len__(self) -> int:
        return len(self._pending)


class Hub:
    """The latest value of every stream, fanned out to the clients' outboxes."""

    __slots__ = ("_outboxes", "latest")

    def __init__(self) -> None:
        self.latest: dict[str, str] = {}
        self._outboxes: set[Outbox] = set()

    def publish(self, stream: str, value: object, *, on_change: bool = False) -> bool:
        """Encode ``value`` once and queue it for every client; False when ``on_change``
        and it equals the stream's last value (nothing queued)."""
        encoded = json.dumps(value, separators=(",", ":"), allow_nan=False)
        if on_change and self.latest.get(stream) == encoded:
            return False
        self.latest[stream] = encoded
        for outbox in self._outboxes:
            outbox.put(stream, encoded)
        return True

    def join(self) -> Outbox:
        """A new client's outbox, holding the latest value of every stream already."""
        outbox = Outbox()
        for stream, encoded in self.latest.items():
            outbox.put(stream, encoded)
        self._outboxes.add(outbox)
        return outbox

    def leave(self, outbox: Outbox) -> None:
        self._outboxes.discard(outbox)

    @property
    def clients(self) -> int:
        return len(self._outboxes)
