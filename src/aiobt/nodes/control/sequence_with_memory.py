"""SequenceWithMemory: a Sequence that does not start over after a failure."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import ControlNode
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status


class SequenceWithMemory(ControlNode):
    """``<SequenceWithMemory>`` (v3: SequenceStar).

    - like Sequence, but a FAILURE halts the children from the failed one on
      and keeps the index: the next tick resumes at the failed child;
    - the index also survives halts (BT.CPP behaviour);
    - after a child that started from IDLE succeeds, it returns RUNNING and
      asks for a wake-up, so each child gets its own tick.
    """

    __slots__ = ("_current", "_skipped")

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._current = 0
        self._skipped = 0

    def execute_sync(self) -> Status:
        if self._status is IDLE:
            self._skipped = 0
        self._set_status(RUNNING)
        children = self.children
        count = len(children)
        while self._current < count:
            child = children[self._current]
            previous = child._status
            status = child.tick_sync()
            if status is RUNNING:
                return RUNNING
            if status is FAILURE:
                self.halt_children_from(self._current)
                return FAILURE
            if status is SUCCESS:
                self._current += 1
                if previous is IDLE and self._current < count:
                    self.emit_wake_up()
                    return RUNNING
            elif status is SKIPPED:
                self._current += 1
                self._skipped += 1
            else:
                raise self.logic_error(f"child {child.path} returned IDLE")
        all_skipped = self._skipped == count
        self.reset_children()
        self._current = self._skipped = 0
        return SKIPPED if all_skipped else SUCCESS
