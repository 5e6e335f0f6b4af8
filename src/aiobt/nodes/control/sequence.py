"""Sequence and AsyncSequence: tick children in order until one fails."""

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


class Sequence(ControlNode):
    """``<Sequence>`` (AND): tick children in order.

    - a child RUNNING: RUNNING, and the same child is ticked next time;
    - a child FAILURE: reset all children, start over next time, FAILURE;
    - every child SUCCESS (or SKIPPED): reset, SUCCESS (SKIPPED if all skipped).
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
            if status is SUCCESS:
                current += 1
                self._current = current
                if yields and previous is IDLE and current < count:
                    self.emit_wake_up()
                    return RUNNING
                continue
            if status is RUNNING:
                return RUNNING
            if status is FAILURE:
                if not reset_finished(children):
                    await self.reset_children()
                self._current = 0
                return FAILURE
            if status is SKIPPED:
                current += 1
                self._current = current
                self._skipped += 1
            else:
                raise self.logic_error(f"child {child.path} returned IDLE")
        all_skipped = self._skipped == count
        if not reset_finished(children):
            await self.reset_children()
        self._current = self._skipped = 0
        return SKIPPED if all_skipped else SUCCESS

    async def on_halt(self) -> None:
        self._current = self._skipped = 0
        await self.reset_children()


class AsyncSequence(Sequence):
    """``<AsyncSequence>``: a Sequence that returns RUNNING (and asks for a
    wake-up) after each child that finished in the tick it started, so long
    chains of instant children stay interruptible."""

    __slots__ = ()
    YIELDS = True
