"""Groot2's hooks: breakpoints and replacements placed on nodes of a running tree.

A hook runs where BT.CPP runs its pre-tick callback: after the node's
pre-conditions (``_skipIf`` ...) found nothing to decide, and only while the
node is IDLE or RUNNING. It is installed through the node's conditions slot
(:class:`HookedConditions` wraps the node's own), so no tick path changes.

A hit publishes a notification. A replacement returns its desired status at
once. A breakpoint cannot block inside a synchronous tick without blocking the
event loop, so it *holds* instead: the node is not ticked and reports RUNNING
to its parent (its own status stays what it was, as Groot2 shows it in
BT.CPP), the tick unwinds and the tree is paused, which suspends only the
coroutine ticking it. The unlock resumes the tree; the next tick reaches the
node again and the hook gives it the unlock's status (SUCCESS or FAILURE
replace the tick, SKIPPED lets it tick). Reactive parents re-check their
conditions on that tick, as they would on any tick. A RUNNING node whose tick
is replaced is halted first (BT.CPP only overwrites its status), so that an
async leaf's task does not run on unseen.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

from aiobt.core.conditions import NodeConditions
from aiobt.core.node import TreeNode
from aiobt.core.status import FAILURE, RUNNING, SUCCESS, Status
from aiobt.core.tree import Tree
from aiobt.loggers.groot2_protocol import NODE_NOT_FOUND, Hook, HookMode, ProtocolError

_REPLACING = (SUCCESS, FAILURE)


class HookedConditions(NodeConditions):
    """A node's own pre/post conditions, with a hook checked before its tick."""

    __slots__ = ("gate", "original")

    def __init__(self, original: NodeConditions | None, gate: Callable[[], Status | None]) -> None:
        fields = dataclasses.fields(NodeConditions)
        values = {f.name: getattr(original, f.name) for f in fields} if original else {}
        super().__init__(**values)
        self.original = original
        self.gate = gate

    def tick_sync(self, node: TreeNode) -> Status:
        pre = self._decide(node)
        if pre is None and not node.status.is_completed:
            pre = self.gate()
            if pre is RUNNING:  # held at a breakpoint: the node is not ticked
                return RUNNING
            if pre is not None and node.status is RUNNING:
                node.halt_sync()  # its work stops: an async leaf's task is cancelled
        if pre is not None:
            return self._settle(node, pre)
        return self._execute(node)


class HookTable:
    """The hooks of one tree, keyed by node uid (BT.CPP 4.8 keeps pre-tick hooks only)."""

    def __init__(self, tree: Tree, nodes: dict[int, TreeNode], notify: Callable[[int], None]):
        self._tree = tree
        self._nodes = nodes
        self._notify = notify
        self._hooks: dict[int, Hook] = {}
        self._paused_by_us = False

    def insert(self, hook: Hook) -> None:
        node = self._node(hook.uid)
        existing = self._hooks.get(hook.uid)
        if existing is not None:
            was_breakpoint = existing.mode is HookMode.BREAKPOINT
            existing.mode, existing.enabled = hook.mode, hook.enabled
            existing.once, existing.desired_status = hook.once, hook.desired_status
            existing.position = hook.position
            if was_breakpoint and hook.mode is HookMode.REPLACE and existing.held:
                self._release(existing)
            return
        self._hooks[hook.uid] = hook
        node.attach_conditions(HookedConditions(node._conditions, lambda: self._gate(hook)))

    def remove(self, uid: int) -> None:
        node = self._node(uid)
        hook = self._hooks.pop(uid, None)
        if hook is None:
            raise ProtocolError(NODE_NOT_FOUND)
        hook.enabled = False
        hooked = node._conditions
        if isinstance(hooked, HookedConditions):
            node.attach_conditions(hooked.original)
        self._resume_if_free()

    def unlock(self, uid: int, status: Status, remove: bool) -> None:
        self._node(uid)
        hook = self._hooks.get(uid)
        if hook is None:
            raise ProtocolError(NODE_NOT_FOUND)
        hook.desired_status = status
        hook.once |= remove
        if hook.mode is HookMode.BREAKPOINT:
            self._release(hook)

    def remove_all(self) -> None:
        for uid in list(self._hooks):
            self.remove(uid)

    def enable_all(self, enabled: bool) -> None:
        """Enable or disable every hook; disabling frees held breakpoints (tick as usual)."""
        for hook in self._hooks.values():
            hook.enabled = enabled
            if not enabled:
                hook.held = hook.released = False
        self._resume_if_free()

    def dump(self) -> list[Hook]:
        return list(self._hooks.values())

    @property
    def holding(self) -> bool:
        return any(hook.held for hook in self._hooks.values())

    # -- inside the tick ----------------------------------------------------------------
    def _gate(self, hook: Hook) -> Status | None:
        """The hook's verdict on one tick: None to tick, RUNNING to hold, or a result."""
        if not hook.enabled or self._hooks.get(hook.uid) is not hook:
            return None
        if not hook.held and not hook.released:
            self._notify(hook.uid)
        if hook.mode is HookMode.BREAKPOINT and not hook.released:
            if not hook.held:
                hook.held = True
                self._pause(self._nodes[hook.uid])
            return RUNNING
        hook.released = False
        result = hook.desired_status
        if hook.once:
            self.remove(hook.uid)
        return result if result in _REPLACING else None

    def _release(self, hook: Hook) -> None:
        hook.held, hook.released = False, True
        self._resume_if_free()

    def _pause(self, node: TreeNode) -> None:
        if not self._tree.paused:
            self._paused_by_us = True
            self._tree.pause(f"Groot2 breakpoint at {node.path} (uid {node.uid})")

    def _resume_if_free(self) -> None:
        if self._paused_by_us and not self.holding:
            self._paused_by_us = False
            self._tree.resume("Groot2 breakpoint released")

    def _node(self, uid: int) -> TreeNode:
        node = self._nodes.get(uid)
        if node is None:
            raise ProtocolError(NODE_NOT_FOUND)
        return node
