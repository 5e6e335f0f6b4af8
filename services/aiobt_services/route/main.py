"""``aiobt route``: Nav2's route server on Zenoh.

Loads a route graph (``--graph-filepath``, Nav2 GeoJSON; a shipped world's name
picks its graph); subscribes ``{ns}/map`` (latched), ``{ns}/pose`` and ``{ns}/scan``
for a global costmap (as the planner's) that the CostmapScorer and the
CollisionMonitor read; serves the actions ``compute_route`` and
``compute_and_track_route`` and the services ``srv/route_server/set_route_graph``,
``srv/route_server/ReroutingService/reroute`` and (with the DynamicEdgesScorer)
``srv/route_server/DynamicEdgesScorer/adjust_edges``; publishes ``{ns}/speed_limit``
(AdjustSpeedLimit) and ``{ns}/route_graph`` (latched); calls ``{ns}/srv/<service_name>``
(std_srvs/Trigger) where the graph asks for a TriggerEvent; holds ``{ns}/nodes/route``. A
graph that does not load is logged and every request fails NO_VALID_GRAPH with that
error. See docs/route.md.
"""

from __future__ import annotations

import argparse
import logging

from aiobt.costmap import InflationParams
from aiobt.costmap.world import FedCostmap, WorldOptions
from aiobt.system.service import (
    non_negative,
    open_bus_unless_stopped,
    open_clock,
    run_service,
    stop_on_signals,
)
from aiobt.transport import BusSettings, add_bus_arguments

from .actions import RouteActions
from .geojson import load_or_explain
from .operations import OperationsManager, ReroutingService
from .options import (
    add_route_arguments,
    args_problem,
    check_plugins,
    edge_scorer,
    operations,
    route_params,
    tracker_params,
)
from .planning import RoutePlanner
from .plugins import Wiring
from .scorers import DynamicEdgesScorer
from .service import RouteService

log = logging.getLogger("aiobt_services.route.main")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    parser.add_argument("--sim-time", action="store_true",
                        help="serve once the simulation's clock ({ns}/clock) runs")  # fmt: skip
    group = parser.add_argument_group("route server", description=__doc__.split("\n\n")[1])
    add_route_arguments(group)
    costmap = parser.add_argument_group("global costmap (as the planner's)")
    add = costmap.add_argument
    add("--robot-radius", type=non_negative, default=0.22, help="inscribed radius, m (%(default)s)")
    add("--inflation-radius", type=non_negative, default=0.55, help="m (default: %(default)s)")
    add("--cost-scaling-factor", type=non_negative, default=3.0, help="1/m (%(default)s)")


def build(args: argparse.Namespace, service: RouteService) -> RouteActions:
    check_plugins(args)
    world = service.world
    wiring = Wiring(world.snapshot, service.publish_speed_limit, service.call_service)
    graph, problem = load_or_explain(args.graph_filepath)
    scorer = edge_scorer(args, wiring)
    service.dynamic_edges = next(
        (s for s in scorer.scorers if isinstance(s, DynamicEdgesScorer)), None
    )
    planner = RoutePlanner(graph, scorer, route_params(args), world.snapshot, problem)
    made = operations(args, wiring)
    service.rerouting = next((op for op in made if isinstance(op, ReroutingService)), None)
    return RouteActions(planner, OperationsManager(made), tracker_params(args),
                        service.robot_pose, service.clock)  # fmt: skip


async def serve(args: argparse.Namespace) -> None:
    stop = stop_on_signals()
    inflation = InflationParams(args.robot_radius, args.inflation_radius, args.cost_scaling_factor)
    world = FedCostmap(WorldOptions(inflation=inflation))
    async with open_bus_unless_stopped(BusSettings.from_args(args), stop) as bus:
        if bus is None:
            return
        clock = await open_clock(bus, args.sim_time, stop)
        if clock is None:
            return
        service = RouteService(bus, world, clock, sim_time=args.sim_time)
        service.start(build(args, service))
        log.info("route server up on namespace '%s'", bus.namespace)
        await stop.wait()


def run(args: argparse.Namespace) -> int:
    """2 for a bad plugin or parameter (named in the log, before the bus is opened)."""
    problem = args_problem(args)
    if problem is not None:
        log.error("route: %s", problem)
        return 2
    return run_service(serve(args), log, "route")
