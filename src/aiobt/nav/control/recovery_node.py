"""RecoveryNode (Nav2): an action and its recovery, retried a number of times."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import ControlNode
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, RUNNING, SKIPPED, SUCCESS, Status


class RecoveryNode(ControlNode):
    """``<RecoveryNode number_of_retries="1">`` (Nav2), exactly two children.

    - first child SUCCESS: reset, SUCCESS; RUNNING: RUNNING; SKIPPED: reset,
      SKIPPED;
    - first child FAILURE: if fewer than ``number_of_retries`` recoveries have
      succeeded, the second child is ticked in the same tick; else reset,
      FAILURE;
    - second child SUCCESS: one retry used, the first child is ticked again in
      the same tick; RUNNING: RUNNING; FAILURE: reset, FAILURE; SKIPPED:
      FAILURE without using a retry (no recovery is possible).

    Having other than two children is a load error (Nav2 throws at the first
    tick).
    """

    __slots__ = ("_current", "_retries")
    MIN_CHILDREN = 2
    MAX_CHILDREN = 2
    PORTS = (input_port("number_of_retries", int, 1, "Number of retries."),)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._current = 0
        self._retries = 0

    def execute_sync(self) -> Status:
        limit: int = self.get_input("number_of_retries")
        if len(self.children) != 2:
            raise self.logic_error("RecoveryNode must have exactly 2 children")
        self._set_status(RUNNING)
        while self._retries <= limit:
            child = self.children[self._current]
            status = child.tick_sync()
            if status is RUNNING:
                return RUNNING
            if status is not SUCCESS and status is not FAILURE and status is not SKIPPED:
                raise self.logic_error(f"child {child.path} returned {status.name}")
            outcome = self._first(status, limit) if self._current == 0 else self._second(status)
            if outcome is not None:
                return outcome
        self.on_halt_sync()
        return FAILURE

    def _first(self, status: Status, limit: int) -> Status | None:
        if status is FAILURE and self._retries < limit:
            self.halt_child(0)
            self._current = 1
            return None
        self.on_halt_sync()
        return status

    def _second(self, status: Status) -> Status | None:
        if status is SUCCESS:
            self.halt_child(1)
            self._retries += 1
            self._current = 0
            return None
        if status is SKIPPED:
            self._current = 0
            self.halt_child(1)
            return FAILURE
        self.on_halt_sync()
        return FAILURE

    def on_halt_sync(self) -> None:
        self._current = self._retries = 0
        self.reset_children()
