"""Shared helpers of the Nav2 node scenarios (no tests here).

``Leaf`` is an action that runs its script on *every* tick, whatever its
status (like Nav2's BT action nodes re-ticked by a PipelineSequence), and
logs ``name`` per tick and ``name:halt`` per halt of a RUNNING leaf.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from aiobt.core.clock import ManualClock
from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.nav import register_nav2_nodes
from aiobt.testing.stubs import parse_status, tree_xml

S, F, R = Status.SUCCESS, Status.FAILURE, Status.RUNNING


@dataclass(slots=True)
class Script:
    """Per-name results (the last repeats), tick and halt counts, one log."""

    results: dict[str, list[Status]] = field(default_factory=dict)
    log: list[str] = field(default_factory=list)

    def set(self, name: str, text: str) -> None:
        self.results[name] = [parse_status(part) for part in text.split()]

    def next(self, name: str) -> Status:
        script = self.results.setdefault(name, [S])
        return script.pop(0) if len(script) > 1 else script[0]

    def ticks(self, name: str) -> int:
        return self.log.count(name)

    def halts(self, name: str) -> int:
        return self.log.count(f"{name}:halt")

    def take(self) -> list[str]:
        taken = list(self.log)
        self.log.clear()
        return taken


class Leaf(TreeNode):
    __slots__ = ()
    SCRIPT: ClassVar[Script]

    def execute_sync(self) -> Status:
        self.SCRIPT.log.append(self.name)
        return self.SCRIPT.next(self.name)

    def on_halt_sync(self) -> None:
        if self._status is Status.RUNNING:
            self.SCRIPT.log.append(f"{self.name}:halt")


def nav2_factory() -> BehaviorTreeFactory:
    """A factory with Nav2's node set registered (no bus: the nodes here need none)."""
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory)
    return factory


def make_factory(script: Script) -> BehaviorTreeFactory:
    factory = nav2_factory()
    bound = type("Leaf", (Leaf,), {"__slots__": (), "SCRIPT": script})
    factory.register_node_type(bound, "Leaf")
    return factory


def build(script: Script, body: str, clock: ManualClock | None = None) -> Tree:
    return make_factory(script).create_tree_from_text(tree_xml(body), clock=clock)
