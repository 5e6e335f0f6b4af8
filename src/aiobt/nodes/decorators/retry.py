"""RetryUntilSuccessful: tick the child again after each failure."""

from __future__ import annotations

from typing import Any, ClassVar

from aiobt.core.composite import DecoratorNode, reset_node
from aiobt.core.node import TreeNode
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status


class RetryUntilSuccessful(DecoratorNode):
    """``<RetryUntilSuccessful num_attempts="N">``: up to N attempts (-1: forever).

    SUCCESS as soon as the child succeeds; FAILURE after N failures (N=0 fails
    without ticking). After an attempt that started and failed within one
    tick, it returns RUNNING and asks for a wake-up, so the tree stays
    interruptible between attempts. A SKIPPED child makes it SKIPPED.
    """

    __slots__ = ("_count", "_limit")
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
        binding = self.config.inputs.get(self.LIMIT_PORT)
        # a literal limit is read once; one bound to a key is read per tick
        self._limit: int | None = (
            binding.value if binding is not None and binding.key is None else None
        )

    def tick_sync(self) -> Status:
        # the short path when nobody listens, no pre/post conditions apply, the
        # limit is a literal and the child does not fail (its common case)
        limit = self._limit
        if (
            limit is None
            or self._conditions is not None
            or self._ctx.listeners
            or not (self._count < limit or limit == -1)
        ):
            return super().tick_sync()
        child = self.child
        assert child is not None
        previous = child._status
        status = child.tick_sync()
        if status is RUNNING:
            self._status = RUNNING
            return RUNNING
        if status is not self.AGAIN and status is not SKIPPED and status is not IDLE:
            self._count = 0  # finished: reset the child, in place unless it is RUNNING
            if child._status is RUNNING:
                child.halt_sync()
            else:
                child._status = IDLE
            self._status = status
            return status
        self._status = RUNNING  # what BT.CPP's node shows during its tick
        status = self._after(child, previous, status, limit)
        if status is not SKIPPED:  # SKIPPED leaves it RUNNING
            self._status = status
        return status

    def execute_sync(self) -> Status:
        limit = self._limit
        if limit is None:
            limit = self.get_input(self.LIMIT_PORT)
        if self._status is not RUNNING:
            if self._ctx.listeners:
                self._set_status(RUNNING)
            else:
                self._status = RUNNING
        if not (self._count < limit or limit == -1):
            self._count = 0
            return self.AGAIN
        child = self.child
        assert child is not None
        previous = child._status
        return self._after(child, previous, child.tick_sync(), limit)

    def _after(self, child: TreeNode, previous: Status, status: Status, limit: int) -> Status:
        """Go on from the child's result ``status`` (it was ``previous`` before)."""
        again = self.AGAIN
        finished = SUCCESS if again is FAILURE else FAILURE
        while True:
            if status is again:
                self._count += 1
                loop = self._count < limit or limit == -1
                self.reset_child()
                if not loop:
                    self._count = 0
                    return again
                if previous is IDLE:
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
            previous = child._status
            status = child.tick_sync()

    def on_halt_sync(self) -> None:
        self._count = 0
        self.reset_child()
