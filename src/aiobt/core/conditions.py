"""Pre- and post-conditions of a node (``_skipIf``, ``_while``, ``_onSuccess``...).

The order and the moments follow BT.CPP 4's ``TreeNode::executeTick``:
pre-conditions are checked in the order failureIf, successIf, skipIf, while;
the first three only when the node is IDLE (or was SKIPPED), ``_while`` also
while it is RUNNING, where a false value halts it and reports SKIPPED. After
the tick, ``_onSuccess``/``_onFailure`` run on completion and ``_post`` on
completion too; ``_onHalted`` runs whenever the node is halted.

Conditions are compiled callables over the node's blackboard; the script
language that produces them lives in :mod:`aiobt.scripting`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from aiobt.core.status import Status

if TYPE_CHECKING:
    from aiobt.core.node import TreeNode

Evaluator = Callable[["TreeNode"], Any]

IDLE = Status.IDLE
RUNNING = Status.RUNNING
SKIPPED = Status.SKIPPED
SUCCESS = Status.SUCCESS
FAILURE = Status.FAILURE


@dataclass(slots=True)
class NodeConditions:
    failure_if: Evaluator | None = None
    success_if: Evaluator | None = None
    skip_if: Evaluator | None = None
    while_true: Evaluator | None = None
    on_success: Evaluator | None = None
    on_failure: Evaluator | None = None
    on_halted_script: Evaluator | None = None
    post: Evaluator | None = None

    def _pre(self, node: TreeNode) -> Status | None:
        status = node.status
        if status is IDLE or status is SKIPPED:
            if self.failure_if is not None and bool(self.failure_if(node)):
                return FAILURE
            if self.success_if is not None and bool(self.success_if(node)):
                return SUCCESS
            if self.skip_if is not None and bool(self.skip_if(node)):
                return SKIPPED
            if self.while_true is not None and not bool(self.while_true(node)):
                return SKIPPED
        return None

    def _post(self, node: TreeNode, status: Status) -> None:
        if status is SUCCESS and self.on_success is not None:
            self.on_success(node)
        elif status is FAILURE and self.on_failure is not None:
            self.on_failure(node)
        if status.is_completed and self.post is not None:
            self.post(node)

    def _settle(self, node: TreeNode, status: Status) -> Status:
        if status is not SKIPPED:
            node._set_status(status)
        self._post(node, status)
        return status

    async def tick(self, node: TreeNode) -> Status:
        pre = self._pre(node)
        if self._while_stops(node, pre):
            await node.halt()
            pre = SKIPPED
        if pre is not None:
            return self._settle(node, pre)
        return self._settle(node, await node.execute())

    def tick_sync(self, node: TreeNode) -> Status:
        pre = self._pre(node)
        if self._while_stops(node, pre):
            node.halt_sync()  # type: ignore[attr-defined]
            pre = SKIPPED
        if pre is not None:
            return self._settle(node, pre)
        return self._settle(node, node.execute_sync())  # type: ignore[attr-defined]

    def _while_stops(self, node: TreeNode, pre: Status | None) -> bool:
        """True when ``_while`` turned false while the node was RUNNING."""
        if pre is not None or node.status is not RUNNING or self.while_true is None:
            return False
        return not bool(self.while_true(node))

    def on_halted(self, node: TreeNode) -> None:
        if self.on_halted_script is not None:
            self.on_halted_script(node)

    def __bool__(self) -> bool:
        return any(
            f is not None
            for f in (
                self.failure_if,
                self.success_if,
                self.skip_if,
                self.while_true,
                self.on_success,
                self.on_failure,
                self.on_halted_script,
                self.post,
            )
        )
