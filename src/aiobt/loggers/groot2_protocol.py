"""Groot2's live-monitoring wire format, as BehaviorTree.CPP 4.8 speaks it.

Pure encoding and decoding, no sockets (see :mod:`aiobt.loggers.groot2`).

- A request is multipart: a 6-byte header (protocol ``u8`` = 2, request type
  ``u8``, a ``u32`` unique id, little-endian), and for some types a payload
  frame.
- A reply is the request header (protocol forced to 2) followed by the
  tree's 16-byte UUID in one 22-byte frame, then the payload frame if any.
- An error reply is ``[b"error", message]``, with no header.
- A hook hit is published as ``[6-byte header of type 'N', str(uid)]``.
"""

from __future__ import annotations

import json
import random
import struct
import uuid
from dataclasses import dataclass
from enum import IntEnum
from typing import Any

from aiobt.core.status import Status

PROTOCOL = 2
HEADER = struct.Struct("<BBI")
STATUS_ENTRY = struct.Struct("<HB")
MAX_UID = 0xFFFF
_TRANSITION_TAIL = struct.Struct("<HB")
_SIX_BYTES = (1 << 48) - 1

# BT.CPP's error replies, word for word (Groot2 shows them)
WRONG_HEADER = "wrong request header"
NOT_RECOGNIZED = "Request not recognized"
NEEDS_TWO_PARTS = "must be 2 parts message"
NODE_NOT_FOUND = "Node ID not found"


class RequestType(IntEnum):
    FULLTREE = ord("T")
    STATUS = ord("S")
    BLACKBOARD = ord("B")
    HOOK_INSERT = ord("I")
    HOOK_REMOVE = ord("R")
    BREAKPOINT_REACHED = ord("N")
    BREAKPOINT_UNLOCK = ord("U")
    HOOKS_DUMP = ord("D")
    REMOVE_ALL_HOOKS = ord("A")
    DISABLE_ALL_HOOKS = ord("X")
    TOGGLE_RECORDING = ord("r")
    GET_TRANSITIONS = ord("t")


class ProtocolError(ValueError):
    """A request Groot2's protocol cannot serve; its text goes back as an error reply."""


class HookMode(IntEnum):
    BREAKPOINT = 0
    REPLACE = 1


def new_tree_uuid() -> bytes:
    """A random (version 4) UUID naming one publisher's tree."""
    return uuid.uuid4().bytes


def reply_header(request: bytes, tree_uuid: bytes) -> bytes:
    """The 22-byte first frame of a reply to the 6-byte ``request`` header."""
    return bytes((PROTOCOL,)) + request[1:6] + tree_uuid


def error_reply(message: str) -> list[bytes]:
    return [b"error", message.encode()]


def request_header(kind: RequestType, unique_id: int | None = None) -> bytes:
    """A request header (the PUB notification uses one with type 'N')."""
    if unique_id is None:
        unique_id = random.getrandbits(32)
    return HEADER.pack(PROTOCOL, kind, unique_id)


def notification(uid: int) -> list[bytes]:
    """What the PUB socket sends when the hook of node ``uid`` is hit."""
    return [request_header(RequestType.BREAKPOINT_REACHED), str(uid).encode()]


def status_code(previous: Status, status: Status) -> int:
    """BT.CPP's status byte: a node back to IDLE reports 10 + where it came from."""
    if status is Status.IDLE:
        return 10 + int(previous.value) if previous is not Status.IDLE else 0
    return int(status.value)


def pack_transitions(transitions: list[tuple[int, int, int]]) -> bytes:
    """9 bytes per (µs since recording started, uid, status): 6-byte time, u16, u8."""
    out = bytearray()
    for stamp_us, uid, status in transitions:
        out += (min(max(stamp_us, 0), _SIX_BYTES)).to_bytes(6, "little")
        out += _TRANSITION_TAIL.pack(uid, status)
    return bytes(out)


# -- hooks ------------------------------------------------------------------------------


