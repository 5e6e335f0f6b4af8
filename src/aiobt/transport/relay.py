"""A subscription whose callback runs on Zenoh's receiving thread: for a reader that
turns each message at once into another (localization's ``pose``: the odometry
composed with its correction), with no hop through the event loop.

A :class:`~aiobt.transport.topics.Subscription` with a callback decodes on Zenoh's
thread, then wakes the event loop for each burst (a write to the loop's self-pipe,
its ``epoll`` returning): at 50 Hz that hand-over is most of what a message costs.
:class:`Relay` calls ``fn(message)`` on Zenoh's thread instead. ``fn`` must be short,
must not block (a publisher's ``put`` with congestion control DROP is fine, a
reliable one may wait on the network) and must only read state the event loop
replaces whole. Its errors are logged (repeats counted), a malformed payload is
logged once per field; nothing reaches the loop.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import TYPE_CHECKING, TypeVar

import zenoh

from aiobt.msgs import Msg
from aiobt.transport.backlog import TypedSubscriber
from aiobt.transport.bridge import callback
from aiobt.transport.repeats import RepeatedErrors

if TYPE_CHECKING:
    from aiobt.transport.bus import Bus

M = TypeVar("M", bound=Msg)
_PUT = zenoh.SampleKind.PUT
log = logging.getLogger("aiobt.transport.relay")


class Relay(TypedSubscriber[M]):
    """``fn`` called on Zenoh's thread with every good ``model`` on ``key`` (see the
    module's docstring)."""

    def __init__(
        self, session: zenoh.Session, key: str, model: type[M], fn: Callable[[M], object],
        max_payload: int,
    ) -> None:  # fmt: skip
        super().__init__(key, model, max_payload)
        self._fn = fn
        self._errors = RepeatedErrors(log, f"{key}: relay callback")
        self._subscriber = session.declare_subscriber(key, callback(self._on_sample))

    def _on_sample(self, sample: zenoh.Sample) -> None:
        """Zenoh thread: decode, then ``fn``; nothing raises out of here."""
        if sample.kind != _PUT:
            return
        self.received += 1
        message = self._decode(sample.payload.to_bytes())
        if message is None:
            return
        try:
            self._fn(message)
        except Exception as exc:
            self._errors.report(exc)

    def close(self) -> None:
        """Undeclare (idempotent); the callback's repeated errors said."""
        super().close()
        self._errors.flush()


def relay(bus: Bus, name: str, model: type[M], fn: Callable[[M], object]) -> Relay[M]:
    """A :class:`Relay` of ``{ns}/{name}`` on ``bus``'s session (undeclared when the
    session closes, or by :meth:`Relay.close`)."""
    return Relay(bus.session, bus.keys.topic(name), model, fn, bus.bridge.max_payload)
