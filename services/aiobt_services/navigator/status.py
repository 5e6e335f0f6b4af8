"""The tree status stream for monitors (``{ns}/bt/...``, models in :mod:`aiobt.msgs.bt`).

:class:`TreeStatusStream` follows one tree instance at a time: it publishes the
structure when a tree is attached, collects status changes while the tree
ticks and publishes them in one :class:`BtTransitions` per :meth:`flush` (the
navigator flushes after each tick), and builds :class:`BtSnapshot` messages on
request. Where the messages go is a :class:`StatusSink` (Zenoh publishers in
the service, a list in tests).
"""

from __future__ import annotations

from typing import Protocol

from aiobt.core.node import NodeKind, TreeNode
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.loggers.observer import StatusObserver
from aiobt.loggers.tree_xml import tree_to_xml
from aiobt.msgs.bt import (
    BtNode,
    BtNodeStatus,
    BtSnapshot,
    BtTransition,
    BtTransitions,
    BtTree,
    NavigationState,
)


class StatusSink(Protocol):
    def tree(self, message: BtTree) -> None: ...
    def transitions(self, message: BtTransitions) -> None: ...
    def snapshot(self, message: BtSnapshot) -> None: ...


def tree_structure(tree: Tree, run: int, action: str, source: str) -> BtTree:
    """The :class:`BtTree` of ``tree`` (nodes depth first, each with its parent's uid)."""
    parents: dict[int, int] = {}
    nodes = []
    for node in tree.nodes():
        for child in node.children_nodes():
            parents[child.uid] = node.uid
        nodes.append(
            BtNode(
                uid=node.uid,
                parent=parents.get(node.uid),
                path=node.path,
                id=node.config.registration_id or type(node).__name__,
                name=node.name,
                kind=getattr(node, "KIND", NodeKind.ACTION),
            )
        )
    return BtTree(
        run=run,
        tree_id=tree.tree_id,
        source=source,
        action=action,
        stamp=tree.clock.now(),
        nodes=nodes,
        xml=tree_to_xml(tree),
    )


class _Collector(StatusObserver):
    def __init__(self, tree: Tree) -> None:
        self.pending: list[BtTransition] = []
        super().__init__(tree)

    def on_transition(self, stamp: float, node: TreeNode, previous: Status, status: Status) -> None:
        self.pending.append(
            BtTransition(uid=node.uid, previous=previous.name, status=status.name, stamp=stamp)
        )


class TreeStatusStream:
    """Publishes one tree instance after another on a :class:`StatusSink`."""

    def __init__(self, sink: StatusSink) -> None:
        self.sink = sink
        self.run = 0
        self._tree: Tree | None = None
        self._collector: _Collector | None = None

    @property
    def tree(self) -> Tree | None:
        return self._tree

    def attach(self, tree: Tree, *, action: str, source: str) -> None:
        """Follow ``tree`` (a new run): its structure is published at once."""
        self.detach()
        self.run += 1
        self._tree = tree
        self._collector = _Collector(tree)
        self.sink.tree(tree_structure(tree, self.run, action, source))

    def detach(self) -> None:
        """Publish what is pending and stop following the tree (its statuses stay
        available to :meth:`snapshot` until the next attach)."""
        if self._collector is not None:
            self.flush()
            self._collector.close()
            self._collector = None

    def flush(self) -> None:
        """One :class:`BtTransitions` with the changes since the last flush, if any."""
        collector = self._collector
        if collector is None or not collector.pending:
            return
        batch, collector.pending = collector.pending, []
        self.sink.transitions(BtTransitions(run=self.run, stamp=batch[-1].stamp, transitions=batch))

    def snapshot(self, state: NavigationState, stamp: float, **navigation: object) -> BtSnapshot:
        """Every node's status now, with the navigation's ``state`` and fields
        (``action``, ``goal_id``, ``ticks``, ``number_of_recoveries``, ...)."""
        tree = self._tree
        nodes = [] if tree is None else [_status_of(node) for node in tree.nodes()]
        fields = {"run": self.run, "tree_id": tree.tree_id if tree else "", "stamp": stamp}
        return BtSnapshot.model_validate({**fields, "state": state, "nodes": nodes, **navigation})


def _status_of(node: TreeNode) -> BtNodeStatus:
    return BtNodeStatus(uid=node.uid, status=node.status.name)
