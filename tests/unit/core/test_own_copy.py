"""Each node class used in a tree ticks through its own copy of its tick's code
(``TreeNode.on_tree_built``), so CPython's inline caches see one class."""

from __future__ import annotations

from typing import Any

from aiobt.core.leaves import ConditionNode, SyncActionNode
from aiobt.core.node import TreeContext
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.nodes.control.sequence import Sequence


class Checks(ConditionNode):
    __slots__ = ()
    calls = 0

    def check(self) -> bool:
        type(self).calls += 1
        return True


class Acts(SyncActionNode):
    __slots__ = ()

    def on_tick(self) -> Status:
        return Status.FAILURE


def _build() -> Tree:
    root = Sequence("s")
    root.add_child(Checks("c"))
    root.add_child(Acts("a"))
    return Tree(root, TreeContext(), root.config.blackboard)


async def test_a_class_gets_its_own_tick_code_when_a_tree_uses_it() -> None:
    assert "tick_sync" not in Checks.__dict__
    tree = _build()
    own = Checks.__dict__["tick_sync"]
    shared = ConditionNode.tick_sync
    assert own is not shared
    assert own.__code__ is not shared.__code__
    assert own.__code__ == shared.__code__  # the same code, its own caches
    assert Acts.__dict__["tick_sync"].__code__ is not SyncActionNode.tick_sync.__code__
    assert await tree.tick_exactly_once() is Status.FAILURE
    assert Checks.calls == 1
    _build()
    assert Checks.__dict__["tick_sync"] is own  # copied once per class


def test_a_copy_keeps_what_the_function_carries() -> None:
    import functools

    from aiobt.core.node import own_copy

    def tick(self: object, *, factor: int = 2) -> int:
        """Doc."""
        return factor

    wrapped: Any = functools.wraps(tick)(lambda self, *, factor=3: factor)
    functions: list[Any] = [tick, wrapped]
    for function in functions:
        copy = own_copy(function)
        assert copy.__code__ is not function.__code__
        assert copy(None) == function(None)
        assert (copy.__qualname__, copy.__doc__) == (function.__qualname__, function.__doc__)
        assert copy.__dict__ == function.__dict__
