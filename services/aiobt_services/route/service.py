"""Wires the route server onto the bus: map, pose and scans in (a global costmap fed by
the planner's robot feed, reused), the two actions, the reroute and set-graph
services, the speed limit and the graph (latched, for viewers) out."""

from __future__ import annotations

import logging
from typing import TypeVar

from aiobt.core.clock import Clock
from aiobt.costmap.feed import RobotFeed
from aiobt.costmap.world import FedCostmap
from aiobt.geometry import XYYaw
from aiobt.msgs import Msg, OccupancyGrid
from aiobt.msgs.remote_actions import ComputeAndTrackRoute, ComputeRoute
from aiobt.msgs.route_graph import DynamicEdges, RouteGraph, SetRouteGraph
from aiobt.msgs.speed_limit import SpeedLimit
from aiobt.msgs.std import Trigger
from aiobt.transport import Bus
from aiobt.transport.announce import announce

from .actions import RouteActions
from .convert import graph_msg
from .geojson import load_or_explain
from .graphs import graph_path
from .operations import ReroutingService
from .planning import RoutePlanner
from .scorers import DynamicEdgesScorer

M = TypeVar("M", bound=Msg)
log = logging.getLogger("aiobt_services.route.service")
SERVER = "route_server"
REROUTE_SERVICE = f"{SERVER}/ReroutingService/reroute"
SPEED_LIMIT_TOPIC = "speed_limit"
GRAPH_TOPIC = "route_graph"


class RouteService:
    """The route server on ``bus``; ``actions`` is built by :func:`main.build` on
    ``world`` (fed here) and on this service's :meth:`robot_pose`."""

    def __init__(self, bus: Bus, world: FedCostmap, clock: Clock, *, sim_time: bool) -> None:
        self.bus = bus
        self.world = world
        self.clock = clock
        self.sim_time = sim_time
        self.feed = RobotFeed(bus, world, clock)
        self.speed_limits = bus.publisher(SPEED_LIMIT_TOPIC, SpeedLimit, reliable=True)
        self.rerouting: ReroutingService | None = None  # set by the operations built
        self.dynamic_edges: DynamicEdgesScorer | None = None  # set by the scorers built
        self.graphs = bus.latched_publisher(GRAPH_TOPIC, RouteGraph)
        self.planner: RoutePlanner | None = None  # the actions' (set by start)

    def robot_pose(self) -> XYYaw:
        """The newest robot pose in ``map`` (LookupError before one came)."""
        self.feed.read()
        return self.world.require_pose()

    async def call_service(self, service: str, request: Msg, reply: type[M],
                           timeout: float) -> M:  # noqa: ASYNC109  # fmt: skip
        """A RouteOperationClient's call (TriggerEvent's): ``{ns}/srv/<service>`` (a
        ROS-style leading or trailing '/' dropped), waiting ``timeout`` s at most."""
        return await self.bus.call(service.strip("/"), request, reply, timeout)

    def publish_speed_limit(self, percent: float) -> None:
        self.speed_limits.put(SpeedLimit(percentage=True, speed_limit=percent))

    def start(self, actions: RouteActions) -> None:
        bus, feed = self.bus, self.feed
        bus.subscribe("map", OccupancyGrid, self.world.on_map, latched=True)
        bus.action_server(ComputeRoute.name, ComputeRoute, feed.action(actions.compute_route))
        bus.action_server(ComputeAndTrackRoute.name, ComputeAndTrackRoute,
                          feed.action(actions.compute_and_track_route),
                          preemption="replace", clock=self.clock)  # fmt: skip
        if self.rerouting is not None:
            bus.serve(REROUTE_SERVICE, Trigger.Request, Trigger.Response, self.reroute)
        if self.dynamic_edges is not None:
            bus.serve(DynamicEdges.service_name, DynamicEdges.Request, DynamicEdges.Response,
                      self.adjust_edges)  # fmt: skip
        self.planner = actions.planner
        bus.serve(SetRouteGraph.service_name, SetRouteGraph.Request, SetRouteGraph.Response,
                  self.set_graph)  # fmt: skip
        self.graphs.put(graph_msg(self.planner.graph, self.clock.now()))
        announce(bus, "route", sim_time=self.sim_time)

    def reroute(self, _req: Trigger.Request) -> Trigger.Response:
        """``route_server/ReroutingService/reroute``: the tracked route is planned anew."""
        if self.rerouting is not None:
            self.rerouting.requested = True
        return Trigger.Response(success=True, message="reroute requested")

    def adjust_edges(self, req: DynamicEdges.Request) -> DynamicEdges.Response:
        """``route_server/DynamicEdgesScorer/adjust_edges``."""
        if self.dynamic_edges is None:
            return DynamicEdges.Response(success=False)
        costs = {edge.edgeid: edge.cost for edge in req.adjust_edges}
        self.dynamic_edges.adjust(req.closed_edges, req.opened_edges, costs)
        log.info("edges closed now: %s; costs set: %s", sorted(self.dynamic_edges.closed), costs)
        return DynamicEdges.Response(success=True)

    def set_graph(self, req: SetRouteGraph.Request) -> SetRouteGraph.Response:
        """``route_server/set_route_graph`` (a shipped world's name or a path)."""
        planner = self.planner
        if planner is None:
            return SetRouteGraph.Response(success=False, message="the server is not started")
        planner.graph, planner.no_graph = load_or_explain(graph_path(req.graph_filepath))
        self.graphs.put(graph_msg(planner.graph, self.clock.now()))
        return SetRouteGraph.Response(success=planner.graph is not None, message=planner.no_graph)