@dataclass(slots=True)
class Hook:
    """A breakpoint (waits for an unlock) or a replacement (returns at once).

    ``desired_status`` SUCCESS or FAILURE replaces the node's tick; SKIPPED
    (or anything else) lets the node tick as usual. ``once`` removes the hook
    after its first use.
    """

    uid: int
    mode: HookMode = HookMode.BREAKPOINT
    enabled: bool = True
    once: bool = False
    desired_status: Status = Status.SKIPPED
    position: int = 0
    held: bool = False
    released: bool = False

    def to_json(self) -> dict[str, Any]:
        return {
            "desired_status": self.desired_status.name,
            "enabled": self.enabled,
            "mode": int(self.mode),
            "once": self.once,
            "position": self.position,
            "uid": self.uid,
        }


def _field(obj: dict[str, Any], key: str, kind: type | tuple[type, ...], what: str) -> Any:
    if key not in obj:
        raise ProtocolError(f"{what}: missing key [{key}] in {json.dumps(obj)}")
    value = obj[key]
    if not isinstance(value, kind) or (kind is int and isinstance(value, bool)):
        raise ProtocolError(f"{what}: key [{key}] has the wrong type in {json.dumps(obj)}")
    return value


def _uid(obj: dict[str, Any], what: str) -> int:
    uid: int = _field(obj, "uid", int, what)
    if not 0 <= uid <= MAX_UID:
        raise ProtocolError(f"{what}: uid {uid} is not a 16-bit node uid")
    return uid


def parse_status(text: str, what: str) -> Status:
    status = Status.__members__.get(text)
    if status is None:
        raise ProtocolError(f"{what}: desired_status {text!r} is not a node status")
    return status


def parse_json(payload: bytes, what: str) -> Any:
    try:
        return json.loads(payload)
    except (ValueError, UnicodeDecodeError) as exc:
        raise ProtocolError(f"{what}: the payload is not JSON: {exc}") from exc


def _object(value: Any, what: str) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise ProtocolError(f"{what}: expected a JSON object, got {json.dumps(value)}")
    return value


def parse_hooks(payload: bytes) -> list[Hook]:
    """HOOK_INSERT's payload: one hook object or an array of them."""
    what = "hook insert"
    data = parse_json(payload, what)
    items = data if isinstance(data, list) else [data]
    hooks = []
    for item in items:
        obj = _object(item, what)
        mode = _field(obj, "mode", int, what)
        if mode not in (0, 1):
            raise ProtocolError(f"{what}: mode {mode} is neither 0 (breakpoint) nor 1 (replace)")
        hooks.append(
            Hook(
                uid=_uid(obj, what),
                mode=HookMode(mode),
                enabled=_field(obj, "enabled", bool, what),
                once=_field(obj, "once", bool, what),
                desired_status=parse_status(_field(obj, "desired_status", str, what), what),
                position=_field(obj, "position", int, what),
            )
        )
    return hooks


def parse_hook_key(payload: bytes, what: str) -> tuple[int, int]:
    """The (uid, position) of HOOK_REMOVE or BREAKPOINT_UNLOCK."""
    obj = _object(parse_json(payload, what), what)
    return _uid(obj, what), _field(obj, "position", int, what)


def parse_unlock(payload: bytes) -> tuple[int, Status, bool]:
    """BREAKPOINT_UNLOCK: (uid, status to return, remove the hook when done).

    As in BT.CPP, a desired_status other than SUCCESS or FAILURE means
    "tick the node as usual" (SKIPPED).
    """
    what = "breakpoint unlock"
    obj = _object(parse_json(payload, what), what)
    uid, _ = parse_hook_key(payload, what)
    text = _field(obj, "desired_status", str, what)
    status = {"SUCCESS": Status.SUCCESS, "FAILURE": Status.FAILURE}.get(text, Status.SKIPPED)
    return uid, status, _field(obj, "remove_when_done", bool, what)
