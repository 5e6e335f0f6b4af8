"""Typed publishers, and latched ones (late joiners get the last value)."""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from typing import Any, Generic, TypeVar

import zenoh
import zenoh.ext

from aiobt.msgs import Msg
from aiobt.transport import _z
from aiobt.transport.bridge import JSON, LoopBridge, callback

M = TypeVar("M", bound=Msg)


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
        self._listeners: list[Any] = []

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

    def on_matching_change(self, fn: Callable[[], object]) -> None:
        """Call ``fn()`` in the event loop whenever subscribers start or stop matching
        (a Zenoh matching listener: nothing runs while it stays the same; plain
        publishers only). ``fn`` reads :attr:`matched` for the state now."""
        if not isinstance(self._pub, zenoh.Publisher):
            raise TypeError(f"{self.key}: a latched publisher always counts as matched")

        def changed(_status: zenoh.MatchingStatus) -> None:  # Zenoh thread
            self._bridge.call(fn)

        self._listeners.append(self._pub.declare_matching_listener(callback(changed)))

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
        for listener in self._listeners:
            _z.undeclare(listener)
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
