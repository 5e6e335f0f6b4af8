"""PipelineSequence (Nav2): re-tick every earlier child while a later one runs."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import ControlNode
from aiobt.core.status import FAILURE, RUNNING, SKIPPED, SUCCESS, Status


class PipelineSequence(ControlNode):
    """``<PipelineSequence>`` (Nav2): a sequence that keeps earlier children ticking.

    - every tick starts from the first child; a child SUCCESS moves on;
    - a child RUNNING at or beyond the furthest child reached so far:
      RUNNING (the children after it are not ticked yet); a RUNNING child
      before that point does not stop the pipeline;
    - a child FAILURE: halt every child, FAILURE;
    - the last child SUCCESS: halt every child (a still-RUNNING first child
      too), SUCCESS.

    Nav2 throws on a SKIPPED child; here a SKIPPED child is passed over like a
    success, so ``_skipIf`` works inside a pipeline.
    """

    __slots__ = ("_furthest",)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._furthest = 0

    def execute_sync(self) -> Status:
        for index, child in enumerate(self.children):
            status = child.tick_sync()
            if status is FAILURE:
                self.on_halt_sync()
                return FAILURE
            if status is RUNNING:
                if index >= self._furthest:
                    self._furthest = index
                    return RUNNING
            elif status is not SUCCESS and status is not SKIPPED:
                raise self.logic_error(f"child {child.path} returned {status.name}")
        self.on_halt_sync()
        return SUCCESS

    def on_halt_sync(self) -> None:
        self._furthest = 0
        self.reset_children()
