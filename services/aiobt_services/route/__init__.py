"""The route server, as Nav2's ``nav2_route``: route graphs (Nav2 GeoJSON), the search
with edge scorers, the dense path, route tracking and operations (pure logic here;
Zenoh only in ``main`` and ``service``)."""

from .errors import GraphError, RouteError
from .geojson import load_graph, parse_graph
from .graph import Graph, GraphEdge, GraphNode, Operation
from .planning import RouteParams, RoutePlanner
from .search import Route, find_route

__all__ = [
    "Graph",
    "GraphEdge",
    "GraphError",
    "GraphNode",
    "Operation",
    "Route",
    "RouteError",
    "RouteParams",
    "RoutePlanner",
    "find_route",
    "load_graph",
    "parse_graph",
]
