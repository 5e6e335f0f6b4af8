"""Nav2's ``RouteTracker`` state: which node the robot heads for, which edge it is on,
and when it has achieved a node.

A node is achieved once the robot, having come within ``radius_to_achieve_node``
(``boundary_radius_to_achieve_node`` for the route's last node, or its first when
no edge is being continued), either leaves that radius again or crosses the line
through the node orthogonal to the bisector of the edges before and after it
(Nav2's refined criterion); at the boundary nodes being within the radius is
enough; being within 0.1 mm always is. Pure state: the server feeds poses.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .graph import GraphEdge, GraphNode
from .intent import ReroutingState
from .search import Route
from .vectors import XY, normalized_dot


@dataclass(frozen=True, slots=True)
class TrackerParams:
    radius_to_achieve_node: float = 2.0
    boundary_radius_to_achieve_node: float = 1.0
    tracker_update_rate: float = 50.0
    aggregate_blocked_ids: bool = False

    def __post_init__(self) -> None:
        for name in ("radius_to_achieve_node", "boundary_radius_to_achieve_node",
                     "tracker_update_rate"):  # fmt: skip
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"{name} must be a finite number > 0, got {value!r}")


class RouteTracker:
    """Progress along ``route``; :meth:`update` with each robot pose."""

    def __init__(self, route: Route, params: TrackerParams, rerouting: ReroutingState) -> None:
        self.route = route
        self.params = params
        self.next_node: GraphNode | None = route.start_node
        self.last_node: GraphNode | None = None
        self.current_edge: GraphEdge | None = None
        self.edge_index = -1  # index in route.edges of current_edge
        self.within_radius = False
        self.continued_edge = rerouting.curr_edge  # the edge a reroute continues, if any
        if rerouting.curr_edge is not None:
            self.current_edge = rerouting.curr_edge
            self.last_node = rerouting.curr_edge.start

    @property
    def edge_exited(self) -> GraphEdge | None:
        if self.edge_index > 0:
            return self.route.edges[self.edge_index - 1]
        return self.continued_edge if self.edge_index == 0 else None

    def update(self, pose: XY) -> tuple[bool, bool]:
        """Take the robot's position: (a node was achieved, the route is complete)."""
        if self.next_node is None or not self._achieved(pose, self.next_node):
            return False, False
        self.within_radius = False
        self.last_node = self.next_node
        self.edge_index += 1
        if self.edge_index < len(self.route.edges):
            self.current_edge = self.route.edges[self.edge_index]
            self.next_node = self.current_edge.end
            return True, False
        self.current_edge = None
        self.next_node = None
        return True, True

    def _boundary(self) -> bool:
        last_index = len(self.route.edges) - 1
        return self.edge_index == last_index or (
            self.edge_index == -1 and self.current_edge is None
        )

    def _achieved(self, pose: XY, node: GraphNode) -> bool:
        dx, dy = node.x - pose[0], node.y - pose[1]
        dist = math.hypot(dx, dy)
        boundary = self._boundary()
        radius = self.params.boundary_radius_to_achieve_node if boundary else (
            self.params.radius_to_achieve_node)  # fmt: skip
        in_radius = dist <= radius
        if dist < 1e-4 or (not in_radius and self.within_radius):
            return True
        self.within_radius = in_radius
        if boundary or not in_radius or self.current_edge is None:
            return in_radius and boundary
        last = self.current_edge.start
        nx, ny = node.x - last.x, node.y - last.y
        after = self.route.edges[self.edge_index + 1].end
        mx, my = after.x - node.x, after.y - node.y
        n_mag, m_mag = math.hypot(nx, ny), math.hypot(mx, my)
        if n_mag < 1e-6 or m_mag < 1e-6:
            return True
        bx, by = nx * m_mag + mx * n_mag, ny * m_mag + my * n_mag  # the unnormalised bisector
        return normalized_dot(bx, by, dx, dy) <= 0.0
