"""Parallel: tick every child each tick; finish on success/failure counts."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import ControlNode
from aiobt.core.node import TreeNode
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status


def threshold(value: int, children: int) -> int:
    """BT.CPP's thresholds: a negative count is counted from the end (-1: all)."""
    return max(children + value + 1, 0) if value < 0 else value


class ParallelBase(ControlNode):
    """What Parallel and ParallelAll share: the children that finished, the failures."""

    __slots__ = ("_completed", "_failures")

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._completed: set[int] = set()
        self._failures = 0

    def _tick_pending(self, index: int, child: TreeNode) -> Status:
        """Tick a child that has not finished yet, and note if it finishes now."""
        status = child.tick_sync()
        if status is SUCCESS:
            self._completed.add(index)
        elif status is FAILURE:
            self._completed.add(index)
            self._failures += 1
        elif status is IDLE:
            raise self.logic_error(f"child {child.path} returned IDLE")
        return status

    def _finish(self, status: Status) -> Status:
        self.on_halt_sync()
        return status

    def on_halt_sync(self) -> None:
        self._completed.clear()
        self._failures = 0
        self.reset_children()


class Parallel(ParallelBase):
    """``<Parallel success_count="-1" failure_count="1">``.

    Ticks every child that has not finished yet, in order, and checks the
    thresholds after each one (so later children may wait a tick):

    - SUCCESS once ``success_count`` children succeeded (negative counts from
      the number of children: -1 is all; skipped children count towards -1);
    - FAILURE once failures reach ``failure_count``, or success became impossible;
    - on finishing, every child is reset (RUNNING ones halted);
    - SKIPPED if every child was skipped; a threshold larger than the number of
      children is a logic error at the first tick.
    """

    __slots__ = ()
    PORTS = (
        input_port("success_count", int, -1, "number of children that must succeed (-1: all)"),
        input_port("failure_count", int, 1, "number of children that must fail (-1: all)"),
    )

    def execute_sync(self) -> Status:
        success_count: int = self.get_input("success_count")
        failure_count: int = self.get_input("failure_count")
        count = len(self.children)
        required_success = threshold(success_count, count)
        required_failure = threshold(failure_count, count)
        if count < required_success:
            raise self.logic_error(
                "number of children is less than success_count: can never succeed"
            )
        if count < required_failure:
            raise self.logic_error("number of children is less than failure_count: can never fail")
        self._set_status(RUNNING)
        skipped = 0
        completed = self._completed
        for index, child in enumerate(self.children):
            if index not in completed and self._tick_pending(index, child) is SKIPPED:
                skipped += 1
            failures = self._failures
            successes = len(completed) - failures
            if successes >= required_success or (
                success_count < 0 and successes + skipped >= required_success
            ):
                return self._finish(SUCCESS)
            if count - failures < required_success or failures == required_failure:
                return self._finish(FAILURE)
        return SKIPPED if skipped == count else RUNNING
