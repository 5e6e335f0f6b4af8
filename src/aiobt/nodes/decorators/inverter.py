"""Inverter: swap SUCCESS and FAILURE."""

from __future__ import annotations

from aiobt.core.composite import DecoratorNode, reset_if_finished
from aiobt.core.status import Status

RUNNING, SUCCESS, FAILURE, IDLE = Status.RUNNING, Status.SUCCESS, Status.FAILURE, Status.IDLE
SKIPPED = Status.SKIPPED


class Inverter(DecoratorNode):
    """``<Inverter>``: SUCCESS becomes FAILURE and back; RUNNING and SKIPPED pass."""

    __slots__ = ()

    async def execute(self) -> Status:
        if self._status is not RUNNING:
            self._set_status(RUNNING)
        child = self.child
        assert child is not None
        # inlined self.tick_child() and child.tick(): no coroutine frame of their own
        if child.is_sync:
            status = child.tick_sync()
        elif child._conditions is None:
            status = await child.execute()
            if status is not SKIPPED and status is not child._status:
                child._set_status(status)
        else:
            status = await child.tick()
        if status is SUCCESS:
            if not reset_if_finished(child):
                await self.reset_child()
            return FAILURE
        if status is FAILURE:
            if not reset_if_finished(child):
                await self.reset_child()
            return SUCCESS
        if status is IDLE:
            raise self.logic_error("child returned IDLE")
        return status
