"""A topic's recent messages, kept by Zenoh and taken in order when the reader asks.

A :class:`~aiobt.transport.topics.Subscription` runs Python for every message (the
decode on Zenoh's thread, then a wake-up of the event loop): at the robot's 50 Hz
odometry about 150-250 us of CPU a message, whether or not the reader needs it
now. A reader that needs a stream only at its own moments (localization wants the
odometry around each scan's stamp, 10 a second) needs none of that.

:class:`Backlog` subscribes into a Zenoh ring of ``capacity`` samples: Zenoh keeps
the newest, drops the oldest, and runs no Python per message. :meth:`Backlog.take`
returns what came since the last take, oldest first, decoded; a malformed or too
large payload is logged once per field and skipped. What a full ring pushed out
before a take is lost (size the ring for the longest gap between takes).
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Generic, TypeVar

import zenoh
from pydantic import ValidationError

from aiobt.msgs import MessageError, Msg, wire_validator
from aiobt.transport import _z
from aiobt.transport.bridge import PayloadTooLarge
from aiobt.transport.repeats import BadMessages

if TYPE_CHECKING:
    from aiobt.transport.bus import Bus

M = TypeVar("M", bound=Msg)
_PUT = zenoh.SampleKind.PUT
log = logging.getLogger("aiobt.transport.backlog")


class TypedSubscriber(Generic[M]):
    """A Zenoh subscriber of ``model`` on ``key`` and its decoding: what a
    :class:`Backlog` and a :class:`~aiobt.transport.relay.Relay` share. ``received``
    counts the PUTs handled; ``dropped_invalid`` the ones found malformed or too large
    (logged once per field)."""

    def __init__(self, key: str, model: type[M], max_payload: int) -> None:
        self.key = key
        self.model = model
        self.received = 0
        self._bad = BadMessages(log)
        self._max_payload = max_payload
        self._validate_json: Callable[[bytes], M] = wire_validator(model)
        self._subscriber: zenoh.Subscriber[Any] | None = None

    def _decode(self, payload: bytes) -> M | None:
        try:
            if len(payload) > self._max_payload:
                raise PayloadTooLarge(self.key, len(payload), self._max_payload)
            return self._validate_json(payload)
        except ValidationError as exc:
            self._bad.drop(MessageError.from_validation(self.model, exc, self.key))
        except PayloadTooLarge as exc:
            self._bad.drop(exc)
        return None

    @property
    def dropped_invalid(self) -> int:
        return self._bad.count

    def close(self) -> None:
        """Undeclare (idempotent)."""
        subscriber, self._subscriber = self._subscriber, None
        if subscriber is not None:
            _z.undeclare(subscriber)


class Backlog(TypedSubscriber[M]):
    """The last ``capacity`` messages of ``model`` on ``key``, taken in order (see the
    module's docstring); closed, :meth:`take` returns nothing."""

    def __init__(
        self, session: zenoh.Session, key: str, model: type[M], capacity: int, max_payload: int
    ) -> None:
        if capacity < 1:
            raise ValueError(f"{key}: a backlog's capacity must be >= 1 message, got {capacity!r}")
        super().__init__(key, model, max_payload)
        self.capacity = capacity
        ring: zenoh.handlers.RingChannel[zenoh.Sample] = zenoh.handlers.RingChannel(capacity)
        self._subscriber = session.declare_subscriber(key, ring)

    def take(self) -> list[M]:
        """The messages that came since the last take (at most ``capacity``), oldest first."""
        subscriber, out = self._subscriber, []
        if subscriber is None:
            return []
        for _ in range(self.capacity):  # bounded: what comes meanwhile waits for the next take
            sample = subscriber.try_recv()
            if sample is None:
                break
            if sample.kind != _PUT:
                continue
            self.received += 1
            message = self._decode(sample.payload.to_bytes())
            if message is not None:
                out.append(message)
        return out


def backlog(bus: Bus, name: str, model: type[M], capacity: int) -> Backlog[M]:
    """A :class:`Backlog` of ``{ns}/{name}`` on ``bus``'s session (undeclared when the
    session closes, or by :meth:`Backlog.close`)."""
    return Backlog(bus.session, bus.keys.topic(name), model, capacity, bus.bridge.max_payload)
