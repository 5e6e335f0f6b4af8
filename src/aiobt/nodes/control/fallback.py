"""Fallback and AsyncFallback: tick children in order until one succeeds."""

from __future__ import annotations

from typing import Any, ClassVar

from aiobt.core.composite import ControlNode
from aiobt.core.status import Status

IDLE, RUNNING, SUCCESS, FAILURE, SKIPPED = (
    Status.IDLE,
    Status.RUNNING,
    Status.SUCCESS,
    Status.FAILURE,
    Status.SKIPPED,
)


class Fallback(ControlNode):
    """``<Fallback>`` (OR): tick children in order.

    - a child RUNNING: RUNNING, and the same child is ticked next time;
    - a child SUCCESS: reset all children, SUCCESS;
    - every child FAILURE (or SKIPPED): reset, FAILURE (SKIPPED if all skipped).
    """

    __slots__ = ("_current", "_skipped")
    YIELDS: ClassVar[bool] = False

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._current = 0
        self._skipped = 0

    async def execute(self) -> Status:
        if self._status is IDLE:
            self._skipped = 0
        self._set_status(RUNNING)
        children = self.children
        count = len(children)
        while self._current < count:
            child = children[self._current]
            previous = child._status
            status = child.tick_sync() if child.is_sync else await child.tick()
            if status is RUNNING:
                return RUNNING
            if status is SUCCESS:
                await self.reset_children()
                self._current = 0
                return SUCCESS
            if status is FAILURE:
                self._current += 1
                if self.YIELDS and previous is IDLE and self._current < count:
                    self.emit_wake_up()
                    return RUNNING
            elif status is SKIPPED:
                self._current += 1
                self._skipped += 1
            else:
                raise self.logic_error(f"child {child.path} returned IDLE")
        all_skipped = self._skipped == count
        await self.reset_children()
        self._current = self._skipped = 0
        return SKIPPED if all_skipped else FAILURE

    async def on_halt(self) -> None:
        self._current = self._skipped = 0
        await self.reset_children()


class AsyncFallback(Fallback):
    """``<AsyncFallback>``: a Fallback that yields (RUNNING + wake-up) after
    each child that failed in the tick it started."""

    __slots__ = ()
    YIELDS = True
