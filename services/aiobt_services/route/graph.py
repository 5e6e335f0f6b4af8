"""The route graph: nodes with coordinates, directed edges, metadata and operations.

As Nav2's ``nav2_route::Graph``: every edge is directional (a two-way lane is two
edges), belongs to its start node, and carries an optional fixed ``cost`` (used
when it is not ``overridable`` or no scorer is set) plus arbitrary ``metadata``.
Coordinates are also kept as one numpy array for nearest-node look-ups.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

Trigger = Literal["NODE", "ON_ENTER", "ON_EXIT"]
TRIGGERS: tuple[Trigger, ...] = ("NODE", "ON_ENTER", "ON_EXIT")
Metadata = dict[str, Any]


@dataclass(frozen=True, slots=True)
class Operation:
    """An operation the graph asks for at a node (``NODE``) or edge (``ON_ENTER``/``ON_EXIT``)."""

    type: str
    trigger: Trigger
    metadata: Metadata = field(default_factory=dict)


@dataclass(eq=False, slots=True)
class GraphNode:
    nodeid: int
    x: float
    y: float
    metadata: Metadata = field(default_factory=dict)
    operations: tuple[Operation, ...] = ()
    edges: list[GraphEdge] = field(default_factory=list)  # the edges leaving this node


@dataclass(eq=False, slots=True)
class GraphEdge:
    edgeid: int
    start: GraphNode
    end: GraphNode
    cost: float = 0.0  # the file's fixed cost; 0 = none given
    overridable: bool = True  # whether the edge scorers may score it
    metadata: Metadata = field(default_factory=dict)
    operations: tuple[Operation, ...] = ()

    @property
    def length(self) -> float:
        return math.hypot(self.end.x - self.start.x, self.end.y - self.start.y)


def metadata_float(holder: GraphNode | GraphEdge, tag: str, default: float) -> float:
    """Metadata ``tag`` as a number (Nav2's ``getValue<float>``); ``default`` if absent or
    not a number."""
    value = holder.metadata.get(tag, default)
    if isinstance(value, bool) or not isinstance(value, int | float):
        return default
    return float(value)


class Graph:
    """Nodes and edges by id; ``xy`` is an ``(n, 2)`` array of node coordinates in
    node order (``nodes``)."""

    __slots__ = ("_index", "edges", "name", "nodes", "xy")

    def __init__(self, nodes: list[GraphNode], edges: list[GraphEdge], name: str = "") -> None:
        self.name = name
        self.nodes = nodes
        self.edges = {edge.edgeid: edge for edge in edges}
        self._index = {node.nodeid: node for node in nodes}
        self.xy: npt.NDArray[np.float64] = np.array(
            [(node.x, node.y) for node in nodes], dtype=np.float64
        ).reshape(-1, 2)

    def __len__(self) -> int:
        return len(self.nodes)

    def __iter__(self) -> Iterator[GraphNode]:
        return iter(self.nodes)

    def node(self, nodeid: int) -> GraphNode | None:
        return self._index.get(nodeid)

    def nearest(self, x: float, y: float, count: int = 1) -> list[GraphNode]:
        """The ``count`` nodes nearest (x, y), nearest first (Nav2's kd-tree query)."""
        if not self.nodes:
            return []
        dist = np.hypot(self.xy[:, 0] - x, self.xy[:, 1] - y)
        order = np.argsort(dist, kind="stable")[: max(1, count)]
        return [self.nodes[int(i)] for i in order]
