"""What a route operation sees (:class:`Event`) and gives back (:class:`OperationResult`),
and when it runs (:data:`ProcessType`): the shapes every operation module shares."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

from .graph import GraphEdge, GraphNode, Metadata
from .search import Route
from .vectors import XY

ProcessType = Literal["ON_GRAPH", "ON_STATUS_CHANGE", "ON_QUERY"]


@dataclass(frozen=True, slots=True)
class Event:
    """What an operation sees: the node achieved, edges entered and exited, the route,
    the robot's position and robot time, and the graph operation's metadata."""

    node: GraphNode | None
    edge_entered: GraphEdge | None
    edge_exited: GraphEdge | None
    route: Route
    pose: XY
    now: float
    metadata: Metadata = field(default_factory=dict)


@dataclass(slots=True)
class OperationResult:
    reroute: bool = False
    blocked_ids: list[int] = field(default_factory=list)
