"""Nav2's route messages (``nav2_msgs/Route``): what the route server returns."""

from __future__ import annotations

from typing import ClassVar

from pydantic import Field

from aiobt.msgs._base import Msg
from aiobt.msgs.geometry import Header, Point


class RouteNode(Msg):
    """``nav2_msgs/RouteNode``: a node of the route graph."""

    nodeid: int = Field(default=0, ge=0)
    position: Point = Field(default_factory=Point)


class RouteEdge(Msg):
    """``nav2_msgs/RouteEdge``: an edge between two route nodes."""

    edgeid: int = Field(default=0, ge=0)
    start: Point = Field(default_factory=Point)
    end: Point = Field(default_factory=Point)


class Route(Msg):
    """``nav2_msgs/Route``: the ordered nodes and edges of a route, and its cost."""

    __bt_type_name__: ClassVar[str] = "nav2_msgs::msg::Route"

    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    route_cost: float = 0.0
    nodes: list[RouteNode] = Field(default_factory=list)
    edges: list[RouteEdge] = Field(default_factory=list)
