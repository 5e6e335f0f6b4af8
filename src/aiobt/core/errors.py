"""Errors, each naming where the problem is: file and line, node path, key."""

from __future__ import annotations


class BehaviorTreeError(Exception):
    """Base of every aiobt error."""


class TreeLoadError(BehaviorTreeError):
    """A tree could not be loaded: bad XML, unknown node, bad port, recursion..."""

    def __init__(
        self,
        message: str,
        *,
        file: str | None = None,
        line: int | None = None,
        node_path: str | None = None,
    ) -> None:
        self.message = message
        self.file = file
        self.line = line
        self.node_path = node_path
        where = ":".join(str(p) for p in (file or "<text>", line) if p is not None)
        at = f" (node {node_path})" if node_path else ""
        super().__init__(f"{where}: {message}{at}")


class LogicError(BehaviorTreeError):
    """A tree is used in a way its nodes do not allow (BT.CPP's LogicError)."""


class PortError(BehaviorTreeError):
    """A port was read or written in a way its declaration does not allow."""


class BlackboardError(BehaviorTreeError):
    """A blackboard entry was missing or set with an incompatible type."""


class NodeError(BehaviorTreeError):
    """A node raised while ticking or halting; names the node's path."""

    def __init__(self, node_path: str, cause: BaseException) -> None:
        self.node_path = node_path
        self.cause = cause
        super().__init__(f"node {node_path}: {type(cause).__name__}: {cause}")
