"""``aiobt planner``: the planner service on Zenoh.

Subscribes ``{ns}/map`` (latched), ``{ns}/pose`` and ``{ns}/scan`` for the
global costmap; serves the actions ``compute_path_to_pose``,
``compute_path_through_poses``, ``smooth_path`` and ``compute_coverage_path``
(planner ids ``GridBased``, ``ThetaStar``), the services
``srv/global_costmap/clear_{entirely,except,around,around_pose}_global_costmap``
and ``srv/is_path_valid``; holds the liveliness token ``{ns}/nodes/planner``.
"""

from __future__ import annotations

import argparse
import logging

from aiobt.costmap import InflationParams, ObstacleParams
from aiobt.msgs import ComputeCoveragePath, ComputePathThroughPoses, ComputePathToPose, SmoothPath
from aiobt.system.catalog import realtime_priority
from aiobt.system.heap import settle
from aiobt.system.realtime import add_realtime_argument, realtime_if_asked
from aiobt.system.service import (
    non_negative,
    open_bus_unless_stopped,
    open_clock,
    positive,
    run_service,
    stop_on_signals,
)
from aiobt.transport import BusSettings, add_bus_arguments

from .actions import SMOOTHERS, ActionOptions, PlannerActions
from .coverage import CoverageParams
from .planning import DEFAULT_PLANNER, PLANNERS
from .service import PlannerService
from .state import CostmapOptions, GlobalCostmap
from .traversal import SearchParams

log = logging.getLogger("aiobt_services.planner.main")
ACTIONS = (ComputePathToPose, ComputePathThroughPoses, SmoothPath, ComputeCoveragePath)


def _factor(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be an integer >= 1, got {text}")
    return value


def describe() -> str:
    """What ``--help`` says the planner serves (from the tables the service uses)."""
    actions = ", ".join(a.name for a in ACTIONS)
    planners = ", ".join(f"{p} (default)" if p == DEFAULT_PLANNER else p for p in PLANNERS)
    smoothers = ", ".join(repr(s) for s in SMOOTHERS)
    return (
        f"Serves the actions {actions}; the service srv/is_path_valid; and "
        "srv/global_costmap/clear_X_global_costmap for X in entirely, except, around, "
        f"around_pose. Planner ids (goal.planner_id): {planners}. Smoother ids "
        f"(goal.smoother_id): {smoothers}, all the simple smoother. "
        "See services/aiobt_services/planner/README.md."
    )


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    parser.add_argument(
        "--sim-time",
        action="store_true",
        help="serve once the simulation's clock ({ns}/clock) runs; paths are stamped with the "
        "robot pose's time either way",
    )
    group = parser.add_argument_group("planner", description=describe())
    add = group.add_argument
    add("--robot-radius", type=non_negative, default=0.22, help="inscribed radius, m (%(default)s)")
    add("--inflation-radius", type=non_negative, default=0.55, help="m (default: %(default)s)")
    add("--cost-scaling-factor", type=non_negative, default=3.0, help="1/m (%(default)s)")
    add("--obstacle-range", type=positive, default=2.5, help="mark up to, m (%(default)s)")
    add("--raytrace-range", type=positive, default=3.0, help="clear up to, m (%(default)s)")
    add(
        "--cost-penalty",
        type=non_negative,
        default=2.0,
        help="cost weight in search (%(default)s)",
    )
    add("--downsample", type=_factor, default=2, help="search on NxN cell blocks (%(default)s)")
    add("--no-allow-unknown", action="store_true", help="never plan through unknown cells")
    add(
        "--use-astar",
        action="store_true",
        help="GridBased searches with the CPython A* instead of the compiled Dijkstra",
    )
    add("--max-planning-time", type=positive, default=2.0, help="s, then TIMEOUT (%(default)s)")
    add("--row-spacing", type=positive, default=0.5, help="coverage rows, m (%(default)s)")
    add("--headland-width", type=non_negative, default=0.5, help="coverage, m (%(default)s)")
    add_realtime_argument(group, realtime_priority("planner"))


def build(args: argparse.Namespace) -> tuple[GlobalCostmap, PlannerActions]:
    costmap_options = CostmapOptions(
        inflation=InflationParams(
            args.robot_radius, args.inflation_radius, args.cost_scaling_factor
        ),
        obstacles=ObstacleParams(
            obstacle_max_range=args.obstacle_range, raytrace_max_range=args.raytrace_range
        ),
        search=SearchParams(
            args.cost_penalty, not args.no_allow_unknown, args.downsample, args.use_astar
        ),
    )
    world = GlobalCostmap(costmap_options)
    actions = PlannerActions(
        world,
        ActionOptions(
            args.max_planning_time, CoverageParams(args.row_spacing, args.headland_width)
        ),
    )
    return world, actions


async def serve(args: argparse.Namespace) -> None:
    stop = stop_on_signals()
    world, actions = build(args)
    realtime = realtime_if_asked(args.realtime_priority)  # before the bus: its threads too
    async with open_bus_unless_stopped(BusSettings.from_args(args), stop) as bus:
        if bus is None:
            return
        clock = await open_clock(bus, args.sim_time, stop)
        if clock is None:
            return
        PlannerService(bus, world, actions, sim_time=args.sim_time, clock=clock).start()
        settle()  # start-up's objects out of the collector's full passes (a request's tail)
        log.info("planner up on namespace '%s'%s", bus.namespace, realtime)
        await stop.wait()


def run(args: argparse.Namespace) -> int:
    return run_service(serve(args), log, "planner")
