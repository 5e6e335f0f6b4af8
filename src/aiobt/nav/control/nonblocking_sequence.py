"""NonblockingSequence (Nav2): tick every child each tick, running or not."""

from __future__ import annotations

from aiobt.core.composite import ControlNode
from aiobt.core.status import FAILURE, RUNNING, SKIPPED, SUCCESS, Status


class NonblockingSequence(ControlNode):
    """``<NonblockingSequence>`` (Nav2): a sequence that never waits on a child.

    - every tick ticks all children in order, whether an earlier one is
      RUNNING or not;
    - a child FAILURE: halt every child, FAILURE (later children not ticked);
    - every child SUCCESS in the same tick: halt every child, SUCCESS;
    - otherwise RUNNING.

    Nav2 throws on a SKIPPED child; here it counts as a success.
    """

    __slots__ = ()

    def execute_sync(self) -> Status:
        all_done = True
        for child in self.children:
            status = child.tick_sync()
            if status is FAILURE:
                self.reset_children()
                return FAILURE
            if status is RUNNING:
                all_done = False
            elif status is not SUCCESS and status is not SKIPPED:
                raise self.logic_error(f"child {child.path} returned {status.name}")
        if all_done:
            self.reset_children()
            return SUCCESS
        return RUNNING
