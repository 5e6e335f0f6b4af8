"""Typed subscriptions: bounded, decoded off the loop, an async iterator, ``latest`` or a
callback (publishers: ``publishers.py``)."""

from __future__ import annotations

import asyncio
import logging
import time
from collections import deque
from collections.abc import Callable
from typing import Generic, Self, TypeVar

import zenoh
import zenoh.ext
from pydantic import ValidationError

from aiobt.msgs import MessageError, Msg, wire_validator
from aiobt.transport.bridge import LoopBridge, PayloadTooLarge, callback
from aiobt.transport.latest import Latest
from aiobt.transport.repeats import BadMessages, RepeatedErrors

M = TypeVar("M", bound=Msg)
_PUT = zenoh.SampleKind.PUT
log = logging.getLogger("aiobt.transport.topics")
# after a drain whose delivery took t seconds of the loop thread's CPU time the next
# waits PAUSE_PER_WORK * t: one subscription's messages take at most 1 / (1 +
# PAUSE_PER_WORK) of the event loop (CPU, not wall time: on a loaded machine a
# preempted delivery would otherwise pause the subscription for nothing)
PAUSE_PER_WORK = 4.0


class Subscription(Generic[M]):
    """Messages of ``model`` on ``key``: an async iterator, ``latest``, or a callback.

    A malformed payload is logged once per key and field, then dropped. With a
    ``callback``, it is called in the event loop for every message delivered (a
    sync function; its errors are logged, repeats counted) and nothing is queued
    for iteration.

    Every subscription is bounded: at most ``queue_size`` messages wait for the
    event loop, and as many for the iterator's reader. When either is full the
    oldest is dropped and counted in ``dropped_overflow``; with a queue of more
    than one the first drop is logged (once). A queue of 1 keeps just the newest
    message (a reader of the latest value), silently. A flood thus costs the
    receiving thread's decoding and never more memory, and at most a fifth of
    the event loop: after a delivery that took t seconds, this subscription
    waits 4 t before the next (``PAUSE_PER_WORK``; t is CPU time), meanwhile its queue keeps
    the newest messages.
    """

    def __init__(
        self,
        key: str,
        model: type[M],
        bridge: LoopBridge,
        callback: Callable[[M], object] | None,
        queue_size: int,
    ) -> None:
        if queue_size < 1:
            raise ValueError(f"{key}: queue_size must be at least 1, got {queue_size}")
        self.key = key
        self.model = model
        self.latest: M | None = None
        self.received = 0
        self._bad = BadMessages(log)
        self._bridge = bridge
        self._callback = callback
        self._validate_json = wire_validator(model)
        self._max_payload = bridge.max_payload
        # Zenoh's thread appends to ``_incoming`` and asks the loop for one drain per
        # burst (what comes while a drain is due is queued undecoded, for the drain to
        # decode if it is not dropped first: a flood costs that thread little); the
        # drain hands the messages to the callback or to ``_queue``, from
        # which readers take them. Both bounded deques (oldest dropped), leaner than an
        # asyncio.Queue on this per-message path.
        self._incoming: deque[M | bytes] = deque(maxlen=queue_size)
        self._queue: deque[M] = deque(maxlen=queue_size)
        self._drain_due = False
        self._resume_at = 0.0  # loop time before which this subscription does not drain
        self._dropped_incoming = 0  # counted in Zenoh's thread only
        self._dropped_queued = 0  # counted in the loop only
        self._overflow_said = False
        self._waiters: list[asyncio.Future[None]] = []
        self._closed = False
        self._errors = RepeatedErrors(log, f"{key}: subscriber callback")
        self._first = asyncio.Event()
        self._undeclare: Callable[[], None] = lambda: None
        self.on_close: Callable[[], None] | None = None  # told once, when closed

    @property
    def queue_size(self) -> int:
        return self._queue.maxlen or 0

    @property
    def dropped_overflow(self) -> int:
        """Messages dropped because a queue was full (the oldest ones)."""
        return self._dropped_incoming + self._dropped_queued

    def on_sample(self, sample: zenoh.Sample) -> None:
        """Zenoh thread: decode here (off the loop), hand the model to the loop.

        Kept lean: it runs for every message, usually with cold caches, and its
        time adds to every message's latency. A good message costs the size check
        and the validation only; the kind is looked at when validation fails (a
        DELETE has no payload, so it always fails)."""
        payload = sample.payload.to_bytes()
        if len(payload) > self._max_payload:
            too_large = PayloadTooLarge(self.key, len(payload), self._max_payload)
            self._bridge.call(self._reject, too_large)
            return
        if self._drain_due:  # a burst: decoded by the drain, and only if not dropped first
            if sample.kind == _PUT:
                self._push(payload)
            return
        try:
            message = self._validate_json(payload)
        except ValidationError as exc:
            if sample.kind == _PUT:  # errors name the key (it has no wildcards)
                self._bridge.call(self._reject, self._error(exc))
            return
        self._push(message)

    def _error(self, exc: ValidationError) -> MessageError:
        return MessageError.from_validation(self.model, exc, self.key)

    def _decoded(self, item: M | bytes) -> M | None:
        """In the loop: a message queued undecoded (in a burst), decoded; None if bad."""
        if not isinstance(item, bytes):
            return item
        try:
            return self._validate_json(item)
        except ValidationError as exc:
            self._reject(self._error(exc))
            return None

    def _push(self, message: M | bytes) -> None:
        """Zenoh thread: queue for the loop (oldest dropped when full), wake it once."""
        incoming = self._incoming
        if len(incoming) == incoming.maxlen:
            self._dropped_incoming += 1
        incoming.append(message)
        if not self._drain_due:
            self._drain_due = True
            self._bridge.call(self._drain)

    def _reject(self, exc: MessageError | PayloadTooLarge) -> None:
        self._bad.drop(exc)

    @property
    def dropped_invalid(self) -> int:
        """Messages dropped as malformed or too large."""
        return self._bad.count

    def _drain(self) -> None:
        """In the loop: deliver what came since the last drain (at most ``queue_size``),
        unless the last drain's work asks for a pause first (then deliver after it)."""
        loop = self._bridge.loop
        pause = self._resume_at - loop.time()
        if pause > 0.0:  # ``_drain_due`` stays set: Zenoh's thread schedules nothing meanwhile
            loop.call_later(pause, self._drain)
            return
        self._drain_due = False  # before popping: a message appended from now on reschedules
        started = time.thread_time()  # CPU time: a process the OS preempted did no work
        self._deliver()
        self._resume_at = loop.time() + (time.thread_time() - started) * PAUSE_PER_WORK

    def _deliver(self) -> None:
        incoming, queue, callback = self._incoming, self._queue, self._callback
        count = len(incoming)
        if not count or self._closed:
            return
        for _ in range(count):
            message = self._decoded(incoming.popleft())
            if message is None:
                count -= 1
                continue
            self.latest = message
            if callback is not None:
                try:
                    callback(message)
                except Exception as exc:
                    self._errors.report(exc)
            else:
                if len(queue) == queue.maxlen:
                    self._dropped_queued += 1
                queue.append(message)  # full: the oldest is dropped
        if count and not self.received:
            self._first.set()
        self.received += count
        if self.dropped_overflow and not self._overflow_said:
            self._say_overflow()
        if callback is None:
            self._wake()

    def _say_overflow(self) -> None:
        self._overflow_said = True
        if self.queue_size == 1:  # a latest-value reader: dropping is what it asked for
            return
        who = "the callback" if self._callback is not None else "the reader"
        log.warning(
            "%s: %s falls behind; the queue of %d is full and the oldest messages "
            "are dropped (reported once; see dropped_overflow)",
            self.key,
            who,
            self.queue_size,
        )

    def _wake(self) -> None:
        for waiter in self._waiters:
            if not waiter.done():
                waiter.set_result(None)

    def __aiter__(self) -> Self:
        return self

    async def __anext__(self) -> M:
        while not self._queue:
            if self._closed:
                raise StopAsyncIteration
            waiter: asyncio.Future[None] = asyncio.get_running_loop().create_future()
            self._waiters.append(waiter)
            try:
                await waiter
            finally:
                self._waiters.remove(waiter)
        return self._queue.popleft()

    async def next(self, timeout: float | None = None) -> M:  # noqa: ASYNC109
        """The next message; ``TimeoutError`` after ``timeout`` seconds."""
        if self._queue or timeout is None:
            return await self.__anext__()
        async with asyncio.timeout(timeout):
            return await self.__anext__()

    async def wait_latest(self, timeout: float | None = None) -> M:  # noqa: ASYNC109
        """The latest message, waiting for the first one if none came yet."""
        async with asyncio.timeout(timeout):
            await self._first.wait()
        assert self.latest is not None
        return self.latest

    def bind(self, undeclare: Callable[[], None]) -> None:
        self._undeclare = undeclare

    def close(self) -> None:
        self._undeclare()
        self._undeclare = lambda: None
        self._closed = True
        self._errors.flush()
        self._wake()
        on_close, self.on_close = self.on_close, None
        if on_close is not None:
            on_close()


