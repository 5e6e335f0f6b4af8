"""Timeout: halt the child and fail when it runs for too long."""

from __future__ import annotations

import asyncio
from typing import Any

from aiobt.core.composite import DecoratorNode
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, RUNNING, Status


class Timeout(DecoratorNode):
    """``<Timeout msec="N">``: FAILURE if the child still runs N ms (clock time)
    after this node started; the child is halted then. The timer starts at the
    first tick of an activation and wakes the tree when it expires; ``msec=0``
    disables it."""

    __slots__ = ("_expired", "_started", "_timer")
    PORTS = (
        input_port(
            "msec",
            int,
            description="after a certain amount of time, halt() the child if it is still running",
            required=True,
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._started = False
        self._expired = False
        self._timer: asyncio.Task[None] | None = None

    async def _expire(self, deadline: float) -> None:
        # the deadline is fixed at the tick: the task may first run after time moved
        await self.clock.sleep(deadline - self.clock.now())
        child = self.child
        if child is not None and child._status is RUNNING:
            self._expired = True
            self.emit_wake_up()

    def _stop_timer(self) -> None:
        timer, self._timer = self._timer, None
        if timer is not None:
            timer.cancel()

    def execute_sync(self) -> Status:
        msec: int = self.get_input("msec")
        if not self._started:
            self._started = True
            self._expired = False
            self._set_status(RUNNING)
            if msec > 0:
                self._timer = asyncio.ensure_future(self._expire(self.clock.now() + msec / 1000.0))
        if self._expired:
            self._started = self._expired = False
            self._timer = None
            self.reset_child()
            return FAILURE
        status = self.tick_child()
        if status.is_completed:
            self._started = False
            self._stop_timer()
            self.reset_child()
        return status

    def on_halt_sync(self) -> None:
        self._started = self._expired = False
        self._stop_timer()
        self.reset_child()
