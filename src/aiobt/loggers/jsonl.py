"""A JSON Lines file of transitions: one object per status change.

``{"stamp": 1.25, "uid": 3, "path": "Main/Sequence/Go", "from": "IDLE", "to": "RUNNING"}``
(``stamp`` in seconds of the tree's clock).
"""

from __future__ import annotations

import json
from pathlib import Path

from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.loggers.observer import StatusObserver


class JsonlLogger(StatusObserver):
    """Appends transitions to ``path`` (created or truncated), flushed every
    ``flush_every`` lines and on :meth:`close`."""

    def __init__(self, tree: Tree, path: str | Path, *, flush_every: int = 256) -> None:
        self.path = Path(path)
        self._file = self.path.open("w", encoding="utf-8")
        self._lines: list[str] = []
        self._flush_every = flush_every
        super().__init__(tree)

    def on_transition(self, stamp: float, node: TreeNode, previous: Status, status: Status) -> None:
        record = {
            "stamp": stamp,
            "uid": node.uid,
            "path": node.path,
            "from": previous.name,
            "to": status.name,
        }
        self._lines.append(json.dumps(record))
        if len(self._lines) >= self._flush_every:
            self.flush()

    def flush(self) -> None:
        if self._lines and not self._file.closed:
            self._file.write("\n".join(self._lines) + "\n")
            self._lines.clear()
            self._file.flush()

    def close(self) -> None:
        super().close()
        self._file.close()
