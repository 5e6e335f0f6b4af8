"""RateController (Nav2): tick the child at most ``hz`` times per second."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import DecoratorNode
from aiobt.core.ports import input_port
from aiobt.core.status import IDLE, RUNNING, SUCCESS, Status


class RateController(DecoratorNode):
    """``<RateController hz="1.0">`` (Nav2), on the tree's clock.

    - the first tick of an activation ticks the child and starts the period;
    - a RUNNING child is ticked on every tick until it finishes;
    - otherwise the child is ticked again once ``1/hz`` seconds have passed
      since the activation started or since its last SUCCESS (a FAILURE does
      not restart the period, as in Nav2);
    - when the child is not ticked, the node returns RUNNING (Nav2 returns its
      own status, which it has just set to RUNNING);
    - returns the child's result when the child finishes (the child is reset
      then, so a stateful child starts afresh on its next tick).
    """

    __slots__ = ("_first", "_period", "_start")
    PORTS = (input_port("hz", float, 10.0, "Rate to throttle an action or a group of actions."),)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._start = 0.0
        self._period = 0.1
        self._first = False

    def execute_sync(self) -> Status:
        if self._status is IDLE:
            hz: float = self.get_input("hz")
            if not hz > 0.0:
                raise self.logic_error(f"hz must be > 0, not {hz!r}")
            self._period = 1.0 / hz
            self._start = self.clock.now()
            self._first = True
        self._set_status(RUNNING)
        child = self.child
        assert child is not None
        due = self.clock.now() - self._start >= self._period
        if not (self._first or due or child._status is RUNNING):
            return RUNNING
        self._first = False
        status = child.tick_sync()
        if status is SUCCESS:
            self._start = self.clock.now()
        if status.is_completed:
            self.reset_child()
        return status
