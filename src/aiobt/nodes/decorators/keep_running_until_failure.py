"""KeepRunningUntilFailure: restart the child after each success."""

from __future__ import annotations

from aiobt.core.composite import DecoratorNode
from aiobt.core.status import FAILURE, RUNNING, SUCCESS, Status


class KeepRunningUntilFailure(DecoratorNode):
    """``<KeepRunningUntilFailure>``: RUNNING after the child succeeds (it is
    reset and ticked again next time), FAILURE when it fails. A SKIPPED child
    also gives RUNNING, as in BT.CPP."""

    __slots__ = ()

    def execute_sync(self) -> Status:
        self._set_status(RUNNING)
        status = self.tick_child()
        if status is SUCCESS:
            self.reset_child()
            return RUNNING
        if status is FAILURE:
            self.reset_child()
            return FAILURE
        return RUNNING
