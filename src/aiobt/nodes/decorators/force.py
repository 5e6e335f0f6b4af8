"""ForceSuccess and ForceFailure: replace the child's result."""

from __future__ import annotations

from typing import ClassVar

from aiobt.core.composite import DecoratorNode
from aiobt.core.status import FAILURE, RUNNING, SUCCESS, Status


class ForceSuccess(DecoratorNode):
    """``<ForceSuccess>``: a finished child gives SUCCESS; RUNNING and SKIPPED pass."""

    __slots__ = ()
    RESULT: ClassVar[Status] = SUCCESS

    def execute_sync(self) -> Status:
        self._set_status(RUNNING)
        status = self.tick_child()
        if status.is_completed:
            self.reset_child()
            return self.RESULT
        return status


class ForceFailure(ForceSuccess):
    """``<ForceFailure>``: a finished child gives FAILURE; RUNNING and SKIPPED pass."""

    __slots__ = ()
    RESULT = FAILURE
