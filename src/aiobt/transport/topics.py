"""Typed topics: publishers, latched publishers (late joiners get the last value), subscriptions."""

from __future__ import annotations

import asyncio
import logging
from collections import deque
from collections.abc import Callable
from typing import Generic, Self, TypeVar

import zenoh
import zenoh.ext
from pydantic import ValidationError

from aiobt.msgs import MessageError, Msg, wire_validator
from aiobt.transport import _z
from aiobt.transport.bridge import JSON, LoopBridge, PayloadTooLarge, callback

M = TypeVar("M", bound=Msg)
_PUT = zenoh.SampleKind.PUT
log = logging.getLogger("aiobt.transport.topics")


class Publisher(Generic[M]):
    """``put(msg)`` publishes one message of ``model`` on ``key``."""

    def __init__(
        self,
        zpub: zenoh.Publisher | zenoh.ext.AdvancedPublisher,
        key: str,
        model: type[M],
        bridge: LoopBridge,
    ) -> None:
        self.key = key
        self.model = model
        self._pub = zpub
        self._bridge = bridge
        self._closed = False

    def put(self, message: M) -> None:
        if not isinstance(message, self.model):
            raise TypeError(f"{self.key}: expected {self.model.__name__}, got {type(message)}")
        payload = message.to_json()
        self._bridge.check_size(self.key, payload)
        self._pub.put(payload)

    @property
    def matched(self) -> bool:
        """Whether a subscriber is known to match (plain publishers only; else True)."""
        if isinstance(self._pub, zenoh.Publisher):
            return _z.matching(self._pub.matching_status)
        return True

    async def wait_for_subscribers(self, timeout: float) -> bool:  # noqa: ASYNC109
        """Wait until a subscriber matches, so that a first message is not lost; False if
        none did within ``timeout`` seconds (as ``ActionClient.wait_for_server``)."""
        try:
            async with asyncio.timeout(timeout):
                while not self.matched:  # noqa: ASYNC110 - zenoh's matching listener is a thread
                    await asyncio.sleep(0.01)
        except TimeoutError:
            return False
        return True

    def close(self) -> None:
        """Undeclare the publisher (idempotent: the bus closes it again on exit)."""
        if self._closed:
            return
        self._closed = True
        _z.undeclare(self._pub)


def declare_publisher(
    session: zenoh.Session, bridge: LoopBridge, key: str, model: type[M], *, reliable: bool
) -> Publisher[M]:
    congestion = zenoh.CongestionControl.BLOCK if reliable else zenoh.CongestionControl.DROP
    zpub = session.declare_publisher(key, encoding=JSON, congestion_control=congestion)
    return Publisher(zpub, key, model, bridge)


def declare_latched_publisher(
    session: zenoh.Session, bridge: LoopBridge, key: str, model: type[M]
) -> Publisher[M]:
    zpub = zenoh.ext.declare_advanced_publisher(
        session,
        key,
        encoding=JSON,
        congestion_control=zenoh.CongestionControl.BLOCK,
        cache=zenoh.ext.CacheConfig(1),
        publisher_detection=True,
    )
    return Publisher(zpub, key, model, bridge)


class Subscription(Generic[M]):
    """Messages of ``model`` on ``key``: an async iterator, ``latest``, or a callback.

    A malformed payload is logged once per key and field, then dropped. With a
    ``callback``, it is called in the event loop for every message (a sync
    function; exceptions are logged) and nothing is queued.
    """

    def __init__(
        self,
        key: str,
        model: type[M],
        bridge: LoopBridge,
        callback: Callable[[M], object] | None,
        queue_size: int,
    ) -> None:
        self.key = key
        self.model = model
        self.latest: M | None = None
        self.received = 0
        self.dropped_invalid = 0
        self.dropped_overflow = 0  # oldest messages pushed out of a full queue
        self._bridge = bridge
        self._callback = callback
        self._validate_json = wire_validator(model)
        self._max_payload = bridge.max_payload
        # a bounded deque (oldest dropped) and the waiting readers' futures: leaner than
        # an asyncio.Queue on this per-message path
        self._queue: deque[M] = deque(maxlen=queue_size if queue_size > 0 else None)
        self._waiters: list[asyncio.Future[None]] = []
        self._closed = False
        self._reported: set[str] = set()
        self._first = asyncio.Event()
        self._undeclare: Callable[[], None] = lambda: None

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
        try:
            message = self._validate_json(payload)
        except ValidationError as exc:
            if sample.kind == _PUT:  # errors name the key (it has no wildcards)
                error = MessageError.from_validation(self.model, exc, self.key)
                self._bridge.call(self._reject, error)
            return
        self._bridge.call(self._deliver, message)

    def _reject(self, exc: MessageError | PayloadTooLarge) -> None:
        self.dropped_invalid += 1
        tag = exc.field if isinstance(exc, MessageError) else "<size>"
        if tag in self._reported:
            log.debug("dropped bad message: %s", exc)
            return
        self._reported.add(tag)
        log.warning("dropped bad message (reported once per field): %s", exc)

    def _deliver(self, message: M) -> None:
        self.latest = message
        if not self.received:
            self._first.set()
        self.received += 1
        if self._callback is not None:
            try:
                self._callback(message)
            except Exception:
                log.exception("%s: subscriber callback failed", self.key)
            return
        if self._closed:
            return
        queue = self._queue
        if len(queue) == queue.maxlen:
            self._overflow()
        queue.append(message)  # full: the oldest is dropped
        self._wake()

    def _overflow(self) -> None:
        self.dropped_overflow += 1
        if self.dropped_overflow == 1:
            log.warning(
                "%s: the reader falls behind; the queue of %d is full and the oldest "
                "messages are dropped (reported once; see dropped_overflow)",
                self.key,
                self._queue.maxlen,
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
        self._wake()


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
    handler = callback(sub.on_sample)
    if latched:
        history = zenoh.ext.HistoryConfig(detect_late_publishers=True, max_samples=1)
        advanced = zenoh.ext.declare_advanced_subscriber(session, key, handler, history=history)
        sub.bind(advanced.undeclare)
    else:
        plain = session.declare_subscriber(key, handler)
        sub.bind(plain.undeclare)
    return sub
