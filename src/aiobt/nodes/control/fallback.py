"""Fallback and AsyncFallback: tick children in order until one succeeds."""

from __future__ import annotations

from typing import Any, ClassVar

from aiobt.core.composite import ControlNode, reset_finished
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
        own = self._status
        if own is not RUNNING:
            if own is IDLE:
                self._skipped = 0
            self._set_status(RUNNING)
        children = self.children
        count = len(children)
        yields = self.YIELDS
        current = self._current  # a local copy, written through on every change
        previous = IDLE
        while current < count:
            child = children[current]
            if yields:
                previous = child._status
            # inlined child.tick(): one coroutine frame per async child, none per sync one
            if child.is_sync:
                status = child.tick_sync()
            elif child._conditions is None:
                status = await child.execute()
                if status is not SKIPPED and status is not child._status:
                    child._set_status(status)
                current = self._current  # as it may be after the await
            else:
                status = await child.tick()
                current = self._current
            if status is RUNNING:
                return RUNNING
            if status is SUCCESS:
                if not reset_finished(children):
                    await self.reset_children()
                self._current = 0
                return SUCCESS
            if status is FAILURE:
                current += 1
                self._current = current
                if yields and previous is IDLE and current < count:
                    self.emit_wake_up()
                    return RUNNING
            elif status is SKIPPED:
                current += 1
                self._current = current
                self._skipped += 1
            else:
                raise self.logic_error(f"child {child.path} returned IDLE")
        all_skipped = self._skipped == count
        if not reset_finished(children):
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
