"""Stub leaves for scenario tests: scripted results, tick/halt counters, a call log.

One :class:`Stubs` object owns the scripts, counters and the shared call log of
every stub node in a tree; :meth:`Stubs.factory` gives a factory with the stub
IDs registered next to the built-ins::

    stubs = Stubs()
    factory = stubs.factory()
    stubs.script("Move", "RUNNING", "RUNNING", "SUCCESS")
    tree = factory.create_tree_from_text(tree_xml('''
        <Sequence>
          <StubCondition name="BatteryOK"/>
          <StubAction name="Move"/>
        </Sequence>'''))

XML IDs (each stub is identified by its ``name``):

- ``StubAction`` — a StatefulActionNode; each call of on_start/on_running
  returns the next scripted result (the last one repeats; default SUCCESS).
  Its ``results`` port scripts it from the XML: ``results="R;R;S"``.
- ``StubCondition`` — a condition; each check returns the next scripted
  result (SUCCESS or FAILURE; default SUCCESS).
- ``StubAsyncAction`` — an async leaf: waits ``msec`` of the tree's clock, then
  returns ``result``; its halts are counted (the task is cancelled).

``settle()`` lets the tasks a tick started take their first steps before a
test moves a ManualClock.

The log holds ``"name:event"`` strings, in order: ``start``, ``running``,
``halted`` (stateful actions), ``check`` (conditions), ``run``, ``done``,
``cancelled`` (async actions).
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any, ClassVar

from aiobt.core.leaves import AsyncActionNode, ConditionNode, StatefulActionNode
from aiobt.core.node import TreeNode
from aiobt.core.ports import input_port
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory

ScriptItem = Status | str | Callable[[TreeNode], Status]

_SHORT = {
    "S": Status.SUCCESS,
    "F": Status.FAILURE,
    "R": Status.RUNNING,
    "K": Status.SKIPPED,
}


def parse_status(text: str) -> Status:
    """``SUCCESS``/``S``, ``FAILURE``/``F``, ``RUNNING``/``R``, ``SKIPPED``/``K``."""
    word = text.strip().upper()
    if word in _SHORT:
        return _SHORT[word]
    try:
        return Status[word]
    except KeyError:
        raise ValueError(f"{text!r} is not a status (SUCCESS, FAILURE, RUNNING, SKIPPED)") from None


def _script_of(items: Iterable[ScriptItem]) -> list[Status | Callable[[TreeNode], Status]]:
    return [parse_status(item) if isinstance(item, str) else item for item in items]


@dataclass(slots=True)
class StubRecord:
    """What one stub (by name) went through."""

    name: str
    ticks: int = 0
    starts: int = 0
    halts: int = 0
    results: list[Status] = field(default_factory=list)


@dataclass(slots=True)
class Stubs:
    """Scripts, counters and the shared call log of the stub nodes of a test."""

    log: list[str] = field(default_factory=list)
    records: dict[str, StubRecord] = field(default_factory=dict)
    scripts: dict[str, list[Status | Callable[[TreeNode], Status]]] = field(default_factory=dict)

    def script(self, name: str, *results: ScriptItem) -> None:
        """Results for stub ``name``, one per call; the last one repeats."""
        self.scripts[name] = _script_of(results)

    def record(self, name: str) -> StubRecord:
        found = self.records.get(name)
        if found is None:
            found = self.records[name] = StubRecord(name)
        return found

    def ticks(self, name: str) -> int:
        return self.record(name).ticks

    def starts(self, name: str) -> int:
        return self.record(name).starts

    def halts(self, name: str) -> int:
        return self.record(name).halts

    def events(self, name: str) -> list[str]:
        """The log entries of one stub, without its name."""
        prefix = f"{name}:"
        return [e[len(prefix) :] for e in self.log if e.startswith(prefix)]

    def clear(self) -> None:
        """Forget the log and counters (scripts stay)."""
        self.log.clear()
        self.records.clear()

    def next_result(self, node: TreeNode, fallback: list[Status]) -> Status:
        script = self.scripts.get(node.name)
        if script is None:
            script = list(fallback) or [Status.SUCCESS]
            self.scripts[node.name] = script
        item = script.pop(0) if len(script) > 1 else script[0]
        status = item(node) if callable(item) else item
        self.record(node.name).results.append(status)
        return status

    def register(self, factory: BehaviorTreeFactory) -> BehaviorTreeFactory:
        """Register StubAction, StubCondition and StubAsyncAction bound to these stubs."""
        for base in (StubAction, StubCondition, StubAsyncAction):
            bound = type(base.__name__, (base,), {"__slots__": (), "STUBS": self})
            bound.__module__ = __name__
            factory.register_node_type(bound, base.__name__, replace=True)
        return factory

    def factory(self) -> BehaviorTreeFactory:
        """A new factory with the built-ins and these stubs registered."""
        return self.register(BehaviorTreeFactory())


_RESULTS_PORT = input_port(
    "results", str, "", "scripted results, ';'-separated (S, F, R, K or full names)"
)


def _port_script(node: TreeNode) -> list[Status]:
    text: str = node.get_input("results", "")
    return [parse_status(part) for part in text.split(";") if part.strip()]


class StubAction(StatefulActionNode):
    """A scripted stateful action: each on_start/on_running returns the next result."""

    __slots__ = ()
    STUBS: ClassVar[Stubs]
    PORTS = (_RESULTS_PORT,)

    def execute_sync(self) -> Status:
        self.STUBS.record(self.name).ticks += 1
        return super().execute_sync()

    def _next(self, event: str) -> Status:
        self.STUBS.log.append(f"{self.name}:{event}")
        return self.STUBS.next_result(self, _port_script(self))

    def on_start(self) -> Status:
        self.STUBS.record(self.name).starts += 1
        return self._next("start")

    def on_running(self) -> Status:
        return self._next("running")

    def on_halted(self) -> None:
        self.STUBS.record(self.name).halts += 1
        self.STUBS.log.append(f"{self.name}:halted")


class StubCondition(ConditionNode):
    """A scripted condition: each check returns the next result."""

    __slots__ = ()
    STUBS: ClassVar[Stubs]
    PORTS = (_RESULTS_PORT,)

    def check(self) -> Status:
        record = self.STUBS.record(self.name)
        record.ticks += 1
        self.STUBS.log.append(f"{self.name}:check")
        return self.STUBS.next_result(self, _port_script(self))


class StubAsyncAction(AsyncActionNode):
    """An async leaf: ``msec`` of clock time, then ``result``; halts cancel it."""

    __slots__ = ()
    STUBS: ClassVar[Stubs]
    PORTS = (
        input_port("msec", int, 0, "clock time to wait before finishing"),
        input_port("result", str, "SUCCESS", "the status to finish with"),
    )

    def execute_sync(self) -> Status:
        self.STUBS.record(self.name).ticks += 1
        return super().execute_sync()

    async def run(self) -> Status:
        stubs = self.STUBS
        stubs.record(self.name).starts += 1
        stubs.log.append(f"{self.name}:run")
        msec: int = self.get_input("msec")
        try:
            if msec > 0:
                await self.clock.sleep(msec / 1000.0)
        except asyncio.CancelledError:
            stubs.record(self.name).halts += 1
            stubs.log.append(f"{self.name}:cancelled")
            raise
        stubs.log.append(f"{self.name}:done")
        result = parse_status(self.get_input("result"))
        stubs.record(self.name).results.append(result)
        return result


def tree_xml(body: str, tree_id: str = "MainTree", *extra_trees: str) -> str:
    """A v4 document with ``body`` as the single child of BehaviorTree ``tree_id``."""
    others = "".join(extra_trees)
    return (
        f'<root BTCPP_format="4" main_tree_to_execute="{tree_id}">'
        f'<BehaviorTree ID="{tree_id}">{body}</BehaviorTree>{others}</root>'
    )


async def tick_statuses(tick: Callable[[], Any], count: int) -> list[Status]:
    """Call an async ``tick`` (e.g. ``tree.tick_exactly_once``) ``count`` times."""
    return [await tick() for _ in range(count)]


async def settle(steps: int = 5) -> None:
    """Let started tasks (async leaves, timers) take their first steps before a
    test moves robot time: ``steps`` passes of the event loop."""
    for _ in range(steps):
        await asyncio.sleep(0)
