"""The route server's results as ``nav2_msgs`` models."""

from __future__ import annotations

from aiobt.msgs import Path
from aiobt.msgs.geometry import Header, Point
from aiobt.msgs.route import Route as RouteMsg
from aiobt.msgs.route import RouteEdge, RouteNode
from aiobt_services.planner.actions import to_path

from .dense import Poses
from .graph import GraphNode
from .search import Route

ROUTE_FRAME = "map"


def _point(node: GraphNode) -> Point:
    return Point(x=node.x, y=node.y)


def route_msg(route: Route, stamp: float) -> RouteMsg:
    return RouteMsg(
        header=Header(stamp=stamp, frame_id=ROUTE_FRAME),
        route_cost=route.route_cost,
        nodes=[RouteNode(nodeid=node.nodeid, position=_point(node)) for node in route.nodes],
        edges=[
            RouteEdge(edgeid=edge.edgeid, start=_point(edge.start), end=_point(edge.end))
            for edge in route.edges
        ],
    )


def path_msg(poses: Poses, stamp: float) -> Path:
    return to_path([(x, y, yaw) for x, y, yaw in poses.tolist()], stamp)
