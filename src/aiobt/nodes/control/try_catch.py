"""TryCatch: a Sequence of "try" children with a "catch" child for failures."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import ControlNode
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status


class TryCatch(ControlNode):
    """``<TryCatch catch_on_halt="false">`` with at least two children.

    - the first N-1 children run as a Sequence (RUNNING, SUCCESS/SKIPPED go on);
      all SUCCESS: SUCCESS (SKIPPED if all were skipped);
    - a try child FAILURE: the try children are reset and the last child (the
      catch) is ticked in the same tick until it finishes; then FAILURE,
      whatever the catch returned;
    - halted while in the try block with ``catch_on_halt="true"``: the try
      children are halted and the catch child ticked once (halted if RUNNING).

    BehaviorTree.CPP added TryCatch after 4.8 (its master branch); aiobt follows
    that implementation, so there is no BT.CPP 4.8 reference to compare with.
    """

    __slots__ = ("_current", "_in_catch", "_skipped")
    MIN_CHILDREN = 2
    PORTS = (
        input_port(
            "catch_on_halt",
            bool,
            False,
            "If true, the catch child is also executed when the TryCatch is halted",
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._current = 0
        self._skipped = 0
        self._in_catch = False

    def _tick(self, index: int) -> Status:
        child = self.children[index]
        return child.tick_sync()

    def execute_sync(self) -> Status:
        if not self._status.is_active:
            self._skipped = 0
            self._in_catch = False
        self._set_status(RUNNING)
        if self._in_catch:
            return self._catch()
        try_count = len(self.children) - 1
        while self._current < try_count:
            status = self._tick(self._current)
            if status is RUNNING:
                return RUNNING
            if status is FAILURE:
                self.reset_children()
                self._current = 0
                self._in_catch = True
                return self._catch()
            if status is IDLE:
                raise self.logic_error(f"child {self.children[self._current].path} returned IDLE")
            self._current += 1
            self._skipped += status is SKIPPED
        all_skipped = self._skipped == try_count
        self.reset_children()
        self._current = self._skipped = 0
        return SKIPPED if all_skipped else SUCCESS

    def _catch(self) -> Status:
        status = self._tick(len(self.children) - 1)
        if status is RUNNING:
            return RUNNING
        self.reset_children()
        self._current = 0
        self._in_catch = False
        return FAILURE

    def on_halt_sync(self) -> None:
        catch_on_halt = bool(self.get_input("catch_on_halt", False))
        if catch_on_halt and not self._in_catch and self._status.is_active:
            for index in range(len(self.children) - 1):
                self.halt_child(index)
            last = len(self.children) - 1
            if self._tick(last) is RUNNING:
                self.halt_child(last)
        self._current = self._skipped = 0
        self._in_catch = False
        self.reset_children()
