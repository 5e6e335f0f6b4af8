"""Bases of the nodes with children: control nodes and decorators.

Reset rules are BT.CPP's: a parent halts only RUNNING children; every other
child is reset to IDLE without a halt. All of it is synchronous.
"""

from __future__ import annotations

from typing import Any

from aiobt.core.node import NodeKind, TreeNode
from aiobt.core.status import IDLE, RUNNING, Status


def reset_node(node: TreeNode) -> None:
    """Halt ``node`` if it is RUNNING, else put it back to IDLE."""
    status = node._status
    if status is RUNNING:
        node.halt_sync()
    elif status is not IDLE:
        node._set_status(IDLE)


def reset_all(nodes: list[TreeNode], keep: int = -1) -> None:
    """:func:`reset_node` on each of ``nodes`` but ``nodes[keep]``, in order.

    Hot path (every finished Sequence resets its children): a finished child
    is set IDLE in place, without a call when nobody listens to status changes.
    """
    index = -1
    for node in nodes:
        index += 1
        status = node._status
        if status is IDLE or index == keep:
            continue
        if status is RUNNING:
            node.halt_sync()
        elif node._ctx.listeners:
            node._set_status(IDLE)
        else:
            node._status = IDLE


class ControlNode(TreeNode):
    """A node with one or more children, ticked in an order it decides."""

    __slots__ = ("children",)
    KIND = NodeKind.CONTROL
    MIN_CHILDREN = 1

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.children: list[TreeNode] = []

    def add_child(self, child: TreeNode) -> None:
        self.children.append(child)

    def children_nodes(self) -> tuple[TreeNode, ...]:
        return tuple(self.children)

    def halt_child(self, index: int) -> None:
        reset_node(self.children[index])

    def halt_children_from(self, start: int) -> None:
        reset_all(self.children[start:])

    def halt_others(self, keep: int) -> None:
        """Reset every child but ``keep``."""
        reset_all(self.children, keep)

    def reset_children(self) -> None:
        reset_all(self.children)

    def on_halt_sync(self) -> None:
        self.reset_children()


class DecoratorNode(TreeNode):
    """A node with exactly one child, whose result it transforms or repeats."""

    __slots__ = ("child",)
    KIND = NodeKind.DECORATOR
    MIN_CHILDREN = 1

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.child: TreeNode | None = None

    def add_child(self, child: TreeNode) -> None:
        self.child = child

    def children_nodes(self) -> tuple[TreeNode, ...]:
        return () if self.child is None else (self.child,)

    def reset_child(self) -> None:
        child = self.child
        if child is not None and child._status is not IDLE:
            reset_node(child)

    def on_halt_sync(self) -> None:
        self.reset_child()

    def tick_child(self) -> Status:
        child = self.child
        assert child is not None
        return child.tick_sync()
