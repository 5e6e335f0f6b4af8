"""Node classes made from plain functions (``register_simple_action`` and friends)."""

from __future__ import annotations

import inspect
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from aiobt.core.leaves import AsyncActionNode, ConditionNode, StatefulActionNode, SyncActionNode
from aiobt.core.node import NodeKind, TreeNode
from aiobt.core.ports import PortInfo
from aiobt.core.status import Status

SimpleFunction = Callable[[TreeNode], Any]


@dataclass(frozen=True, slots=True)
class StatefulCallbacks:
    """``on_start(node)``, ``on_running(node)`` and optional ``on_halted(node)``."""

    on_start: Callable[[TreeNode], Status]
    on_running: Callable[[TreeNode], Status]
    on_halted: Callable[[TreeNode], None] | None = None


def simple_node_class(
    node_id: str, fn: SimpleFunction | StatefulCallbacks, ports: tuple[PortInfo, ...], kind: str
) -> type[TreeNode]:
    """A TreeNode subclass named ``node_id`` that calls ``fn(node)``.

    A condition calls it as ``check``; an action as a sync ``on_tick``, or as
    ``run`` of an async leaf when ``fn`` is a coroutine function;
    :class:`StatefulCallbacks` make a StatefulActionNode.
    """
    namespace: dict[str, Any] = {
        "__slots__": (),
        "PORTS": ports,
        "__doc__": inspect.getdoc(fn) or f"{node_id}.",
    }
    base: type[TreeNode]
    if isinstance(fn, StatefulCallbacks):
        callbacks = fn
        base = StatefulActionNode
        namespace["on_start"] = lambda self: callbacks.on_start(self)
        namespace["on_running"] = lambda self: callbacks.on_running(self)
        if callbacks.on_halted is not None:
            halted = callbacks.on_halted
            namespace["on_halted"] = lambda self: halted(self)
    elif kind == NodeKind.CONDITION:
        base = ConditionNode
        namespace["check"] = lambda self: fn(self)
    elif inspect.iscoroutinefunction(fn):
        base = AsyncActionNode
        coro_fn = fn

        async def run(self: TreeNode) -> Any:
            return await coro_fn(self)

        namespace["run"] = run
    else:
        base = SyncActionNode
        namespace["on_tick"] = lambda self: fn(self)
    cls = type(node_id if node_id.isidentifier() else "SimpleNode", (base,), namespace)
    cls.__module__ = __name__
    return cls
