"""Delay: wait some time before ticking the child."""

from __future__ import annotations

import asyncio
from typing import Any

from aiobt.core.composite import DecoratorNode
from aiobt.core.ports import input_port
from aiobt.core.status import RUNNING, Status


class Delay(DecoratorNode):
    """``<Delay delay_msec="N">``: RUNNING for N ms of clock time, then the
    child is ticked until it finishes (and the delay starts again on the next
    activation). The elapsed delay wakes the tree; ``delay_msec=0`` ticks the
    child at once."""

    __slots__ = ("_done", "_started", "_timer")
    PORTS = (
        input_port(
            "delay_msec", int, description="tick the child after a few milliseconds", required=True
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._started = False
        self._done = False
        self._timer: asyncio.Task[None] | None = None

    async def _wait(self, deadline: float) -> None:
        # the deadline is fixed at the tick: the task may first run after time moved
        await self.clock.sleep(deadline - self.clock.now())
        self._done = True
        self.emit_wake_up()

    def execute_sync(self) -> Status:
        msec: int = self.get_input("delay_msec")
        if not self._started:
            self._started = True
            self._set_status(RUNNING)
            self._done = msec <= 0
            if not self._done:
                self._timer = asyncio.ensure_future(self._wait(self.clock.now() + msec / 1000.0))
        if not self._done:
            return RUNNING
        status = self.tick_child()
        if status.is_completed:
            self._started = self._done = False
            self._timer = None
            self.reset_child()
        return status

    def on_halt_sync(self) -> None:
        self._started = self._done = False
        timer, self._timer = self._timer, None
        if timer is not None:
            timer.cancel()
        self.reset_child()
