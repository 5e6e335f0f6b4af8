"""Pre- and post-conditions of a node (``_skipIf``, ``_while``, ``_onSuccess``...).

The order and the moments follow BT.CPP 4.8's ``TreeNode::executeTick``:

- pre-conditions are checked in the order failureIf, successIf, skipIf,
  while, and only when the node is IDLE: the first true one of the first
  three decides the result (FAILURE, SUCCESS, SKIPPED) without ticking the
  node; a false ``_while`` gives SKIPPED;
- while the node is RUNNING only ``_while`` is checked: false halts the node
  (its ``_onHalted`` runs) and reports SKIPPED; a node still SUCCESS or
  FAILURE (not reset by its parent) checks none;
- when the result is SUCCESS or FAILURE, whether it came from a pre-condition
  or from the tick, ``_onSuccess`` or ``_onFailure`` runs, then ``_post``,
  and only then the node's status changes; SKIPPED leaves the status as it is;
- ``_onHalted`` runs after every halt of the node.

Conditions are compiled callables over the node's blackboard, produced by the
factory's ``script_compiler`` (:func:`aiobt.script.compile_condition`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from aiobt.core.errors import NodeError
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status

if TYPE_CHECKING:
    from aiobt.core.node import TreeNode

Evaluator = Callable[["TreeNode"], Any]


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
        if node.status is IDLE:
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
        if status is SUCCESS:
            if self.on_success is not None:
                self.on_success(node)
        elif status is FAILURE:
            if self.on_failure is not None:
                self.on_failure(node)
        else:
            return
        if self.post is not None:
            self.post(node)

    def _settle(self, node: TreeNode, status: Status) -> Status:
        self._post(node, status)
        if status is not SKIPPED:
            node._set_status(status)
        return status

    def tick_sync(self, node: TreeNode) -> Status:
        pre = self._decide(node)
        if pre is not None:
            return self._settle(node, pre)
        return self._execute(node)

    def _decide(self, node: TreeNode) -> Status | None:
        """The result the conditions give without ticking the node, or None to tick."""
        pre = self._pre(node)
        if self._while_stops(node, pre):
            node.halt_sync()
            pre = SKIPPED
        return pre

    def _execute(self, node: TreeNode) -> Status:
        try:
            status = node.execute_sync()
        except NodeError:
            raise
        except Exception as exc:
            raise NodeError(node.path, exc) from exc
        return self._settle(node, status)

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
