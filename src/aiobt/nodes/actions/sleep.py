"""Sleep: RUNNING for some milliseconds of clock time, then SUCCESS."""

from __future__ import annotations

from aiobt.core.leaves import AsyncActionNode
from aiobt.core.ports import input_port
from aiobt.core.status import Status


class Sleep(AsyncActionNode):
    """``<Sleep msec="N"/>``: SUCCESS after N ms of the tree's clock (at once if
    N <= 0); the tree is woken when the time is up; halting cancels the wait."""

    __slots__ = ()
    PORTS = (input_port("msec", int, required=True),)

    async def run(self) -> Status:
        msec: int = self.get_input("msec")
        if msec > 0:
            await self.clock.sleep(msec / 1000.0)
        return Status.SUCCESS
