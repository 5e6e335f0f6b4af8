"""Per-node statistics (like BT.CPP's TreeObserver), with real tick counts.

Status listeners only see changes, so a RUNNING node ticked again, or a
skipped one (SKIPPED leaves a node IDLE), would be invisible. While attached,
:class:`TreeStatistics` therefore swaps each node's class for a cached
subclass whose ``tick_sync`` counts the call and its result (the awaitable
``tick`` goes through it); closing it restores the original classes. Nothing
is instrumented when it is not attached.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from aiobt.core.node import TreeNode
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status
from aiobt.core.tree import Tree
from aiobt.loggers.observer import StatusObserver


@dataclass(slots=True)
class NodeStatistics:
    """What one node did since the observer was attached.

    ``ticks`` counts every tick; ``successes``/``failures``/``skips``/
    ``running`` count the statuses those ticks returned; ``transitions``
    counts status changes other than back to IDLE (BT.CPP's
    transitions_count); ``last_status`` is the last status a tick returned,
    ``last_result`` the last SUCCESS or FAILURE; ``last_stamp`` the clock time
    of the last change.
    """

    uid: int
    path: str
    ticks: int = 0
    successes: int = 0
    failures: int = 0
    skips: int = 0
    running: int = 0
    transitions: int = 0
    last_status: Status = IDLE
    last_result: Status = IDLE
    last_stamp: float = 0.0

    def count(self, status: Status) -> None:
        self.ticks += 1
        self.last_status = status
        if status is SUCCESS:
            self.successes += 1
            self.last_result = status
        elif status is FAILURE:
            self.failures += 1
            self.last_result = status
        elif status is SKIPPED:
            self.skips += 1
        elif status is RUNNING:
            self.running += 1


_ACTIVE: dict[int, NodeStatistics] = {}  # id(node) -> its statistics, while instrumented


def _counted(cls: type[TreeNode]) -> type[TreeNode]:
    """A subclass of ``cls`` whose ``tick_sync`` also counts (made once per class).

    It is kept on ``cls`` itself, not in a module-level cache: classes made per
    node (unrolled composites) then go away with their tree.
    """
    if cls.__dict__.get("_stats_counting", False):
        return cls
    found: type[TreeNode] | None = cls.__dict__.get("_stats_counted")
    if found is not None:
        return found
    original_tick_sync = cls.tick_sync

    def tick_sync(self: TreeNode) -> Status:
        status = original_tick_sync(self)
        stats = _ACTIVE.get(id(self))
        if stats is not None:
            stats.count(status)
        return status

    namespace: dict[str, Any] = {
        "__slots__": (),
        "__module__": cls.__module__,
        "_stats_counting": True,
        "tick_sync": tick_sync,
    }
    counted = type(cls.__name__, (cls,), namespace)
    type.__setattr__(cls, "_stats_counted", counted)
    return counted


class TreeStatistics(StatusObserver):
    """Counts ticks and results per node of ``tree`` while attached."""

    def __init__(self, tree: Tree) -> None:
        self.by_uid: dict[int, NodeStatistics] = {}
        self._originals: list[tuple[TreeNode, type[TreeNode]]] = []
        for node in tree.nodes():
            stats = NodeStatistics(node.uid, node.path)
            self.by_uid[node.uid] = stats
            _ACTIVE[id(node)] = stats
            original = type(node)
            counted = _counted(original)
            if counted is not original:
                node.__class__ = counted
                self._originals.append((node, original))
        super().__init__(tree)

    def on_transition(self, stamp: float, node: TreeNode, previous: Status, status: Status) -> None:
        stats = self.by_uid.get(node.uid)
        if stats is not None:
            stats.last_stamp = stamp
            if status is not IDLE:
                stats.transitions += 1

    def __getitem__(self, key: int | str) -> NodeStatistics:
        """Statistics by uid, or by node name or path."""
        if isinstance(key, int):
            return self.by_uid[key]
        for node in self.tree.nodes():
            if key in (node.path, node.name):
                return self.by_uid[node.uid]
        raise KeyError(f"no node named {key!r} in tree {self.tree.tree_id!r}")

    def close(self) -> None:
        for node, original in self._originals:
            node.__class__ = original
        for node in self.tree.nodes():
            _ACTIVE.pop(id(node), None)
        self._originals.clear()
        super().close()
