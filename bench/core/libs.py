"""One shape, four runtimes: aiobt, py_trees, BehaviorTree.CPP (behaviortreepy)
with Python leaves, and the await floor.

Each builder returns a zero-argument tick function (a coroutine function for
aiobt and the floor). With a :class:`Counter`, the leaves (and, where the
library lets us see them, the inner nodes) count their ticks, so the bench can
check that every runtime visits the same nodes per tree tick.

The await floor is the minimal asyncio-native tree walk: one ``async def`` per
node; a tree tick awaits the root's coroutine, each inner node awaits its
children's coroutines one after the other with the same control decision as
the node it stands for (Sequence: stop at the first non-SUCCESS; Fallback: at
the first non-FAILURE; Inverter swaps; RetryUntilSuccessful passes through),
and a leaf coroutine returns its constant status. No status is stored, nothing
is reset, no listener is checked.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from enum import Enum
from typing import Any

import behaviortreepy as btcpp
import py_trees

from aiobt import BehaviorTreeFactory, ConditionNode, StatefulActionNode, Status, SyncActionNode
from aiobt.core.node import TreeNode
from aiobt.nodes.control.fallback import Fallback
from aiobt.nodes.control.reactive_fallback import ReactiveFallback
from aiobt.nodes.control.reactive_sequence import ReactiveSequence
from aiobt.nodes.control.sequence import Sequence
from aiobt.nodes.decorators.inverter import Inverter
from aiobt.nodes.decorators.retry import RetryUntilSuccessful
from bench.core.shapes import Spec, to_xml

SUCCESS, FAILURE, RUNNING = Status.SUCCESS, Status.FAILURE, Status.RUNNING


@dataclass(slots=True)
class Counter:
    leaves: int = 0
    nodes: int = 0  # inner nodes, where countable


COUNTER = Counter()  # used only by the counting builds

# -- aiobt ----------------------------------------------------------------------------


class OkAction(SyncActionNode):
    __slots__ = ()

    def on_tick(self) -> Status:
        return SUCCESS


class OkCondition(ConditionNode):
    __slots__ = ()

    def check(self) -> Status:
        return SUCCESS


class FailCondition(ConditionNode):
    __slots__ = ()

    def check(self) -> Status:
        return FAILURE


class RunAction(StatefulActionNode):
    __slots__ = ()

    def on_start(self) -> Status:
        return RUNNING

    def on_running(self) -> Status:
        return RUNNING


def _counting(base: type[TreeNode], hooks: tuple[str, ...]) -> type[TreeNode]:
    namespace: dict[str, Any] = {"__slots__": ()}
    for hook in hooks:
        original = getattr(base, hook)

        def counted(self: TreeNode, _original: Any = original) -> Any:
            COUNTER.leaves += 1
            return _original(self)

        namespace[hook] = counted
    return type(base.__name__, (base,), namespace)


AIOBT_LEAVES = (OkAction, OkCondition, FailCondition, RunAction)
AIOBT_COUNTING = (
    _counting(OkAction, ("on_tick",)),
    _counting(OkCondition, ("check",)),
    _counting(FailCondition, ("check",)),
    _counting(RunAction, ("on_start", "on_running")),
)
AIOBT_INNER = (
    Sequence,
    ReactiveSequence,
    Fallback,
    ReactiveFallback,
    Inverter,
    RetryUntilSuccessful,
)


def aiobt_tick(spec: Spec, counting: bool = False) -> Callable[[], Awaitable[Status]]:
    factory = BehaviorTreeFactory()
    for cls in AIOBT_COUNTING if counting else AIOBT_LEAVES:
        factory.register_node_type(cls, cls.__name__)
    return factory.create_tree_from_text(to_xml(spec)).tick_exactly_once


@contextmanager
def aiobt_inner_counted() -> Iterator[None]:
    """Count every tick of aiobt's inner nodes (tick_sync patched on the classes).

    Composites built into a tree have a class of their own, a subclass with a
    tick unrolled for their children (``aiobt.nodes.control.unrolled``): every
    subclass that defines its own ``tick_sync`` is patched too.
    """
    classes: list[type[TreeNode]] = []
    pending = list(AIOBT_INNER)
    while pending:
        cls = pending.pop()
        if cls in AIOBT_INNER or "tick_sync" in cls.__dict__:
            classes.append(cls)
        pending.extend(cls.__subclasses__())
    saved = {cls: cls.__dict__.get("tick_sync") for cls in classes}

    def wrap(execute: Any) -> Any:
        def counted(self: TreeNode) -> Status:
            COUNTER.nodes += 1
            return execute(self)  # type: ignore[no-any-return]

        return counted

    try:
        for cls in saved:
            cls.tick_sync = wrap(cls.tick_sync)  # type: ignore[method-assign]
        yield
    finally:
        for cls, tick in saved.items():
            if tick is None:
                del cls.tick_sync
            else:
                cls.tick_sync = tick  # type: ignore[method-assign]


# -- py_trees -------------------------------------------------------------------------

PT = py_trees.common.Status


def _pt_leaf(result: PT, counting: bool) -> type[py_trees.behaviour.Behaviour]:
    if counting:

        def update(self: Any) -> PT:
            COUNTER.leaves += 1
            return result
    else:

        def update(self: Any) -> PT:
            return result

    return type("Leaf", (py_trees.behaviour.Behaviour,), {"update": update})


def _pt_node(spec: Spec, leaves: dict[str, type[py_trees.behaviour.Behaviour]]) -> Any:
    name = spec.name or spec.kind
    if spec.is_leaf:
        return leaves[spec.kind](name)
    kids = [_pt_node(child, leaves) for child in spec.children]
    kind = spec.kind
    if kind == "Sequence":
        return py_trees.composites.Sequence(name, memory=True, children=kids)
    if kind == "ReactiveSequence":
        return py_trees.composites.Sequence(name, memory=False, children=kids)
    if kind == "Fallback":
        return py_trees.composites.Selector(name, memory=True, children=kids)
    if kind == "ReactiveFallback":
        return py_trees.composites.Selector(name, memory=False, children=kids)
    if kind == "Inverter":
        return py_trees.decorators.Inverter(name, kids[0])
    if kind == "RetryUntilSuccessful":
        attempts = int(dict(spec.attrs)["num_attempts"])
        return py_trees.decorators.Retry(name, kids[0], num_failures=attempts)
    raise ValueError(f"no py_trees equivalent for {kind}")


class _VisitCounter(py_trees.visitors.VisitorBase):
    def __init__(self) -> None:
        super().__init__(full=False)  # run on the ticked nodes only

    def run(self, behaviour: Any) -> None:
        if behaviour.children or isinstance(behaviour, py_trees.decorators.Decorator):
            COUNTER.nodes += 1


def pytrees_tick(spec: Spec, counting: bool = False) -> Callable[[], None]:
    leaves = {
        "OkAction": _pt_leaf(PT.SUCCESS, counting),
        "OkCondition": _pt_leaf(PT.SUCCESS, counting),
        "FailCondition": _pt_leaf(PT.FAILURE, counting),
        "RunAction": _pt_leaf(PT.RUNNING, counting),
    }
    tree = py_trees.trees.BehaviourTree(_pt_node(spec, leaves))
    if counting:
        tree.visitors.append(_VisitCounter())
    return tree.tick


# -- BehaviorTree.CPP via behaviortreepy -----------------------------------------------


def btcpp_tick(spec: Spec, counting: bool = False) -> Callable[[], Any]:
    ns = btcpp.NodeStatus
    ok, fail, run = ns.SUCCESS, ns.FAILURE, ns.RUNNING

    def body(result: Any) -> Callable[[Any], Any]:
        if counting:

            def counted(node: Any) -> Any:
                COUNTER.leaves += 1
                return result

            return counted
        return lambda node: result

    factory = btcpp.BehaviorTreeFactory()
    factory.register_simple_action("OkAction", body(ok))
    factory.register_simple_condition("OkCondition", body(ok))
    factory.register_simple_condition("FailCondition", body(fail))
    factory.register_simple_stateful_action("RunAction", body(run), body(run))
    return factory.create_tree_from_text(to_xml(spec)).tick_exactly_once  # type: ignore[no-any-return]


# -- the await floor --------------------------------------------------------------------

Coro = Callable[[], Awaitable[Enum]]


def _floor_leaf(result: Status) -> Coro:
    async def leaf() -> Status:
        return result

    return leaf


def _floor_until(children: list[Coro], keep_going: Status) -> Coro:
    async def walk() -> Enum:
        for child in children:
            status = await child()
            if status is not keep_going:
                return status
        return keep_going

    return walk


def _floor_inverter(child: Coro) -> Coro:
    async def invert() -> Enum:
        status = await child()
        if status is SUCCESS:
            return FAILURE
        return SUCCESS if status is FAILURE else status

    return invert


def _floor_pass(child: Coro) -> Coro:
    async def passthrough() -> Enum:
        return await child()

    return passthrough


def _floor_counted(inner: Coro, is_leaf: bool) -> Coro:
    async def counted() -> Enum:
        if is_leaf:
            COUNTER.leaves += 1
        else:
            COUNTER.nodes += 1
        return await inner()

    return counted


_FLOOR_LEAVES = {"OkAction": SUCCESS, "OkCondition": SUCCESS, "FailCondition": FAILURE}


def floor_tick(spec: Spec, counting: bool = False) -> Coro:
    if spec.is_leaf:
        coro = _floor_leaf(_FLOOR_LEAVES.get(spec.kind, RUNNING))
    else:
        kids = [floor_tick(child, counting) for child in spec.children]
        if spec.kind in ("Sequence", "ReactiveSequence"):
            coro = _floor_until(kids, SUCCESS)
        elif spec.kind in ("Fallback", "ReactiveFallback"):
            coro = _floor_until(kids, FAILURE)
        elif spec.kind == "Inverter":
            coro = _floor_inverter(kids[0])
        elif spec.kind == "RetryUntilSuccessful":
            coro = _floor_pass(kids[0])
        else:
            raise ValueError(f"no floor equivalent for {spec.kind}")
    return _floor_counted(coro, spec.is_leaf) if counting else coro


BUILDERS: dict[str, Callable[[Spec, bool], Callable[[], Any]]] = {
    "floor": floor_tick,
    "aiobt": aiobt_tick,
    "py_trees": pytrees_tick,
    "btcpp": btcpp_tick,
}
ASYNC = {"floor", "aiobt"}
