"""Groot2-replayable ``.btlog`` files (BT.CPP 4's FileLogger2 format).

Layout, little-endian::

    b"BTCPP4-FileLogger2"  protocol byte (1)
    int32 XML length, tree XML with _uid attributes (see tree_xml)
    int64 first time stamp, microseconds since the Unix epoch
    then per transition 9 bytes: 6-byte µs offset from the first time stamp,
    uint16 node uid, uint8 status (IDLE 0, RUNNING 1, SUCCESS 2, FAILURE 3, SKIPPED 4)

Offsets are measured on the tree's clock, so a run on a ManualClock or a
scaled clock replays at robot time. Transitions to IDLE are recorded too, as
BT.CPP does.
"""

from __future__ import annotations

import struct
from pathlib import Path

from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.loggers.observer import StatusObserver
from aiobt.loggers.tree_xml import tree_to_xml

MAGIC = b"BTCPP4-FileLogger2"
PROTOCOL = 1
_RECORD = struct.Struct("<IHHB")  # offset low 32 bits, offset high 16 bits, uid, status
_MAX_OFFSET = (1 << 48) - 1


class BtlogLogger(StatusObserver):
    """Writes ``tree``'s transitions to ``path`` (must end in ``.btlog``).

    Records are packed into a buffer and written every ``flush_every``
    records and on :meth:`flush`/:meth:`close`.
    """

    def __init__(self, tree: Tree, path: str | Path, *, flush_every: int = 1024) -> None:
        self.path = Path(path)
        if self.path.suffix != ".btlog":
            raise ValueError(f"BtlogLogger: the file name must end in .btlog, not {self.path.name}")
        for node in tree.nodes():
            if not 0 <= node.uid <= 0xFFFF:
                raise ValueError(f"BtlogLogger: uid {node.uid} of {node.path} does not fit 16 bits")
        self._buffer = bytearray()
        self._flush_bytes = flush_every * _RECORD.size
        xml = tree_to_xml(tree).encode("utf-8")
        self._file = self.path.open("wb")
        super().__init__(tree)
        self._file.write(MAGIC + bytes((PROTOCOL,)) + struct.pack("<i", len(xml)) + xml)
        self._file.write(struct.pack("<q", self.epoch_us))

    def on_transition(self, stamp: float, node: TreeNode, previous: Status, status: Status) -> None:
        offset = min(self.offset_us(stamp), _MAX_OFFSET)
        self._buffer += _RECORD.pack(offset & 0xFFFFFFFF, offset >> 32, node.uid, status.value)
        if len(self._buffer) >= self._flush_bytes:
            self.flush()

    def flush(self) -> None:
        if self._buffer and not self._file.closed:
            self._file.write(self._buffer)
            self._buffer.clear()
            self._file.flush()

    def close(self) -> None:
        super().close()
        self._file.close()
