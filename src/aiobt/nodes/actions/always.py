"""AlwaysSuccess and AlwaysFailure."""

from __future__ import annotations

from aiobt.core.leaves import SyncActionNode
from aiobt.core.status import Status


class AlwaysSuccess(SyncActionNode):
    """``<AlwaysSuccess/>``: SUCCESS."""

    __slots__ = ()

    def execute_sync(self) -> Status:
        return Status.SUCCESS


class AlwaysFailure(SyncActionNode):
    """``<AlwaysFailure/>``: FAILURE."""

    __slots__ = ()

    def execute_sync(self) -> Status:
        return Status.FAILURE
