"""SubTree: runs another BehaviorTree with its own (remapped) blackboard."""

from __future__ import annotations

from typing import Any

from aiobt.core.blackboard import Blackboard
from aiobt.core.composite import DecoratorNode
from aiobt.core.node import NodeKind
from aiobt.core.status import RUNNING, Status


class SubTreeNode(DecoratorNode):
    """``<SubTree ID="Other" port="{key}" _autoremap="true"/>``

    - ticks the root of tree ``ID`` and returns its status;
    - resets the subtree when it finishes;
    - its blackboard is a child scope: explicit remapping, ``_autoremap``.
    """

    __slots__ = ("subtree_blackboard", "tree_id")
    KIND = NodeKind.SUBTREE

    def __init__(
        self, *args: Any, tree_id: str, subtree_blackboard: Blackboard, **kwargs: Any
    ) -> None:
        super().__init__(*args, **kwargs)
        self.tree_id = tree_id
        self.subtree_blackboard = subtree_blackboard

    def execute_sync(self) -> Status:
        if self._status is Status.IDLE:
            self._set_status(RUNNING)
        child = self.child
        assert child is not None
        status = child.tick_sync()
        if status.is_completed:
            self.reset_child()
        return status
