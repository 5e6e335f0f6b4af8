"""RetryUntilSuccessful: tick the child again after each failure."""

from __future__ import annotations

from typing import Any, ClassVar

from aiobt.core.composite import DecoratorNode, reset_node
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status


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

    def execute_sync(self) -> Status:
        binding = self.config.inputs.get(self.LIMIT_PORT)
        limit: int = (
            binding.value  # a literal: no lookup per tick
            if binding is not None and binding.key is None
            else self.get_input(self.LIMIT_PORT)
        )
        again = self.AGAIN
        finished = SUCCESS if again is FAILURE else FAILURE
        loop = self._count < limit or limit == -1
        if self._status is not RUNNING:
            if self._ctx.listeners:
                self._set_status(RUNNING)
            else:
                self._status = RUNNING
        child = self.child
        assert child is not None
        while loop:
            previous = child._status
            status = child.tick_sync()
            if status is again:
                self._count += 1
                loop = self._count < limit or limit == -1
                self.reset_child()
                if previous is IDLE and loop:
                    self.emit_wake_up()
                    return RUNNING
            elif status is finished:
                self._count = 0
                reset_node(child)
                return finished
            elif status is RUNNING:
                return RUNNING
            elif status is SKIPPED:
                self.reset_child()
                return SKIPPED
            else:
                raise self.logic_error("child returned IDLE")
        self._count = 0
        return again

    def on_halt_sync(self) -> None:
        self._count = 0
        self.reset_child()
