"""The route server's results as ``nav2_msgs`` models."""

from __future__ import annotations

from aiobt.msgs import Path, pose_fields
from aiobt.msgs.geometry import Header, Point
from aiobt.msgs.route import Route as RouteMsg
from aiobt.msgs.route import RouteEdge, RouteNode
from aiobt.msgs.route_graph import RouteGraph

from .dense import Poses
from .graph import Graph, GraphEdge, GraphNode
from .search import Route

ROUTE_FRAME = "map"


def _point(node: GraphNode) -> Point:
    return Point(x=node.x, y=node.y)


def _node(node: GraphNode) -> RouteNode:
    return RouteNode(nodeid=node.nodeid, position=_point(node))


def _edge(edge: GraphEdge) -> RouteEdge:
    return RouteEdge(edgeid=edge.edgeid, start=_point(edge.start), end=_point(edge.end))


def route_msg(route: Route, stamp: float) -> RouteMsg:
    return RouteMsg(
        header=Header(stamp=stamp, frame_id=ROUTE_FRAME),
        route_cost=route.route_cost,
        nodes=[_node(node) for node in route.nodes],
        edges=[_edge(edge) for edge in route.edges],
    )


def graph_msg(graph: Graph | None, stamp: float) -> RouteGraph:
    """The whole graph for viewers; an empty one without a graph."""
    if graph is None:
        return RouteGraph(header=Header(stamp=stamp, frame_id=ROUTE_FRAME))
    return RouteGraph(
        header=Header(stamp=stamp, frame_id=ROUTE_FRAME),
        name=graph.name,
        nodes=[_node(node) for node in graph],
        edges=[_edge(edge) for edge in graph.edges.values()],
    )


def path_msg(poses: Poses, stamp: float) -> Path:
    """The dense path in ``map``, validated as one nested dict (as the planner builds its
    paths: a fraction of building each pose's models one by one)."""
    header = {"stamp": stamp, "frame_id": ROUTE_FRAME}
    return Path.model_validate({
        "header": header,
        "poses": [{"header": header, "pose": pose_fields(x, y, yaw)}
                  for x, y, yaw in poses.tolist()],
    })  # fmt: skip
