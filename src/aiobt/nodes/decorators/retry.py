"""RetryUntilSuccessful: tick the child again after each failure."""

from __future__ import annotations

from typing import Any, ClassVar

from aiobt.core.composite import DecoratorNode, reset_if_finished
from aiobt.core.ports import input_port
from aiobt.core.status import Status

IDLE, RUNNING, SUCCESS, FAILURE, SKIPPED = (
    Status.IDLE,
    Status.RUNNING,
    Status.SUCCESS,
    Status.FAILURE,
    Status.SKIPPED,
)


class RetryUntilSuccessful(DecoratorNode):
    """``<RetryUntilSuccessful num_attempts="N">``: up to N attempts (-1: forever).

    SUCCESS as soon as the child succeeds; FAILURE after N failures (N=0 fails
    without ticking). After an attempt that started and failed within one
    tick, it returns RUNNING and asks for a wake-up, so the tree stays
    interruptible between attempts. A SKIPPED child makes it SKIPPED.
    """

    __slots__ = ("_count",)
    PORTS = (
        input_port(
            "num_attempts",
            int,
            description="execute again a failing child up to N times; -1 loops forever",
            required=True,
        ),
    )
    LIMIT_PORT: ClassVar[str] = "num_attempts"
    AGAIN: ClassVar[Status] = FAILURE  # the child result that triggers another run

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._count = 0

    async def execute(self) -> Status:
        limit: int = self.get_input(self.LIMIT_PORT)
        again = self.AGAIN
        finished = SUCCESS if again is FAILURE else FAILURE
        loop = self._count < limit or limit == -1
        if self._status is not RUNNING:
            self._set_status(RUNNING)
        child = self.child
        assert child is not None
        while loop:
            previous = child._status
            # inlined child.tick(): one coroutine frame per async child, none per sync one
            if child.is_sync:
                status = child.tick_sync()
            elif child._conditions is None:
                status = await child.execute()
                if status is not SKIPPED and status is not child._status:
                    child._set_status(status)
            else:
                status = await child.tick()
            if status is again:
                self._count += 1
                loop = self._count < limit or limit == -1
                await self.reset_child()
                if previous is IDLE and loop:
                    self.emit_wake_up()
                    return RUNNING
            elif status is finished:
                self._count = 0
                if not reset_if_finished(child):
                    await self.reset_child()
                return finished
            elif status is RUNNING:
                return RUNNING
            elif status is SKIPPED:
                await self.reset_child()
                return SKIPPED
            else:
                raise self.logic_error("child returned IDLE")
        self._count = 0
        return again

    async def on_halt(self) -> None:
        self._count = 0
        await self.reset_child()
