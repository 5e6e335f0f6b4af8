"""WasEntryUpdated: SUCCESS if a blackboard entry was written since the last tick."""

from __future__ import annotations

from typing import Any

from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import input_port
from aiobt.core.status import Status
from aiobt.nodes.decorators.entry_updated import entry_key


class WasEntryUpdated(SyncActionNode):
    """``<WasEntryUpdated entry="{goal}"/>``: SUCCESS when ``goal`` was written
    since this node last looked (the first look counts any earlier write),
    FAILURE otherwise or when the entry does not exist."""

    __slots__ = ("_key", "_sequence_id")
    PORTS = (input_port("entry", str, description="Entry to check"),)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._key = entry_key(self)
        self._sequence_id = 0

    def on_tick(self) -> Status:
        entry = self.config.blackboard.entry(self._key)
        if entry is None:
            return Status.FAILURE
        previous, self._sequence_id = self._sequence_id, entry.sequence_id
        return Status.SUCCESS if previous != entry.sequence_id else Status.FAILURE
