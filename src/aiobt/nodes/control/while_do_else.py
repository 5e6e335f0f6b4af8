"""WhileDoElse: a reactive IfThenElse that re-checks its condition every tick."""

from __future__ import annotations

from aiobt.core.composite import ControlNode
from aiobt.core.status import FAILURE, RUNNING, SUCCESS, Status


class WhileDoElse(ControlNode):
    """``<WhileDoElse>`` with 2 or 3 children: while, do, else.

    Every tick the first child is ticked; SUCCESS halts the else-branch and
    ticks the second child, FAILURE halts the do-branch and ticks the third
    (FAILURE when there are two children). When the ticked branch finishes,
    every child is reset. A SKIPPED condition, or other than 2 or 3 children,
    is a logic error at tick.
    """

    __slots__ = ()

    def execute_sync(self) -> Status:
        children = self.children
        count = len(children)
        if count not in (2, 3):
            raise self.logic_error(f"WhileDoElse must have 2 or 3 children, it has {count}")
        self._set_status(RUNNING)
        condition = children[0]
        status = condition.tick_sync()
        if status is RUNNING:
            return RUNNING
        if status is SUCCESS:
            if count == 3:
                self.halt_child(2)
            branch = children[1]
            status = branch.tick_sync()
        elif status is FAILURE:
            if count == 3:
                self.halt_child(1)
                branch = children[2]
                status = branch.tick_sync()
        else:
            raise self.logic_error(f"condition {condition.path} returned {status.name}")
        if status is RUNNING:
            return RUNNING
        self.reset_children()
        return status
