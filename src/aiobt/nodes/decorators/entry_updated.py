"""SkipUnlessUpdated and WaitValueUpdate: tick the child when an entry was written."""

from __future__ import annotations

from typing import Any, ClassVar

from aiobt.core.composite import DecoratorNode
from aiobt.core.node import TreeNode
from aiobt.core.ports import input_port
from aiobt.core.status import RUNNING, Status


def entry_key(node: TreeNode) -> str:
    """The blackboard key of the ``entry`` port: ``{key}`` or a plain ``key``."""
    binding = node.config.inputs.get("entry")
    key = None if binding is None else (binding.key or str(binding.value or ""))
    if not key:
        raise ValueError(f"{node.path}: port [entry] must name a blackboard entry")
    return key


class EntryUpdatedDecorator(DecoratorNode):
    """Ticks its child only if ``entry`` was written since the last check."""

    __slots__ = ("_key", "_running", "_sequence_id")
    IF_NOT_UPDATED: ClassVar[Status] = Status.SKIPPED
    PORTS = (input_port("entry", str, description="Entry to check"),)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._key = entry_key(self)
        self._sequence_id = 0
        self._running = False

    def execute_sync(self) -> Status:
        if not self._running:
            entry = self.config.blackboard.entry(self._key)
            if entry is None:
                return self.IF_NOT_UPDATED
            previous, self._sequence_id = self._sequence_id, entry.sequence_id
            if previous == entry.sequence_id:
                return self.IF_NOT_UPDATED
        status = self.tick_child()
        self._running = status is RUNNING
        if status.is_completed:
            # BT.CPP's DecoratorNode::executeTick: own status first, then the child reset
            self._set_status(status)
            self.reset_child()
        return status

    def on_halt_sync(self) -> None:
        self._running = False
        self.reset_child()


class SkipUnlessUpdated(EntryUpdatedDecorator):
    """``<SkipUnlessUpdated entry="{goal}">``: SKIPPED unless ``goal`` was written
    since the last check (a missing entry skips too); a RUNNING child is ticked
    again without checking."""

    __slots__ = ()
    IF_NOT_UPDATED = Status.SKIPPED


class WaitValueUpdate(EntryUpdatedDecorator):
    """``<WaitValueUpdate entry="{goal}">``: RUNNING until ``goal`` is written
    (again), then tick the child; a RUNNING child is ticked again without
    checking."""

    __slots__ = ()
    IF_NOT_UPDATED = Status.RUNNING