def declare_subscription(
    session: zenoh.Session,
    bridge: LoopBridge,
    key: str,
    model: type[M],
    *,
    callback_fn: Callable[[M], object] | None,
    latched: bool,
    queue_size: int,
) -> Subscription[M]:
    sub = Subscription(key, model, bridge, callback_fn, queue_size)
    bind_subscriber(session, key, sub, latched=latched)
    return sub


def bind_subscriber(
    session: zenoh.Session, key: str, sub: Subscription[M], *, latched: bool
) -> None:
    """Declare ``sub.on_sample`` on ``key`` (with a latched publisher's last value)."""
    handler = callback(sub.on_sample)
    if latched:
        advanced = zenoh.ext.declare_advanced_subscriber(session, key, handler, history=_latched())
        sub.bind(advanced.undeclare)
    else:
        plain = session.declare_subscriber(key, handler)
        sub.bind(plain.undeclare)


def bind_ring(session: zenoh.Session, key: str, newest: Latest[M], *, latched: bool) -> None:
    """Subscribe ``newest`` on ``key`` into a Zenoh ring of its ``keep`` samples (with a
    latched publisher's last value): no Python runs per message."""
    ring: zenoh.handlers.RingChannel[zenoh.Sample] = zenoh.handlers.RingChannel(newest.keep)
    if latched:
        advanced = zenoh.ext.declare_advanced_subscriber(session, key, ring, history=_latched())
        newest.bind(advanced.handler, advanced.undeclare)
    else:
        plain = session.declare_subscriber(key, ring)
        newest.bind(plain.handler, plain.undeclare)


def _latched() -> zenoh.ext.HistoryConfig:
    return zenoh.ext.HistoryConfig(detect_late_publishers=True, max_samples=1)
