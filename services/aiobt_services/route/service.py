"""Wires the route server onto the bus: map, pose and scans in (the planner's global
costmap and robot feed, reused), the two actions, the reroute service, the speed
limit and the graph out."""

from __future__ import annotations

import logging

from aiobt.core.clock import Clock
from aiobt.costmap.world import FedCostmap
from aiobt.msgs import OccupancyGrid
from aiobt.msgs.remote_actions import ComputeAndTrackRoute, ComputeRoute
from aiobt.msgs.speed_limit import SpeedLimit
from aiobt.msgs.std import Trigger
from aiobt.system.announce import announce
from aiobt.transport import Bus
from aiobt_services.planner.feed import RobotFeed

from .actions import RouteActions
from .operations import ReroutingService
from .vectors import XY

log = logging.getLogger("aiobt_services.route.service")
SERVER = "route_server"
REROUTE_SERVICE = f"{SERVER}/ReroutingService/reroute"
SPEED_LIMIT_TOPIC = "speed_limit"


class RouteService:
    """The route server on ``bus``; ``actions`` is built by :func:`main.build` on
    ``world`` (fed here) and on this service's :meth:`robot_position`."""

    def __init__(self, bus: Bus, world: FedCostmap, clock: Clock, *, sim_time: bool) -> None:
        self.bus = bus
        self.world = world
        self.clock = clock
        self.sim_time = sim_time
        self.feed = RobotFeed(bus, world, clock)
        self.speed_limits = bus.publisher(SPEED_LIMIT_TOPIC, SpeedLimit, reliable=True)
        self.rerouting: ReroutingService | None = None  # set by the operations built

    def robot_position(self) -> XY:
        """The newest robot pose in ``map`` (LookupError before one came)."""
        self.feed.read()
        x, y, _ = self.world.require_pose()
        return (x, y)

    def publish_speed_limit(self, percent: float) -> None:
        self.speed_limits.put(SpeedLimit(percentage=True, speed_limit=percent))

    def start(self, actions: RouteActions) -> None:
        bus, feed, rerouting = self.bus, self.feed, self.rerouting
        bus.subscribe("map", OccupancyGrid, self.world.on_map, latched=True)
        bus.action_server(ComputeRoute.name, ComputeRoute, feed.action(actions.compute_route))
        bus.action_server(ComputeAndTrackRoute.name, ComputeAndTrackRoute,
                          feed.action(actions.compute_and_track_route))  # fmt: skip
        if rerouting is not None:

            def reroute(_req: Trigger.Request) -> Trigger.Response:
                rerouting.requested = True
                return Trigger.Response(success=True, message="reroute requested")

            bus.serve(REROUTE_SERVICE, Trigger.Request, Trigger.Response, reroute)
        announce(bus, "route", sim_time=self.sim_time)
