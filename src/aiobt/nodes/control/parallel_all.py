"""ParallelAll: tick every child until all have finished."""

from __future__ import annotations

from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, RUNNING, SKIPPED, SUCCESS, Status
from aiobt.nodes.control.parallel import ParallelBase, threshold


class ParallelAll(ParallelBase):
    """``<ParallelAll max_failures="1">``: run every child to completion.

    When all children have finished (or were skipped) it returns FAILURE if at
    least ``max_failures`` of them failed, else SUCCESS (so ``max_failures=0``
    always fails, as in BT.CPP; negative counts from the end, -1 is all).
    SKIPPED if every child was skipped.
    """

    __slots__ = ()
    PORTS = (
        input_port(
            "max_failures",
            int,
            1,
            "if the number of children returning FAILURE reaches this value, "
            "ParallelAll returns FAILURE (-1: all)",
        ),
    )

    def execute_sync(self) -> Status:
        count = len(self.children)
        max_failures = threshold(self.get_input("max_failures"), count)
        if count < max_failures:
            raise self.logic_error("number of children is less than max_failures: can never fail")
        self._set_status(RUNNING)
        skipped = 0
        completed = self._completed
        for index, child in enumerate(self.children):
            if index not in completed and self._tick_pending(index, child) is SKIPPED:
                skipped += 1
        if skipped == count:
            return SKIPPED
        if skipped + len(completed) < count:
            return RUNNING
        return self._finish(FAILURE if self._failures >= max_failures else SUCCESS)
