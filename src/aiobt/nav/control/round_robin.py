"""RoundRobin (Nav2): each activation resumes at the child after the last one tried."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import ControlNode
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, RUNNING, SKIPPED, SUCCESS, Status


class RoundRobin(ControlNode):
    """``<RoundRobin wrap_around="false">`` (Nav2), as Nav2 main's ``round_robin_node.cpp``.

    - ticks the current child; RUNNING: RUNNING;
    - SUCCESS: the next activation starts at the following child; reset all
      children, SUCCESS;
    - FAILURE (or SKIPPED): the following child is ticked in the same tick;
      once every child failed in a row (failures count across activations, until
      a success or a halt): reset, FAILURE; every child SKIPPED in this tick:
      SKIPPED.

    ``wrap_around`` (Nav2 Kilted+, default false): without it the node does not go
    back to the first child after the last one. Nav2's quirk, matched here: once
    the last child has returned, whatever it returned, the node resets and
    returns FAILURE (SKIPPED if every child of this tick was skipped), even when
    the last child succeeded or the round started mid-way; the next activation
    starts over at the first child. With ``wrap_around="true"`` it rotates forever
    (Nav2's old behaviour). A halt also starts over at the first child.
    """

    __slots__ = ("_current", "_failed")
    PORTS = (
        input_port(
            "wrap_around",
            bool,
            False,
            "Controls wrap-around behavior. When `false`, the node returns FAILURE instead "
            "of wrapping to the first child after all children have been attempted. When "
            "`true`, the node wraps around to the first child and continues the round-robin "
            "behavior.",
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._current = 0
        self._failed = 0

    def execute_sync(self) -> Status:
        wrap: bool = self.get_input("wrap_around")
        count = len(self.children)
        self._set_status(RUNNING)
        skipped = 0
        while self._failed + skipped < count:
            child = self.children[self._current]
            status = child.tick_sync()
            if status is RUNNING:
                return RUNNING
            if status not in (SUCCESS, FAILURE, SKIPPED):
                raise self.logic_error(f"child {child.path} returned {status.name}")
            self._current += 1
            if self._current == count:
                if not wrap:  # the end of the round: FAILURE, whatever the child said
                    skipped += status is SKIPPED
                    break
                self._current = 0
            if status is SUCCESS:
                self._failed = 0
                self.reset_children()
                return SUCCESS
            if status is FAILURE:
                self._failed += 1
            else:
                skipped += 1
        self.on_halt_sync()
        return SKIPPED if skipped == count else FAILURE

    def on_halt_sync(self) -> None:
        self._current = self._failed = 0
        self.reset_children()
