"""SingleTrigger (Nav2): let the child run to completion once per activation."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import DecoratorNode
from aiobt.core.status import FAILURE, IDLE, RUNNING, Status


class SingleTrigger(DecoratorNode):
    """``<SingleTrigger>`` (Nav2).

    - armed when ticked while IDLE (its parent reset or halted it);
    - armed: ticks the child and returns its status; once the child finished
      (SUCCESS or FAILURE) it is disarmed and the child is reset;
    - disarmed: FAILURE without ticking the child, until re-armed by a reset.

    A SKIPPED child leaves it armed.
    """

    __slots__ = ("_armed",)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._armed = True

    def execute_sync(self) -> Status:
        if self._status is IDLE:
            self._armed = True
        self._set_status(RUNNING)
        if not self._armed:
            return FAILURE
        status = self.tick_child()
        if status.is_completed:
            self._armed = False
            self.reset_child()
        return status
