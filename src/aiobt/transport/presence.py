"""Liveliness-based presence: is a server (or any process's token) there right now?"""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import Callable

import zenoh

from aiobt.transport import _z
from aiobt.transport.bridge import LoopBridge, callback


class Presence:
    """Watches liveliness tokens on one key: ``present`` while at least one is alive.

    ``on_change`` listeners are called in the loop with the new state.
    """

    def __init__(self, session: zenoh.Session, bridge: LoopBridge, key: str) -> None:
        self.key = key
        self._alive: set[str] = set()
        self.seen = False  # a token was alive at some point
        self._event = asyncio.Event()
        self._listeners: list[Callable[[bool], None]] = []
        self._bridge = bridge  # before declaring: history samples may arrive at once
        self._sub = session.liveliness().declare_subscriber(
            key, callback(self._on_sample), history=True
        )

    def _on_sample(self, sample: zenoh.Sample) -> None:
        alive = sample.kind == zenoh.SampleKind.PUT
        self._bridge.call(self._update, str(sample.key_expr), alive)

    def _update(self, token: str, alive: bool) -> None:
        was = self.present
        if alive:
            self._alive.add(token)
            self.seen = True
        else:
            self._alive.discard(token)
        if self.present:
            self._event.set()
        else:
            self._event.clear()
        if was != self.present:
            for listener in list(self._listeners):
                listener(self.present)

    @property
    def present(self) -> bool:
        return bool(self._alive)

    @property
    def lost(self) -> bool:
        """Seen alive before, and no token alive now (killed, stopped, restarting)."""
        return self.seen and not self._alive

    async def wait(self, timeout: float | None) -> bool:  # noqa: ASYNC109
        """True once present (at once if already), False if ``timeout`` passes first."""
        if self.present:
            return True
        with contextlib.suppress(TimeoutError):
            async with asyncio.timeout(timeout):
                await self._event.wait()
        return self.present

    def add_listener(self, listener: Callable[[bool], None]) -> None:
        self._listeners.append(listener)

    def remove_listener(self, listener: Callable[[bool], None]) -> None:
        with contextlib.suppress(ValueError):
            self._listeners.remove(listener)

    def close(self) -> None:
        self._listeners.clear()
        _z.undeclare(self._sub)
