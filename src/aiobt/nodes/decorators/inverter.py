"""Inverter: swap SUCCESS and FAILURE."""

from __future__ import annotations

from aiobt.core.composite import DecoratorNode, reset_node
from aiobt.core.status import FAILURE, IDLE, RUNNING, SUCCESS, Status


class Inverter(DecoratorNode):
    """``<Inverter>``: SUCCESS becomes FAILURE and back; RUNNING and SKIPPED pass."""

    __slots__ = ()

    def tick_sync(self) -> Status:
        # the short path when nobody listens and no pre/post conditions apply
        if self._conditions is not None or self._ctx.listeners:
            return super().tick_sync()
        child = self.child
        assert child is not None
        status = child.tick_sync()
        if status is SUCCESS or status is FAILURE:
            child._status = IDLE  # a finished child, reset in place
            status = FAILURE if status is SUCCESS else SUCCESS
            self._status = status
            return status
        self._status = RUNNING  # RUNNING, or SKIPPED that leaves the node RUNNING (BT.CPP)
        if status is IDLE:
            raise self.logic_error("child returned IDLE")
        return status

    def execute_sync(self) -> Status:
        quiet = not self._ctx.listeners
        if self._status is not RUNNING:
            if quiet:
                self._status = RUNNING
            else:
                self._set_status(RUNNING)
        child = self.child
        assert child is not None
        status = child.tick_sync()
        if status is SUCCESS or status is FAILURE:
            if quiet:  # a finished child: reset in place
                child._status = IDLE
            else:
                reset_node(child)
            return FAILURE if status is SUCCESS else SUCCESS
        if status is IDLE:
            raise self.logic_error("child returned IDLE")
        return status
