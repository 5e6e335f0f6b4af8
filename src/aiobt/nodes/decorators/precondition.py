"""Precondition: tick the child only if a script condition holds."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import DecoratorNode
from aiobt.core.ports import input_port
from aiobt.core.status import Status
from aiobt.nodes.actions.script import ScriptCode
from aiobt.nodes.decorators.status_port import status_input


class Precondition(DecoratorNode):
    """``<Precondition if="battery > 20" else="FAILURE">``.

    - the condition is checked only when the child is not already running;
    - false: return ``else`` (default FAILURE; SUCCESS, SKIPPED, RUNNING
      allowed) without ticking the child;
    - true: tick the child and return its status; once the child finishes it
      is reset and the condition is checked again at the next tick.
    """

    __slots__ = ("_children_running", "_script")
    PORTS = (
        input_port("if", str),
        input_port("else", Status, Status.FAILURE, "Return status if condition is false"),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._script = ScriptCode(self, condition=True, port="if")
        self._children_running = False

    def execute_sync(self) -> Status:
        otherwise = status_input(self, "else")
        if not self._children_running:
            self._children_running = bool(self._script.run())
            if not self._children_running:
                return otherwise
        status = self.tick_child()
        if status.is_completed:
            self.reset_child()
            self._children_running = False
        return status

    def on_halt_sync(self) -> None:
        self._children_running = False
        self.reset_child()
