"""Bases of the nodes with children: control nodes and decorators.

Reset rules are BT.CPP's: a parent halts only RUNNING children; every other
child is reset to IDLE without a halt.
"""

from __future__ import annotations

from typing import Any

from aiobt.core.node import NodeKind, TreeNode
from aiobt.core.status import Status

IDLE = Status.IDLE
RUNNING = Status.RUNNING
SKIPPED = Status.SKIPPED


async def reset_node(node: TreeNode) -> None:
    """Halt ``node`` if it is RUNNING, else put it back to IDLE."""
    status = node._status
    if status is RUNNING:
        await node.halt()
    elif status is not IDLE:
        node._set_status(IDLE)


def reset_finished(nodes: list[TreeNode], keep: int = -1) -> bool:
    """Set every finished node of ``nodes`` but ``nodes[keep]`` IDLE, in order,
    without awaiting; stop at the first RUNNING one and return False.

    The caller then awaits the async reset (:func:`reset_all`,
    :meth:`ControlNode.halt_others`), which halts it and goes on, so the
    effects come in the same order. Hot paths call this first to spare a
    coroutine when no child is RUNNING.
    """
    index = -1
    for node in nodes:
        index += 1
        status = node._status
        if status is IDLE or index == keep:
            continue
        if status is RUNNING:
            return False
        if node._ctx.listeners:
            node._set_status(IDLE)
        else:
            node._status = IDLE
    return True


def reset_if_finished(node: TreeNode) -> bool:
    """:func:`reset_finished` for one node: False (nothing done) if RUNNING."""
    status = node._status
    if status is RUNNING:
        return False
    if status is not IDLE:
        if node._ctx.listeners:
            node._set_status(IDLE)
        else:
            node._status = IDLE
    return True


async def reset_all(nodes: list[TreeNode]) -> None:
    """:func:`reset_node` on each of ``nodes``, in order.

    Hot path (every finished Sequence resets all its children): a finished
    child is set IDLE in place, without a coroutine per child, and without a
    call when nobody listens to status changes.
    """
    for node in nodes:
        status = node._status
        if status is IDLE:
            continue
        if status is RUNNING:
            await node.halt()
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

    async def halt_child(self, index: int) -> None:
        await reset_node(self.children[index])

    async def halt_children_from(self, start: int) -> None:
        await reset_all(self.children[start:])

    async def halt_others(self, keep: int) -> None:
        """Reset every child but ``keep`` (inline: this runs on every reactive tick)."""
        for index, child in enumerate(self.children):
            status = child._status
            if index == keep or status is IDLE:
                continue
            if status is RUNNING:
                await child.halt()
            elif child._ctx.listeners:
                child._set_status(IDLE)
            else:
                child._status = IDLE

    async def reset_children(self) -> None:
        await reset_all(self.children)

    async def on_halt(self) -> None:
        await self.reset_children()


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

    async def reset_child(self) -> None:
        child = self.child
        if child is not None and child._status is not IDLE:
            await reset_node(child)

    async def on_halt(self) -> None:
        await self.reset_child()

    async def tick_child(self) -> Status:
        child = self.child
        assert child is not None
        if child.is_sync:
            return child.tick_sync()
        if child._conditions is None:  # inlined child.tick(): one frame less
            status = await child.execute()
            if status is not SKIPPED and status is not child._status:
                child._set_status(status)
            return status
        return await child.tick()
