"""IfThenElse: a condition child chooses the then- or else-branch."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import ControlNode
from aiobt.core.status import FAILURE, RUNNING, SUCCESS, Status


class IfThenElse(ControlNode):
    """``<IfThenElse>`` with 2 or 3 children: if, then, else.

    - the first child is ticked until it finishes (it is not re-checked while
      a branch runs: use WhileDoElse for that);
    - SUCCESS: the second child's result; FAILURE: the third child's result,
      or FAILURE when there is no third child (the condition keeps its status
      until the next completion resets it, as in BT.CPP);
    - a SKIPPED condition, or other than 2 or 3 children, is a logic error at tick.
    """

    __slots__ = ("_branch",)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._branch = 0

    def execute_sync(self) -> Status:
        children = self.children
        if len(children) not in (2, 3):
            raise self.logic_error(f"IfThenElse must have 2 or 3 children, it has {len(children)}")
        self._set_status(RUNNING)
        if self._branch == 0:
            condition = children[0]
            status = condition.tick_sync()
            if status is RUNNING:
                return RUNNING
            if status is SUCCESS:
                self._branch = 1
            elif status is FAILURE:
                if len(children) == 2:
                    return FAILURE
                self._branch = 2
            else:
                raise self.logic_error(f"condition {condition.path} returned {status.name}")
        branch = children[self._branch]
        status = branch.tick_sync()
        if status is RUNNING:
            return RUNNING
        self.reset_children()
        self._branch = 0
        return status

    def on_halt_sync(self) -> None:
        self._branch = 0
        self.reset_children()
