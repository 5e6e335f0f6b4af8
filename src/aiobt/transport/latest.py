"""The newest message on a topic, decoded when read: arrivals never wake the event loop.

A :class:`~aiobt.transport.topics.Subscription` hands every burst to the event loop,
and each hand-over is a cross-thread wake-up (a write to the loop's self-pipe, the
loop's ``epoll`` returning): on a small virtual machine about 100 us of CPU, paid
for each of the 250 bursts a wall second of a robot's pose stream at a sim speed-up
of 10, whether or not anybody reads them. A reader that only wants the robot's
pose *now* (a plan's start, a probe, a status line) needs none of that.

:class:`Latest` keeps the newest payload as Zenoh's thread received it (bytes and the
wall time of arrival, one reference swap: no lock, no decode, no loop call) and
decodes it when :meth:`Latest.get` is called, once per new payload. A malformed
payload is logged once per field and the last good message stays the answer.

``keep`` > 1 also keeps the last ``keep`` payloads (a robot's poses, to find the one
stamped with a scan): :meth:`Latest.newest_first` decodes them newest first, each at
most once, as far as the reader goes. :meth:`Latest.wait_latest` waits for a first
message: the one arrival after it asked is handed to the loop, no other.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections import deque
from collections.abc import Callable, Iterator
from typing import Any, Generic, TypeVar

import zenoh
from pydantic import ValidationError

from aiobt.msgs import MessageError, Msg, wire_validator
from aiobt.transport.bridge import LoopBridge, PayloadTooLarge
from aiobt.transport.repeats import BadMessages

M = TypeVar("M", bound=Msg)
_REFUSED = object()  # a kept payload found malformed or too large
_PUT = zenoh.SampleKind.PUT
log = logging.getLogger("aiobt.transport.latest")


class Latest(Generic[M]):
    """The newest ``model`` on ``key``, decoded on :meth:`get` (see the module's docstring).

    ``received`` counts the samples that arrived (PUTs of any size); ``dropped_invalid``
    the ones found malformed or too large. ``bridge`` (the bus's) serves
    :meth:`wait_latest`."""

    __slots__ = (
        "_arrived",
        "_bad",
        "_bridge",
        "_decoded",
        "_kept",
        "_max_payload",
        "_raw",
        "_undeclare",
        "_validate_json",
        "_waiter",
        "key",
        "model",
        "on_close",
        "received",
    )

    def __init__(
        self, key: str, model: type[M], max_payload: int, *, keep: int = 1,
        bridge: LoopBridge | None = None,
    ) -> None:  # fmt: skip
        if keep < 1:
            raise ValueError(f"{key}: keep must be >= 1 message, got {keep!r}")
        self.key = key
        self.model = model
        self.received = 0
        self._bad = BadMessages(log)
        self._max_payload = max_payload
        self._validate_json = wire_validator(model)
        # Zenoh's thread swaps in [payload, arrival, decoded]; a reader fills the third
        self._raw: list[Any] | None = None
        self._kept: deque[list[Any]] | None = deque(maxlen=keep) if keep > 1 else None
        self._decoded: M | None = None
        self._arrived = float("nan")  # wall time of the payload ``_decoded`` came in
        self._bridge = bridge
        self._waiter: asyncio.Future[None] | None = None
        self._undeclare: Callable[[], None] = lambda: None
        self.on_close: Callable[[], None] | None = None

    def on_sample(self, sample: zenoh.Sample) -> None:
        """Zenoh thread: keep the payload and when it came; call into the loop only
        for a :meth:`wait_latest` waiting."""
        if sample.kind == _PUT:
            raw = [sample.payload.to_bytes(), time.monotonic(), None]
            self._raw = raw
            if self._kept is not None:
                self._kept.append(raw)  # atomic under the GIL
            self.received += 1
            waiter = self._waiter
            if waiter is not None and self._bridge is not None:
                self._waiter = None
                self._bridge.call(_wake, waiter)

    def get(self) -> M | None:
        """The newest good message (None before the first); decodes a new payload once."""
        raw = self._raw  # read once: Zenoh's thread may swap in a newer one meanwhile
        if raw is None:
            return None
        decoded = self._decode(raw)  # cached in the entry: decoded once
        if decoded is not None:
            self._decoded, self._arrived = decoded, raw[1]
        return self._decoded

    def newest_first(self) -> Iterator[M]:
        """The kept messages (the last ``keep``), newest first, each decoded at most once
        and only when the iteration reaches it; malformed ones are skipped."""
        kept = self._kept
        newest = self._raw  # a copy of the kept ones: Zenoh's thread appends meanwhile
        for raw in reversed(list(kept) if kept is not None else [newest] if newest else []):
            decoded = self._decode(raw)
            if decoded is not None:
                yield decoded

    async def wait_latest(self, timeout: float | None = None) -> M:  # noqa: ASYNC109
        """The newest good message, waiting (at most ``timeout`` s) for one to come."""
        if self._bridge is None:
            raise RuntimeError(f"{self.key}: wait_latest needs the bus's bridge")
        async with asyncio.timeout(timeout):
            while (newest := self.get()) is None:
                waiter = self._waiter  # shared by every reader waiting
                if waiter is None or waiter.done():
                    waiter = self._waiter = self._bridge.loop.create_future()
                if self._raw is not None and self._raw[2] is None:
                    continue  # came between get() and the waiter: decode it
                await asyncio.shield(waiter)  # a reader giving up leaves it to the others
        return newest

    def _decode(self, raw: list[Any]) -> M | None:
        """``raw``'s message, decoded on the first call (None, logged once: malformed)."""
        if raw[2] is not None:
            return None if raw[2] is _REFUSED else raw[2]
        payload = raw[0]
        try:
            if len(payload) > self._max_payload:
                raise PayloadTooLarge(self.key, len(payload), self._max_payload)
            raw[2] = self._validate_json(payload)
        except ValidationError as exc:
            self._bad.drop(MessageError.from_validation(self.model, exc, self.key))
        except PayloadTooLarge as exc:
            self._bad.drop(exc)
        else:
            return raw[2]
        raw[2] = _REFUSED
        return None

    @property
    def arrived(self) -> float:
        """``time.monotonic()`` when the message :meth:`get` returns arrived (nan: none yet)."""
        self.get()
        return self._arrived

    @property
    def dropped_invalid(self) -> int:
        """Payloads :meth:`get` found malformed or too large."""
        return self._bad.count

    def bind(self, undeclare: Callable[[], None]) -> None:
        self._undeclare = undeclare

    def close(self) -> None:
        """Undeclare (idempotent); :meth:`get` keeps answering the last message."""
        self._undeclare()
        self._undeclare = lambda: None
        on_close, self.on_close = self.on_close, None
        if on_close is not None:
            on_close()


def _wake(waiter: asyncio.Future[None]) -> None:
    if not waiter.done():
        waiter.set_result(None)
