"""SQLite (BT.CPP's schema and rows), JSONL and console transition loggers."""

from __future__ import annotations

import io
import json
import sqlite3
from pathlib import Path

import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.loggers import ConsoleLogger, JsonlLogger, SqliteLogger, TransitionRecorder
from aiobt.testing.stubs import Stubs, tree_xml

BODY = '<Sequence><StubAction name="Go"/><AlwaysSuccess name="Done"/></Sequence>'


def _tree(clock: ManualClock) -> tuple[Tree, Stubs]:
    stubs = Stubs()
    stubs.script("Go", "RUNNING", "SUCCESS")
    return stubs.factory().create_tree_from_text(tree_xml(BODY), clock=clock), stubs


async def _run(tree: Tree, clock: ManualClock) -> None:
    await tree.tick_exactly_once()  # t=0: Go RUNNING
    clock.advance(0.5)
    await tree.tick_exactly_once()  # t=0.5: Go SUCCESS, Done SUCCESS, all reset


def _columns(db: sqlite3.Connection, table: str) -> list[tuple[str, str, int, int]]:
    return [(r[1], r[2], r[3], r[5]) for r in db.execute(f"PRAGMA table_info({table})")]


async def test_sqlite_schema_and_rows(tmp_path: Path) -> None:
    clock = ManualClock()
    tree, _ = _tree(clock)
    path = tmp_path / "run.db3"
    with SqliteLogger(tree, path) as logger, TransitionRecorder(tree) as recorder:
        await _run(tree, clock)
    db = sqlite3.connect(path)
    assert _columns(db, "Transitions") == [
        ("timestamp", "INTEGER", 1, 1),
        ("session_id", "INTEGER", 1, 0),
        ("node_uid", "INTEGER", 1, 0),
        ("duration", "INTEGER", 0, 0),
        ("state", "INTEGER", 1, 0),
        ("extra_data", "VARCHAR", 0, 0),
    ]
    assert _columns(db, "Nodes") == [
        ("session_id", "INTEGER", 1, 0),
        ("fullpath", "VARCHAR", 0, 0),
        ("node_uid", "INTEGER", 1, 0),
    ]
    assert [c[0] for c in _columns(db, "Definitions")] == ["session_id", "date", "xml_tree"]
    ((session, xml),) = db.execute("SELECT session_id, xml_tree FROM Definitions").fetchall()
    assert session == logger.session_id == 1
    assert '_uid="2"' in xml
    assert "StubAction" in xml
    nodes = db.execute("SELECT node_uid, fullpath FROM Nodes ORDER BY node_uid").fetchall()
    assert nodes == [(n.uid, n.path) for n in tree.nodes()]
    rows = db.execute(
        "SELECT timestamp, session_id, node_uid, duration, state FROM Transitions "
        "ORDER BY timestamp"
    ).fetchall()
    assert [(r[2], r[4]) for r in rows] == [(t.uid, t.status.value) for t in recorder.transitions]
    stamps = [r[0] for r in rows]
    assert stamps == sorted(set(stamps))  # strictly increasing, as BT.CPP makes them
    assert stamps[-1] - stamps[0] >= 500_000  # half a second of tree-clock time
    go_done = next(r for r in rows if r[2] == 2 and r[4] == Status.SUCCESS.value)
    assert 499_990 <= go_done[3] <= 500_000  # Go ran 0.5 s (less the 1 µs monotonic bumps)
    db.close()


async def test_sqlite_append_adds_a_session(tmp_path: Path) -> None:
    path = tmp_path / "run.btdb"
    for append in (False, True):
        clock = ManualClock()
        tree, _ = _tree(clock)
        with SqliteLogger(tree, path, append=append):
            await _run(tree, clock)
    db = sqlite3.connect(path)
    assert db.execute("SELECT session_id FROM Definitions").fetchall() == [(1,), (2,)]
    counts = db.execute("SELECT session_id, COUNT(*) FROM Transitions GROUP BY session_id")
    first, second = counts.fetchall()
    assert first[1] == second[1] > 0
    db.close()
    clock = ManualClock()
    tree, _ = _tree(clock)
    SqliteLogger(tree, path).close()  # append=False empties the tables
    db = sqlite3.connect(path)
    assert db.execute("SELECT COUNT(*) FROM Transitions").fetchone() == (0,)
    db.close()


def test_sqlite_rejects_another_extension(tmp_path: Path) -> None:
    tree = BehaviorTreeFactory().create_tree_from_text(tree_xml("<AlwaysSuccess/>"))
    with pytest.raises(ValueError, match=r"\.db3 or \.btdb"):
        SqliteLogger(tree, tmp_path / "x.sqlite")


async def test_jsonl_one_object_per_transition(tmp_path: Path) -> None:
    clock = ManualClock(start=10.0)
    tree, _ = _tree(clock)
    path = tmp_path / "run.jsonl"
    with JsonlLogger(tree, path, flush_every=3), TransitionRecorder(tree) as recorder:
        await _run(tree, clock)
    lines = path.read_text().splitlines()
    records = [json.loads(line) for line in lines]
    assert len(records) == len(recorder.transitions) > 3
    assert records[0] == {
        "stamp": 10.0,
        "uid": 1,
        "path": "MainTree/Sequence",
        "from": "IDLE",
        "to": "RUNNING",
    }
    assert [(r["uid"], r["from"], r["to"], r["stamp"]) for r in records] == [
        (t.uid, t.previous.name, t.status.name, t.stamp) for t in recorder.transitions
    ]
    assert {r["path"] for r in records} == {n.path for n in tree.nodes()}


async def test_console_logger_lines() -> None:
    clock = ManualClock()
    tree, _ = _tree(clock)
    out = io.StringIO()
    with ConsoleLogger(tree, out, show_idle=False):
        await _run(tree, clock)
    lines = out.getvalue().splitlines()
    assert lines[0] == f"[0.000]: {'Sequence':<25} IDLE -> RUNNING"
    assert lines[1] == f"[0.000]: {'Go':<25} IDLE -> RUNNING"
    assert all("-> IDLE" not in line for line in lines)
    assert lines[-1] == f"[0.500]: {'Sequence':<25} RUNNING -> SUCCESS"
    colored = io.StringIO()
    with ConsoleLogger(tree, colored, color=True):
        await tree.tick_exactly_once()
    assert "\x1b[33mRUNNING\x1b[0m" in colored.getvalue()


async def test_console_logger_defaults_to_logging(caplog: pytest.LogCaptureFixture) -> None:
    clock = ManualClock()
    tree, _ = _tree(clock)
    with caplog.at_level("INFO", logger="aiobt.transitions"), ConsoleLogger(tree):
        await tree.tick_exactly_once()
    assert any(
        "Go" in r.getMessage() and "IDLE -> RUNNING" in r.getMessage() for r in caplog.records
    )
