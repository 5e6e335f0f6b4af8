"""The tree a monitor shows, kept from ``{ns}/bt/tree``, ``/transitions`` and ``/snapshot``.

Pure state and text: :class:`TreeView` takes the messages in any order (a
transition or snapshot of another tree instance than the structure's is
dropped) and renders as many lines as the screen has. A tree too tall for
the screen shows the nodes that are not IDLE and their ancestors; what is
still too much is cut with a count of the nodes left out.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

from aiobt.msgs.bt import BtNode, BtSnapshot, BtTransitions, BtTree

_COLOURS = {"RUNNING": "33", "SUCCESS": "32", "FAILURE": "31", "SKIPPED": "90", "IDLE": "2"}


@dataclass(slots=True)
class TreeView:
    tree: BtTree | None = None
    status: dict[int, str] = field(default_factory=dict)
    snapshot: BtSnapshot | None = None
    children: dict[int | None, list[BtNode]] = field(default_factory=dict)

    def on_tree(self, tree: BtTree) -> None:
        self.tree = tree
        self.status = {node.uid: "IDLE" for node in tree.nodes}
        self.children = {}
        for node in tree.nodes:
            self.children.setdefault(node.parent, []).append(node)
        if self.snapshot is not None and self.snapshot.run != tree.run:
            self.snapshot = None

    def on_transitions(self, message: BtTransitions) -> list[tuple[BtNode, str]]:
        """Apply one tick's changes; the (node, new status) pairs applied."""
        if self.tree is None or message.run != self.tree.run:
            return []
        nodes = {node.uid: node for node in self.tree.nodes}
        applied: list[tuple[BtNode, str]] = []
        for change in message.transitions:
            if change.uid in nodes:
                self.status[change.uid] = change.status
                applied.append((nodes[change.uid], change.status))
        return applied

    def on_snapshot(self, snapshot: BtSnapshot) -> None:
        if self.tree is None or snapshot.run != self.tree.run:
            return
        self.snapshot = snapshot
        for entry in snapshot.nodes:
            if entry.uid in self.status:
                self.status[entry.uid] = entry.status

    def header(self) -> str:
        if self.tree is None:
            return "waiting for the navigator's tree (bt/tree)..."
        text = f"{self.tree.tree_id} (run {self.tree.run})"
        shot = self.snapshot
        if shot is not None:
            text += (
                f"  {shot.state}  t={shot.stamp:.1f} s  ticks {shot.ticks}  "
                f"recoveries {shot.number_of_recoveries}  "
                f"distance {shot.distance_remaining:.2f} m"
            )
            if shot.error_code:
                text += f"  error {shot.error_code} {shot.error_msg}"
        return text

    def render(self, height: int = 10_000, colour: bool = False) -> list[str]:
        """The header and the tree, at most ``height`` lines."""
        lines = [self.header()]
        if self.tree is None:
            return lines
        rows = list(self._rows(None, 0, self._shown(height - 1)))
        room = max(1, height - 1)
        if len(rows) <= room:
            return lines + [self._line(depth, node, colour) for depth, node in rows]
        kept = rows[: room - 1]
        hidden = len(self.tree.nodes) - len(kept)
        lines += [self._line(depth, node, colour) for depth, node in kept]
        return [*lines, f"... {hidden} more nodes (a taller terminal shows them)"]

    def _shown(self, room: int) -> set[int] | None:
        """None (every node) when the tree fits, else the active nodes and their ancestors."""
        assert self.tree is not None
        if len(self.tree.nodes) <= room:
            return None
        parents = {node.uid: node.parent for node in self.tree.nodes}
        shown: set[int] = set()
        for uid, status in self.status.items():
            current: int | None = uid if status != "IDLE" or parents[uid] is None else None
            while current is not None and current not in shown:
                shown.add(current)
                current = parents[current]
        return shown

    def _rows(
        self, parent: int | None, depth: int, shown: set[int] | None
    ) -> Iterator[tuple[int, BtNode]]:
        for node in self.children.get(parent, []):
            if shown is None or node.uid in shown:
                yield depth, node
                yield from self._rows(node.uid, depth + 1, shown)

    def _line(self, depth: int, node: BtNode, colour: bool) -> str:
        status = self.status.get(node.uid, "IDLE")
        label = node.id if node.name == node.id else f"{node.id} [{node.name}]"
        text = f"{'  ' * depth}{label}"
        mark = f"{status:<8}"
        if colour:
            mark = f"\033[{_COLOURS[status]}m{mark}\033[0m"
        return f"{mark} {text}"
