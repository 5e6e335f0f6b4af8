"""Text for people: a unicode rendering of a tree and its current statuses (test
failures, the CLI), and :func:`plural` ("1 recovery", "2 recoveries").

::

    ◐ Sequence [RUNNING]
    ├── ✔ Leaf "A" [SUCCESS]
    └── ◐ Leaf "B" [RUNNING]
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.core.tree import Tree

if TYPE_CHECKING:
    from aiobt.loggers.stats import TreeStatistics

GLYPHS = {
    Status.IDLE: "○",
    Status.RUNNING: "◐",
    Status.SUCCESS: "✔",
    Status.FAILURE: "✘",
    Status.SKIPPED: "⤼",
}
_COLORS = {
    Status.IDLE: "\x1b[2m",
    Status.RUNNING: "\x1b[33m",
    Status.SUCCESS: "\x1b[32m",
    Status.FAILURE: "\x1b[31m",
    Status.SKIPPED: "\x1b[34m",
}
_RESET = "\x1b[0m"


def _label(node: TreeNode, color: bool, stats: TreeStatistics | None) -> str:
    node_id = node.config.registration_id or type(node).__name__
    if node_id == "SubTree":
        node_id = f"SubTree {getattr(node, 'tree_id', '')}".rstrip()
    name = f' "{node.name}"' if node.name not in (node_id, node.config.registration_id) else ""
    status = node.status
    text = f"{GLYPHS[status]} {node_id}{name} [{status.name}]"
    if stats is not None and node.uid in stats.by_uid:
        counts = stats.by_uid[node.uid]
        text += f" ticks={counts.ticks} ok={counts.successes} fail={counts.failures}"
        if counts.skips:
            text += f" skip={counts.skips}"
    return f"{_COLORS[status]}{text}{_RESET}" if color else text


def render(
    target: Tree | TreeNode, *, color: bool = False, stats: TreeStatistics | None = None
) -> str:
    """The tree (or the subtree under a node) as indented unicode lines.

    ``color`` adds ANSI colors; ``stats`` appends each node's tick counts.
    """
    root = target.root if isinstance(target, Tree) else target
    lines = [_label(root, color, stats)]

    def walk(node: TreeNode, prefix: str) -> None:
        children = node.children_nodes()
        for index, child in enumerate(children):
            last = index == len(children) - 1
            lines.append(f"{prefix}{'└── ' if last else '├── '}{_label(child, color, stats)}")
            walk(child, prefix + ("    " if last else "│   "))

    walk(root, "")
    return "\n".join(lines)


def plural(count: int, word: str, words: str = "") -> str:
    """``1 recovery``, ``2 recoveries``, ``0 goals`` (``words``: the plural, default word+s)."""
    if count == 1:
        return f"1 {word}"
    if not words:
        words = (
            word[:-1] + "ies" if word.endswith("y") and word[-2:-1] not in "aeiou" else word + "s"
        )
    return f"{count} {words}"
