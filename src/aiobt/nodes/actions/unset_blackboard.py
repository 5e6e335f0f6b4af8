"""UnsetBlackboard: remove a blackboard entry."""

from __future__ import annotations

from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import input_port
from aiobt.core.status import Status


class UnsetBlackboard(SyncActionNode):
    """``<UnsetBlackboard key="answer"/>``: remove the entry (SUCCESS even if absent)."""

    __slots__ = ()
    PORTS = (input_port("key", str, description="key of the entry to remove", required=True),)

    def on_tick(self) -> Status:
        self.config.blackboard.unset(self.get_input("key"))
        return Status.SUCCESS
