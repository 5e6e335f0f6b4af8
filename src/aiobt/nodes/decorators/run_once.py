"""RunOnce: tick the child to completion once, then skip (or repeat its result)."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import DecoratorNode
from aiobt.core.ports import input_port
from aiobt.core.status import RUNNING, SKIPPED, Status


class RunOnce(DecoratorNode):
    """``<RunOnce then_skip="true">``: once its child has finished, it is never
    ticked again; afterwards RunOnce returns SKIPPED (or, with
    ``then_skip="false"``, the child's result). It remembers even across halts."""

    __slots__ = ("_result",)
    PORTS = (
        input_port(
            "then_skip",
            bool,
            True,
            "if true, skip after the first execution, "
            "otherwise return the status the child returned once",
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._result: Status | None = None

    def execute_sync(self) -> Status:
        skip = self.get_input("then_skip", True)
        if self._result is not None:
            return SKIPPED if skip else self._result
        self._set_status(RUNNING)
        status = self.tick_child()
        if status.is_completed:
            self._result = status
            self.reset_child()
        return status
