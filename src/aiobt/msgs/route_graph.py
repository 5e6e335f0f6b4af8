"""The route server's graph on the wire: the graph for viewers (Nav2 publishes it as
markers on ``route_graph``), ``nav2_msgs/SetRouteGraph`` and ``nav2_msgs/DynamicEdges``."""

from __future__ import annotations

from typing import ClassVar, TypeAlias

from pydantic import Field

from aiobt.msgs._base import Msg
from aiobt.msgs.geometry import Header
from aiobt.msgs.route import RouteEdge, RouteNode


class RouteGraph(Msg):
    """Every node and directed edge of the route server's graph (latched on
    ``{ns}/route_graph``); empty when the server has no graph."""

    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    name: str = ""
    nodes: list[RouteNode] = Field(default_factory=list)
    edges: list[RouteEdge] = Field(default_factory=list)


class _SetRouteGraphRequest(Msg):
    graph_filepath: str


class _SetRouteGraphResponse(Msg):
    success: bool = False
    message: str = ""  # aiobt's addition: why it failed


class SetRouteGraph:
    """``nav2_msgs/SetRouteGraph`` (``route_server/set_route_graph``): load another graph.
    As in Nav2, the graph in use is dropped first: after a failure there is none."""

    service_name: ClassVar[str] = "route_server/set_route_graph"
    Request: TypeAlias = _SetRouteGraphRequest
    Response: TypeAlias = _SetRouteGraphResponse


class EdgeCost(Msg):
    """``nav2_msgs/EdgeCost``: a cost for one edge."""

    edgeid: int = Field(ge=0)
    cost: float


class _DynamicEdgesRequest(Msg):
    closed_edges: list[int] = Field(default_factory=list)
    opened_edges: list[int] = Field(default_factory=list)
    adjust_edges: list[EdgeCost] = Field(default_factory=list)


class _DynamicEdgesResponse(Msg):
    success: bool = False


class DynamicEdges:
    """``nav2_msgs/DynamicEdges`` (``route_server/DynamicEdgesScorer/adjust_edges``):
    close edges, reopen them, set their costs, from a third party (a fleet manager)."""

    service_name: ClassVar[str] = "route_server/DynamicEdgesScorer/adjust_edges"
    Request: TypeAlias = _DynamicEdgesRequest
    Response: TypeAlias = _DynamicEdgesResponse
