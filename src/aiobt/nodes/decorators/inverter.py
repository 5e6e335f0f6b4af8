"""Inverter: swap SUCCESS and FAILURE."""

from __future__ import annotations

from aiobt.core.composite import DecoratorNode
from aiobt.core.status import Status

RUNNING, SUCCESS, FAILURE, IDLE = Status.RUNNING, Status.SUCCESS, Status.FAILURE, Status.IDLE


class Inverter(DecoratorNode):
    """``<Inverter>``: SUCCESS becomes FAILURE and back; RUNNING and SKIPPED pass."""

    __slots__ = ()

    async def execute(self) -> Status:
        self._set_status(RUNNING)
        status = await self.tick_child()
        if status is SUCCESS:
            await self.reset_child()
            return FAILURE
        if status is FAILURE:
            await self.reset_child()
            return SUCCESS
        if status is IDLE:
            raise self.logic_error("child returned IDLE")
        return status
