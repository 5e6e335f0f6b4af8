"""ParallelAll: tick every child until all have finished."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import ControlNode
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status
from aiobt.nodes.control.parallel import threshold


class ParallelAll(ControlNode):
    """``<ParallelAll max_failures="1">``: run every child to completion.

    When all children have finished (or were skipped) it returns FAILURE if at
    least ``max_failures`` of them failed, else SUCCESS (so ``max_failures=0``
    always fails, as in BT.CPP; negative counts from the end, -1 is all).
    SKIPPED if every child was skipped.
    """

    __slots__ = ("_completed", "_failures")
    PORTS = (
        input_port(
            "max_failures",
            int,
            1,
            "if the number of children returning FAILURE reaches this value, "
            "ParallelAll returns FAILURE (-1: all)",
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._completed: set[int] = set()
        self._failures = 0

    def execute_sync(self) -> Status:
        count = len(self.children)
        max_failures = threshold(self.get_input("max_failures"), count)
        if count < max_failures:
            raise self.logic_error("number of children is less than max_failures: can never fail")
        self._set_status(RUNNING)
        skipped = 0
        completed = self._completed
        for index, child in enumerate(self.children):
            if index in completed:
                continue
            status = child.tick_sync()
            if status is SUCCESS:
                completed.add(index)
            elif status is FAILURE:
                completed.add(index)
                self._failures += 1
            elif status is SKIPPED:
                skipped += 1
            elif status is IDLE:
                raise self.logic_error(f"child {child.path} returned IDLE")
        if skipped == count:
            return SKIPPED
        if skipped + len(completed) < count:
            return RUNNING
        self.reset_children()
        failed = self._failures >= max_failures
        completed.clear()
        self._failures = 0
        return FAILURE if failed else SUCCESS

    def on_halt_sync(self) -> None:
        self._completed.clear()
        self._failures = 0
        self.reset_children()
