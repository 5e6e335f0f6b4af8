"""The stub a substitution rule puts in place of a decorator that has no implementation."""

from __future__ import annotations

from aiobt.core.composite import DecoratorNode
from aiobt.core.manifest import NodeBuilder
from aiobt.core.node import NodeConfig, TreeNode
from aiobt.core.status import RUNNING, Status


class PassThrough(DecoratorNode):
    """A stubbed decorator: ticks its child and returns the child's status.

    Built by ``--stub`` for decorators known only from a ``<TreeNodesModel>``
    (e.g. a plugin's), so the tree runs through them instead of failing.
    """

    __slots__ = ()

    def execute_sync(self) -> Status:
        self._set_status(RUNNING)
        status = self.tick_child()
        if status.is_completed:
            self.reset_child()
        return status


def pass_through_builder() -> NodeBuilder:
    def build(name: str, config: NodeConfig) -> TreeNode:
        return PassThrough(name, config)

    return build
