"""A SQLite transition log with BT.CPP's SqliteLogger schema (``.db3``/``.btdb``).

Tables, as BT.CPP creates them:

- ``Definitions(session_id, date, xml_tree)``: one row per logging session,
  with the tree's XML (``_uid`` attributes, see :mod:`aiobt.loggers.tree_xml`);
- ``Nodes(session_id, fullpath, node_uid)``: every node of the session;
- ``Transitions(timestamp, session_id, node_uid, duration, state, extra_data)``:
  ``timestamp`` in µs since the Unix epoch (tree-clock time since attach
  added to the wall time at attach), strictly increasing as BT.CPP makes it;
  ``duration`` in µs when a node leaves RUNNING, else 0.
"""

from __future__ import annotations

import sqlite3
from pathlib import Path

from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.loggers.observer import StatusObserver
from aiobt.loggers.tree_xml import tree_to_xml

SCHEMA = (
    "CREATE TABLE IF NOT EXISTS Transitions ("
    "timestamp  INTEGER PRIMARY KEY NOT NULL, "
    "session_id INTEGER NOT NULL, "
    "node_uid   INTEGER NOT NULL, "
    "duration   INTEGER, "
    "state      INTEGER NOT NULL,"
    "extra_data VARCHAR );",
    "CREATE TABLE IF NOT EXISTS Nodes ("
    "session_id INTEGER NOT NULL, "
    "fullpath   VARCHAR, "
    "node_uid   INTEGER NOT NULL );",
    "CREATE TABLE IF NOT EXISTS Definitions ("
    "session_id INTEGER PRIMARY KEY AUTOINCREMENT, "
    "date       TEXT NOT NULL,"
    "xml_tree   TEXT NOT NULL);",
)

Row = tuple[int, int, int, int, int, None]


class SqliteLogger(StatusObserver):
    """Logs ``tree`` into the database at ``path``; ``append=False`` empties it first.

    Rows are inserted every ``flush_every`` transitions and on close.
    """

    def __init__(
        self, tree: Tree, path: str | Path, *, append: bool = False, flush_every: int = 512
    ) -> None:
        self.path = Path(path)
        if self.path.suffix not in (".db3", ".btdb"):
            raise ValueError(f"SqliteLogger: the file name must end in .db3 or .btdb, not {path}")
        self._db = sqlite3.connect(self.path)
        self._db_open = True
        self._rows: list[Row] = []
        self._started: dict[int, int] = {}
        self._last = 0
        self._flush_every = flush_every
        self.session_id = self._open_session(tree, append)
        super().__init__(tree)

    def _open_session(self, tree: Tree, append: bool) -> int:
        db = self._db
        for statement in SCHEMA:
            db.execute(statement)
        if not append:
            for table in ("Transitions", "Definitions", "Nodes"):
                db.execute(f"DELETE FROM {table};")
        db.execute(
            "INSERT INTO Definitions (date, xml_tree) VALUES (datetime('now','localtime'), ?);",
            (tree_to_xml(tree),),
        )
        (session_id,) = db.execute("SELECT MAX(session_id) FROM Definitions;").fetchone()
        db.executemany(
            "INSERT INTO Nodes VALUES (?, ?, ?);",
            [(session_id, node.path, node.uid) for node in tree.nodes()],
        )
        db.commit()
        return int(session_id)

    def on_transition(self, stamp: float, node: TreeNode, previous: Status, status: Status) -> None:
        timestamp = max(self._last + 1, self.epoch_us + self.offset_us(stamp))
        self._last = timestamp
        duration = 0
        if previous is Status.IDLE and status is Status.RUNNING:
            self._started[node.uid] = timestamp
        elif previous is Status.RUNNING and status is not Status.RUNNING:
            duration = timestamp - self._started.get(node.uid, timestamp)
        self._rows.append((timestamp, self.session_id, node.uid, duration, status.value, None))
        if len(self._rows) >= self._flush_every:
            self.flush()

    def flush(self) -> None:
        if self._rows:
            self._db.executemany("INSERT INTO Transitions VALUES (?, ?, ?, ?, ?, ?);", self._rows)
            self._db.commit()
            self._rows.clear()

    def close(self) -> None:
        if self._db_open:
            super().close()
            self._db.execute("PRAGMA optimize;")
            self._db.close()
            self._db_open = False
