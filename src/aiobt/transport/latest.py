"""The newest message on a topic, decoded when read: arrivals run no Python at all.

A :class:`~aiobt.transport.topics.Subscription` hands every burst to the event loop,
and each hand-over is a cross-thread wake-up (a write to the loop's self-pipe, the
loop's ``epoll`` returning): on a small virtual machine about 100 us of CPU, paid
for each of the 250 bursts a wall second of a robot's pose stream at a sim speed-up
of 10, whether or not anybody reads them. A reader that only wants the robot's
pose *now* (a plan's start, a probe, a status line) needs none of that.

:class:`Latest` subscribes into a Zenoh ring of ``keep`` samples: Zenoh keeps the
newest ones and drops the older, with no Python call per message (a Python callback
only to keep the payload costs Zenoh's receiving thread the GIL for each message,
bench/history/transport.md). A read (:meth:`Latest.get`, :meth:`Latest.newest_first`,
:attr:`Latest.received`) takes what the ring holds and decodes the newest once. A
malformed payload is logged once per field and the last good message stays the
answer. Read it from one thread (the event loop's).

``keep`` > 1 also keeps the last ``keep`` payloads (a robot's poses, to find the one
stamped with a scan): :meth:`Latest.newest_first` decodes them newest first, each at
most once, as far as the reader goes. :meth:`Latest.wait_latest` waits for a first
message, looking at the ring (:func:`look_after`): nothing calls into the loop.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections import deque
from collections.abc import Callable, Iterator
from typing import Any, Generic, Protocol, TypeVar

import zenoh
from pydantic import ValidationError

from aiobt.msgs import MessageError, Msg, wire_validator
from aiobt.transport.bridge import PayloadTooLarge
from aiobt.transport.repeats import BadMessages

M = TypeVar("M", bound=Msg)
T = TypeVar("T")
_REFUSED = object()  # a kept payload found malformed or too large
_PUT = zenoh.SampleKind.PUT
WAIT_LOOK = 0.002  # wall s: the shortest time between two looks for a first message
WAIT_LOOK_MAX = 0.02  # wall s: the longest
log = logging.getLogger("aiobt.transport.latest")


class Ring(Protocol):
    """What :class:`Latest` reads: a subscriber's Zenoh ring (``RingChannel``'s handler)."""

    def try_recv(self) -> zenoh.Sample | None: ...


def look_after(waited: float) -> float:
    """Wall s until the next look for a first message, ``waited`` s into the wait: a
    tenth of the wait so far, between ``WAIT_LOOK`` and ``WAIT_LOOK_MAX`` (a message
    is seen at most 10 % of the wait, or 2 ms, after it came; a long wait looks 50
    times a second)."""
    return min(WAIT_LOOK_MAX, max(WAIT_LOOK, waited / 10.0))


async def first_read(read: Callable[[], T | None], timeout: float | None) -> T:  # noqa: ASYNC109
    """``read()``'s first answer that is not None, looked for every :func:`look_after`
    wall s (at most ``timeout`` s: TimeoutError): a wait on rings nothing calls back from."""
    loop = asyncio.get_running_loop()
    start = loop.time()
    async with asyncio.timeout(timeout):
        while (found := read()) is None:  # noqa: ASYNC110 - nothing calls the loop
            await asyncio.sleep(look_after(loop.time() - start))
    return found


class Latest(Generic[M]):
    """The newest ``model`` on ``key``, decoded on :meth:`get` (see the module's docstring).

    ``received`` counts the samples taken from the ring (PUTs of any size; one that
    newer ones pushed out of the ring before any read is not counted); ``dropped_invalid``
    the ones found malformed or too large."""

    __slots__ = (
        "_arrived",
        "_bad",
        "_decoded",
        "_kept",
        "_max_payload",
        "_raw",
        "_received",
        "_ring",
        "_undeclare",
        "_validate_json",
        "keep",
        "key",
        "model",
        "on_close",
    )

    def __init__(self, key: str, model: type[M], max_payload: int, *, keep: int = 1) -> None:
        if keep < 1:
            raise ValueError(f"{key}: keep must be >= 1 message, got {keep!r}")
        self.key = key
        self.model = model
        self.keep = keep  # the ring's capacity
        self._received = 0
        self._bad = BadMessages(log)
        self._max_payload = max_payload
        self._validate_json = wire_validator(model)
        self._raw: list[Any] | None = None  # [payload, taken at, decoded]; a read fills the third
        self._kept: deque[list[Any]] | None = deque(maxlen=keep) if keep > 1 else None
        self._decoded: M | None = None
        self._arrived = float("nan")  # wall time the payload ``_decoded`` was taken
        self._ring: Ring | None = None
        self._undeclare: Callable[[], None] = lambda: None
        self.on_close: Callable[[], None] | None = None

    def _take(self) -> None:
        """Take what the ring holds (at most ``keep``, newest last)."""
        ring = self._ring
        if ring is None:
            return
        for _ in range(self.keep + 2):  # bounded: what comes meanwhile waits for the next read
            sample = ring.try_recv()
            if sample is None:
                return
            if sample.kind == _PUT:
                raw = [sample.payload.to_bytes(), time.monotonic(), None]
                self._raw = raw
                if self._kept is not None:
                    self._kept.append(raw)
                self._received += 1

    @property
    def received(self) -> int:
        """Samples taken from the ring so far (reading takes what it holds)."""
        self._take()
        return self._received

    def get(self) -> M | None:
        """The newest good message (None before the first); decodes a new payload once."""
        self._take()
        raw = self._raw
        if raw is None:
            return None
        decoded = self._decode(raw)  # cached in the entry: decoded once
        if decoded is not None:
            self._decoded, self._arrived = decoded, raw[1]
        return self._decoded

    def newest_first(self) -> Iterator[M]:
        """The kept messages (the last ``keep``), newest first, each decoded at most once
        and only when the iteration reaches it; malformed ones are skipped."""
        self._take()
        kept = self._kept
        newest = self._raw  # a copy of the kept ones: a read meanwhile appends
        for raw in reversed(list(kept) if kept is not None else [newest] if newest else []):
            decoded = self._decode(raw)
            if decoded is not None:
                yield decoded

    async def wait_latest(self, timeout: float | None = None) -> M:  # noqa: ASYNC109
        """The newest good message, waiting (at most ``timeout`` s) for one to come
        (looking at the ring, :func:`look_after`: nothing calls into the loop)."""
        return await first_read(self.get, timeout)

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
        """``time.monotonic()`` when the message :meth:`get` returns was taken from the
        ring (nan: none yet): no earlier than its arrival, and no later than the first
        read after it (a reader reading each cycle: within a cycle of it)."""
        self.get()
        return self._arrived

    @property
    def dropped_invalid(self) -> int:
        """Payloads :meth:`get` found malformed or too large."""
        return self._bad.count

    def bind(self, ring: Ring, undeclare: Callable[[], None]) -> None:
        """Read from ``ring`` (a subscriber's ring of ``keep``) until ``undeclare``."""
        self._ring = ring
        self._undeclare = undeclare

    def close(self) -> None:
        """Undeclare (idempotent); :meth:`get` keeps answering the last message taken."""
        self._take()
        self._ring = None
        self._undeclare()
        self._undeclare = lambda: None
        on_close, self.on_close = self.on_close, None
        if on_close is not None:
            on_close()
