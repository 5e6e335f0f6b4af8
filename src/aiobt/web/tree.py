"""The running tree's statuses for the page, kept from the navigator's status stream.

:class:`~aiobt.monitor.TreeView` (the terminal monitor's state) keeps the
current status of every node; this adds each node's last status other than
IDLE, so the page can show what a node ended with after its parent reset it
(Groot2's "idle, coming from SUCCESS").
"""

from __future__ import annotations

from aiobt.monitor import TreeView
from aiobt.msgs.bt import BtSnapshot, BtTransitions, BtTree
from aiobt.web.convert import Json, tree_payload


class TreeStatus:
    """Structure and statuses of the navigator's latest tree instance."""

    def __init__(self) -> None:
        self.view = TreeView()
        self.last: dict[int, str] = {}

    def on_tree(self, tree: BtTree) -> Json:
        """Take a new structure; its payload for the page."""
        if self.view.tree is None or self.view.tree.run != tree.run:
            self.last = {}
        self.view.on_tree(tree)
        return tree_payload(tree)

    def on_transitions(self, message: BtTransitions) -> bool:
        """Apply one tick's changes; False when they belong to another tree instance."""
        applied = self.view.on_transitions(message)
        for node, status in applied:
            if status != "IDLE":
                self.last[node.uid] = status
        return bool(applied)

    def on_snapshot(self, snapshot: BtSnapshot) -> bool:
        if self.view.tree is None or snapshot.run != self.view.tree.run:
            return False
        self.view.on_snapshot(snapshot)
        for entry in snapshot.nodes:
            if entry.status != "IDLE":
                self.last[entry.uid] = entry.status
        return True

    def payload(self) -> Json | None:
        """Every node's status (and last non-IDLE one) by uid, or None before a tree."""
        if self.view.tree is None:
            return None
        return {
            "run": self.view.tree.run,
            "status": {str(uid): status for uid, status in self.view.status.items()},
            "last": {str(uid): status for uid, status in self.last.items()},
        }
