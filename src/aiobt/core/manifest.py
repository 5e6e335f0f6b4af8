"""Node manifests: what the factory knows about each registered node ID."""

from __future__ import annotations

import functools
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from aiobt.core.node import NodeConfig, NodeKind, TreeNode
from aiobt.core.ports import PortInfo
from aiobt.core.status import Status

NodeBuilder = Callable[[str, NodeConfig], TreeNode]


@dataclass(slots=True)
class NodeManifest:
    """A registered node: its XML ID, kind, ports and how to build it."""

    id: str
    kind: str
    ports: dict[str, PortInfo]
    builder: NodeBuilder
    description: str = ""
    builtin: bool = False
    node_class: type[TreeNode] | None = None

    @property
    def child_range(self) -> tuple[int, int | None]:
        """(minimum, maximum) number of children; None is unbounded."""
        if self.kind == NodeKind.CONTROL:
            minimum = getattr(self.node_class, "MIN_CHILDREN", 1)
            return (minimum, getattr(self.node_class, "MAX_CHILDREN", None))
        if self.kind in (NodeKind.DECORATOR, NodeKind.SUBTREE):
            return (1, 1)
        return (0, 0)


def ports_dict(ports: tuple[PortInfo, ...] | list[PortInfo]) -> dict[str, PortInfo]:
    return {port.name: port for port in ports}


@dataclass(frozen=True, slots=True)
class TestNodeConfig:
    """What a substituted test node does (BT.CPP's TestNodeConfig).

    It returns ``status`` after ``delay`` seconds of clock time (0: at once),
    and runs ``on_complete(node)`` when it finishes, if given.
    """

    __test__ = False  # not a pytest test class

    status: Status = Status.SUCCESS
    delay: float = 0.0
    on_complete: Callable[[TreeNode], Any] | None = None


Substitution = str | TestNodeConfig


@functools.lru_cache(maxsize=256)
def _wildcard(pattern: str) -> re.Pattern[str]:
    """BT.CPP's wildcards: ``*`` any text, ``?`` one character; everything else,
    brackets included (``Sequence[main]`` in node paths), is literal."""
    parts = (".*" if c == "*" else "." if c == "?" else re.escape(c) for c in pattern)
    return re.compile("".join(parts), re.DOTALL)


@dataclass(slots=True)
class SubstitutionRules:
    """Wildcard patterns over node paths, names or IDs, mapped to replacements."""

    rules: list[tuple[str, Substitution]] = field(default_factory=list)

    def add(self, pattern: str, replacement: Substitution) -> None:
        self.rules.append((pattern, replacement))

    def match(self, path: str, name: str, node_id: str) -> Substitution | None:
        for pattern, replacement in self.rules:
            regex = _wildcard(pattern)
            if any(regex.fullmatch(text) for text in (path, name, node_id)):
                return replacement
        return None

    def __bool__(self) -> bool:
        return bool(self.rules)
