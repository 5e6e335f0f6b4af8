"""Groot2's BLACKBOARD reply: the entries of the subtree instances asked for, in MessagePack.

As BT.CPP 4.8 does: ``{instance name: {key: value}}`` for every name found
(the main tree is named by its tree ID, a subtree instance by its full
path), names not found left out, ``nil`` for an empty instance and when
none was found. An instance
shows its local entries only; a port remapped to the parent shows in the
parent's dump. Values are made plain for MessagePack (numbers, text, lists,
maps; pydantic models and dataclasses as maps; enums by name); a value with no
plain form is ``nil``, as an entry of a type BT.CPP cannot export to JSON.
"""

from __future__ import annotations

import dataclasses
import enum
import math
import struct
from typing import Any

import msgpack
from pydantic import BaseModel

from aiobt.core.blackboard import Blackboard
from aiobt.core.tree import Tree
from aiobt.loggers.tree_xml import subtree_instances

_SCALARS = (bool, int, float, str, bytes, type(None))
_FLOAT32_MAX = 3.4028234663852886e38
_DOUBLE = msgpack.Packer(use_bin_type=True)
_SINGLE = msgpack.Packer(use_bin_type=True, use_single_float=True)


def instance_blackboards(tree: Tree) -> dict[str, Blackboard]:
    """Blackboard of each subtree instance, under the name Groot2 asks for it by."""
    found: dict[str, Blackboard] = {}
    for instance in subtree_instances(tree):
        if instance.top is None:
            continue
        found[instance.fullpath or instance.tree_id] = instance.top.config.blackboard
    return found


def _remapped(blackboard: Blackboard, key: str) -> bool:
    if blackboard.parent is None:
        return False
    return key in blackboard.remapping or (blackboard.autoremap and not key.startswith("_"))


def plain(value: Any) -> Any:
    """``value`` as MessagePack can carry it, or None."""
    if isinstance(value, _SCALARS):
        return value
    if isinstance(value, enum.Enum):
        return value.name
    if isinstance(value, list | tuple):
        return [plain(item) for item in value]
    if isinstance(value, dict):
        return {str(key): plain(item) for key, item in value.items()}
    if isinstance(value, BaseModel):
        return value.model_dump(mode="json")
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return plain(dataclasses.asdict(value))
    tolist = getattr(value, "tolist", None)  # numpy arrays and scalars
    return plain(tolist()) if callable(tolist) else None


def local_entries(blackboard: Blackboard) -> dict[str, Any]:
    """The entries this scope owns, sorted by key (BT.CPP's JSON maps are sorted)."""
    entries = {
        key: plain(entry.value) if entry.has_value else None
        for key, entry in blackboard.items()
        if not _remapped(blackboard, key)
    }
    return dict(sorted(entries.items()))


def dump_blackboards(blackboards: dict[str, Blackboard], names: str) -> bytes:
    """MessagePack of the instances named in ``names`` (``"a;b"``)."""
    dump = {
        name: local_entries(blackboards[name]) or None  # BT.CPP's empty JSON is null
        for name in names.split(";")
        if name in blackboards
    }
    return pack(dict(sorted(dump.items())) or None)


def pack(value: Any) -> bytes:
    """MessagePack as nlohmann::json writes it: a float that a 32-bit float holds
    exactly is written as one (BT.CPP's dump is byte for byte the same)."""
    if isinstance(value, dict):
        header: bytes = _DOUBLE.pack_map_header(len(value))
        return header + b"".join(pack(key) + pack(item) for key, item in value.items())
    if isinstance(value, list):
        header = _DOUBLE.pack_array_header(len(value))
        return header + b"".join(pack(item) for item in value)
    if isinstance(value, float) and _fits_float32(value):
        return _single(value)
    packed: bytes = _DOUBLE.pack(value)
    return packed


def _fits_float32(value: float) -> bool:
    if not math.isfinite(value):
        return True
    if abs(value) > _FLOAT32_MAX:
        return False
    single: float = struct.unpack("<f", struct.pack("<f", value))[0]
    return single == value


def _single(value: float) -> bytes:
    packed: bytes = _SINGLE.pack(value)
    return packed
