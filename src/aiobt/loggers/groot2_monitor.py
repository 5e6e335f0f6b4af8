"""Groot2's requests answered for one tree, with no sockets (those are in :mod:`.groot2`).

:meth:`Groot2Monitor.handle` takes a request's frames and returns the reply's.
The status buffer starts from the nodes' current statuses, so a Groot2
attaching to a running tree sees RUNNING nodes as RUNNING at once (BT.CPP
starts from all IDLE). Entries are in BT.CPP's order: the main tree's nodes,
then each subtree instance's.
"""

from __future__ import annotations

import json
import logging
import time
from collections import deque
from collections.abc import Callable

from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.loggers.groot2_blackboard import dump_blackboards, instance_blackboards
from aiobt.loggers.groot2_hooks import HookTable
from aiobt.loggers.groot2_protocol import (
    HEADER,
    MAX_UID,
    NEEDS_TWO_PARTS,
    NOT_RECOGNIZED,
    STATUS_ENTRY,
    WRONG_HEADER,
    ProtocolError,
    RequestType,
    error_reply,
    new_tree_uuid,
    pack_transitions,
    parse_hook_key,
    parse_hooks,
    parse_unlock,
    reply_header,
    status_code,
)
from aiobt.loggers.observer import StatusObserver
from aiobt.loggers.tree_xml import subtree_instances, tree_to_xml

log = logging.getLogger("aiobt.loggers.groot2")

_WITH_PAYLOAD = {
    RequestType.BLACKBOARD,
    RequestType.HOOK_INSERT,
    RequestType.HOOK_REMOVE,
    RequestType.BREAKPOINT_UNLOCK,
    RequestType.TOGGLE_RECORDING,
}


def groot2_node_order(tree: Tree) -> list[TreeNode]:
    """Every node, main tree first, then each subtree instance (BT.CPP's order)."""
    return [node for instance in subtree_instances(tree) for node in instance.nodes()]


class Groot2Monitor(StatusObserver):
    """Answers Groot2 for ``tree``; ``notify(frames)`` publishes hook hits.

    ``max_transitions`` bounds the recording buffer between two GET_TRANSITIONS
    (BT.CPP keeps 1000; the oldest go first).
    """

    def __init__(
        self,
        tree: Tree,
        notify: Callable[[int], None],
        *,
        max_transitions: int = 100_000,
    ) -> None:
        nodes = groot2_node_order(tree)
        for node in nodes:
            if not 0 < node.uid <= MAX_UID:
                raise ValueError(
                    f"Groot2: node {node.path} has uid {node.uid}; Groot2's protocol needs "
                    f"uids 1..{MAX_UID}, as the factory numbers them"
                )
        self.uuid = new_tree_uuid()
        self.xml = tree_to_xml(tree, builtin_models=True).encode()
        self._status = bytearray(STATUS_ENTRY.size * len(nodes))
        self._offset: dict[int, int] = {}
        for index, node in enumerate(nodes):
            offset = index * STATUS_ENTRY.size
            STATUS_ENTRY.pack_into(self._status, offset, node.uid, node.status.value)
            self._offset[node.uid] = offset + 2
        self._blackboards = instance_blackboards(tree)
        self.hooks = HookTable(tree, {node.uid: node for node in nodes}, notify)
        self._recording_start: float | None = None
        self._transitions: deque[tuple[int, int, int]] = deque(maxlen=max_transitions)
        super().__init__(tree)

    def on_transition(self, stamp: float, node: TreeNode, previous: Status, status: Status) -> None:
        offset = self._offset.get(node.uid)
        if offset is not None:
            self._status[offset] = status_code(previous, status)
        if self._recording_start is not None:
            since = round((stamp - self._recording_start) * 1e6)
            self._transitions.append((since, node.uid, status.value))

    def close(self) -> None:
        """Remove every hook (freeing a held breakpoint) and detach from the tree."""
        self.hooks.remove_all()
        super().close()

    # -- requests -----------------------------------------------------------------------
    def handle(self, frames: list[bytes]) -> list[bytes]:
        """The reply to one request; bad requests get BT.CPP's error replies."""
        header = frames[0] if frames else b""
        if len(header) != HEADER.size:
            return error_reply(WRONG_HEADER)
        _, kind, _ = HEADER.unpack(header)
        if kind not in RequestType._value2member_map_ or kind == RequestType.BREAKPOINT_REACHED:
            return error_reply(NOT_RECOGNIZED)
        request = RequestType(kind)
        if request in _WITH_PAYLOAD and len(frames) != 2:
            return error_reply(NEEDS_TWO_PARTS)
        try:
            payload = self._answer(request, frames[1] if len(frames) > 1 else b"")
        except ProtocolError as exc:
            log.warning("Groot2 %s request refused: %s", request.name, exc)
            return error_reply(str(exc))
        reply = [reply_header(header, self.uuid)]
        return reply if payload is None else [*reply, payload]

    def _answer(self, request: RequestType, payload: bytes) -> bytes | None:
        if request is RequestType.FULLTREE:
            return self.xml
        if request is RequestType.STATUS:
            return bytes(self._status)
        if request is RequestType.BLACKBOARD:
            return dump_blackboards(self._blackboards, payload.decode(errors="replace"))
        if request is RequestType.GET_TRANSITIONS:
            transitions = list(self._transitions)
            self._transitions.clear()
            return pack_transitions(transitions)
        if request is RequestType.TOGGLE_RECORDING:
            return self._toggle_recording(payload)
        self._hook_request(request, payload)
        return self._hooks_json() if request is RequestType.HOOKS_DUMP else None

    def _hook_request(self, request: RequestType, payload: bytes) -> None:
        if request is RequestType.HOOK_INSERT:
            for hook in parse_hooks(payload):
                self.hooks.insert(hook)
        elif request is RequestType.HOOK_REMOVE:
            uid, _ = parse_hook_key(payload, "hook remove")
            self.hooks.remove(uid)
        elif request is RequestType.BREAKPOINT_UNLOCK:
            self.hooks.unlock(*parse_unlock(payload))
        elif request is RequestType.REMOVE_ALL_HOOKS:
            self.hooks.remove_all()
        elif request is RequestType.DISABLE_ALL_HOOKS:
            self.hooks.enable_all(False)

    def _hooks_json(self) -> bytes:
        hooks = [hook.to_json() for hook in self.hooks.dump()]
        return json.dumps(hooks, separators=(",", ":")).encode()

    def _toggle_recording(self, payload: bytes) -> bytes | None:
        if payload == b"start":
            self._recording_start = self.tree.clock.now()
            self._transitions.clear()
            return str(time.time_ns() // 1000).encode()
        if payload == b"stop":
            self._recording_start = None
            return None
        raise ProtocolError(f"toggle recording: expected 'start' or 'stop', got {payload!r}")
