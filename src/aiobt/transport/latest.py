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
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from typing import Generic, TypeVar

import zenoh
from pydantic import ValidationError

from aiobt.msgs import MessageError, Msg, wire_validator
from aiobt.transport.bridge import PayloadTooLarge
from aiobt.transport.repeats import BadMessages

M = TypeVar("M", bound=Msg)
_PUT = zenoh.SampleKind.PUT
log = logging.getLogger("aiobt.transport.latest")


class Latest(Generic[M]):
    """The newest ``model`` on ``key``, decoded on :meth:`get` (see the module's docstring).

    ``received`` counts the samples that arrived (PUTs of any size); ``dropped_invalid``
    the ones :meth:`get` found malformed or too large."""

    __slots__ = (
        "_arrived",
        "_bad",
        "_decoded",
        "_max_payload",
        "_raw",
        "_seen",
        "_undeclare",
        "_validate_json",
        "key",
        "model",
        "on_close",
        "received",
    )

    def __init__(self, key: str, model: type[M], max_payload: int) -> None:
        self.key = key
        self.model = model
        self.received = 0
        self._bad = BadMessages(log)
        self._max_payload = max_payload
        self._validate_json = wire_validator(model)
        self._raw: tuple[bytes, float] | None = None  # Zenoh's thread swaps it whole
        self._seen: tuple[bytes, float] | None = None  # the payload decoded last (or refused)
        self._decoded: M | None = None
        self._arrived = float("nan")  # wall time of the payload ``_decoded`` came in
        self._undeclare: Callable[[], None] = lambda: None
        self.on_close: Callable[[], None] | None = None

    def on_sample(self, sample: zenoh.Sample) -> None:
        """Zenoh thread: keep the payload and when it came; nothing else."""
        if sample.kind == _PUT:
            self._raw = (sample.payload.to_bytes(), time.monotonic())
            self.received += 1

    def get(self) -> M | None:
        """The newest good message (None before the first); decodes a new payload once."""
        raw = self._raw  # read once: Zenoh's thread may swap in a newer one meanwhile
        if raw is None or raw is self._seen:
            return self._decoded
        self._seen = raw
        payload, arrived = raw
        try:
            if len(payload) > self._max_payload:
                raise PayloadTooLarge(self.key, len(payload), self._max_payload)
            self._decoded = self._validate_json(payload)
        except ValidationError as exc:
            self._bad.drop(MessageError.from_validation(self.model, exc, self.key))
        except PayloadTooLarge as exc:
            self._bad.drop(exc)
        else:
            self._arrived = arrived
        return self._decoded

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
