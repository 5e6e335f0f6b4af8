""".btlog files: decoded byte by byte by an independent reader, and against BT.CPP's own."""

from __future__ import annotations

import asyncio
import struct
import time
from dataclasses import dataclass
from pathlib import Path

import pytest
from lxml import etree

from aiobt.core.clock import ManualClock
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.loggers import BtlogLogger, TransitionRecorder

DOC = """<root BTCPP_format="4" main_tree_to_execute="Main">
<BehaviorTree ID="Main">
  <Sequence>
    <AlwaysSuccess name="first"/>
    <SubTree ID="Sub" name="subby"/>
    <AlwaysSuccess name="ok"/>
  </Sequence>
</BehaviorTree>
<BehaviorTree ID="Sub">
  <Fallback><AlwaysFailure/><AlwaysSuccess/></Fallback>
</BehaviorTree>
</root>"""


@dataclass
class Btlog:
    protocol: int
    xml: str
    first_us: int
    records: list[tuple[int, int, int]]  # (µs offset, uid, status)


def read_btlog(data: bytes) -> Btlog:
    """Independent reader of BT.CPP's FileLogger2 layout."""
    magic = b"BTCPP4-FileLogger2"
    assert data[: len(magic)] == magic
    protocol = data[len(magic)]
    pos = len(magic) + 1
    (xml_len,) = struct.unpack_from("<i", data, pos)
    pos += 4
    xml = data[pos : pos + xml_len].decode("utf-8")
    pos += xml_len
    (first_us,) = struct.unpack_from("<q", data, pos)
    pos += 8
    body = data[pos:]
    assert len(body) % 9 == 0, "records are 9 bytes each"
    records = []
    for start in range(0, len(body), 9):
        chunk = body[start : start + 9]
        offset = int.from_bytes(chunk[0:6], "little")
        uid = int.from_bytes(chunk[6:8], "little")
        records.append((offset, uid, chunk[8]))
    return Btlog(protocol, xml, first_us, records)


def _record_count(path: Path) -> int:
    data = path.read_bytes()
    header = 19 + 4 + int.from_bytes(data[19:23], "little") + 8 if len(data) >= 23 else len(data)
    return max(0, len(data) - header) // 9


def uid_map(xml: str) -> dict[int, tuple[str, str]]:
    """uid -> (element tag, name or subtree ID) from a log's XML."""
    root = etree.fromstring(xml.encode())
    return {
        int(str(e.get("_uid"))): (str(e.tag), e.get("name") or e.get("ID") or "")
        for e in root.iter()
        if e.get("_uid") is not None
    }


async def test_btlog_header_xml_and_records_decode(tmp_path: Path) -> None:
    clock = ManualClock(start=100.0)
    tree = BehaviorTreeFactory().create_tree_from_text(DOC, clock=clock)
    path = tmp_path / "run.btlog"
    before = time.time_ns() // 1000
    with BtlogLogger(tree, path) as log, TransitionRecorder(tree) as recorder:
        clock.advance(0.25)
        await tree.tick_once()
        clock.advance(1.5)
        await tree.tick_once()
        log.flush()
    decoded = read_btlog(path.read_bytes())
    assert decoded.protocol == 1
    assert before <= decoded.first_us <= time.time_ns() // 1000
    expected = [
        (round((t.stamp - 100.0) * 1e6), t.uid, t.status.value) for t in recorder.transitions
    ]
    assert decoded.records == expected
    assert {offset for offset, _, _ in decoded.records} == {250_000, 1_750_000}
    assert (0, 1, Status.RUNNING.value) not in decoded.records  # offsets are clock time
    assert decoded.records[0] == (250_000, 1, Status.RUNNING.value)  # Sequence starts first
    assert decoded.records[-1] == (1_750_000, 1, Status.IDLE.value)  # transitions to IDLE too
    nodes = {node.uid: node for node in tree.nodes()}
    assert all(uid in nodes for _, uid, _ in decoded.records)
    assert uid_map(decoded.xml) == {
        1: ("Sequence", "Sequence"),
        2: ("AlwaysSuccess", "first"),
        3: ("SubTree", "Sub"),
        4: ("Fallback", "Fallback"),
        5: ("AlwaysFailure", "AlwaysFailure"),
        6: ("AlwaysSuccess", "AlwaysSuccess"),
        7: ("AlwaysSuccess", "ok"),
    }
    root = etree.fromstring(decoded.xml.encode())
    trees = [(e.get("ID"), e.get("_fullpath")) for e in root.findall("BehaviorTree")]
    assert trees == [("Main", ""), ("Sub", "subby")]
    (subtree,) = root.iter("SubTree")
    assert len(subtree) == 0  # its nodes live in their own BehaviorTree element
    model = root.find("TreeNodesModel")
    assert model is not None
    models = {e.get("ID") for e in model}
    assert {"Sequence", "Fallback", "AlwaysSuccess", "AlwaysFailure"} <= models


async def test_btlog_matches_behaviortree_cpp_own_file(tmp_path: Path) -> None:
    btpy = pytest.importorskip("behaviortreepy")
    factory = btpy.BehaviorTreeFactory()
    factory.register_behavior_tree_from_text(DOC)
    cpp_tree = factory.create_tree("Main")
    cpp_path = tmp_path / "cpp.btlog"
    cpp_logger = btpy.FileLogger(cpp_tree, str(cpp_path))
    cpp_tree.tick_once()
    expected_records = 17
    deadline = time.monotonic() + 5.0
    while _record_count(cpp_path) < expected_records:
        assert time.monotonic() < deadline, "BT.CPP's writer thread did not write its records"
        await asyncio.sleep(0.02)  # wall time: its writer thread writes every 10 ms
        cpp_logger.flush()
    del cpp_logger
    tree = BehaviorTreeFactory().create_tree_from_text(DOC, clock=ManualClock())
    ours_path = tmp_path / "ours.btlog"
    with BtlogLogger(tree, ours_path):
        await tree.tick_once()
    cpp = read_btlog(cpp_path.read_bytes())
    ours = read_btlog(ours_path.read_bytes())
    assert cpp.protocol == ours.protocol == 1
    assert [(uid, st) for _, uid, st in ours.records] == [(uid, st) for _, uid, st in cpp.records]
    assert uid_map(ours.xml) == uid_map(cpp.xml)


def test_btlog_rejects_another_extension(tmp_path: Path) -> None:
    tree = BehaviorTreeFactory().create_tree_from_text(DOC)
    with pytest.raises(ValueError, match=r"must end in \.btlog"):
        BtlogLogger(tree, tmp_path / "run.log")
    assert tree.context.listeners == []


async def test_logger_detaches_on_close(tmp_path: Path) -> None:
    tree = BehaviorTreeFactory().create_tree_from_text(DOC)
    logger = BtlogLogger(tree, tmp_path / "a.btlog")
    assert len(tree.context.listeners) == 1
    logger.close()
    logger.close()
    assert tree.context.listeners == []
    await tree.tick_once()
    assert read_btlog((tmp_path / "a.btlog").read_bytes()).records == []


async def test_btlog_writes_every_flush_every_records(tmp_path: Path) -> None:
    tree = BehaviorTreeFactory().create_tree_from_text(DOC)
    path = tmp_path / "batched.btlog"
    with BtlogLogger(tree, path, flush_every=4), TransitionRecorder(tree) as recorder:
        await tree.tick_once()
        total = len(recorder.transitions)
        assert total > 4
        assert _record_count(path) == total - total % 4  # whole batches only
    assert _record_count(path) == total  # the rest on close
