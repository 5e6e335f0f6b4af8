"""``aiobt route``'s flags, by Nav2's ``route_server`` parameter names (dashes for
underscores), and the server's parts built from them."""

from __future__ import annotations

import argparse
from typing import Any

from aiobt.msgs import Msg
from aiobt.system.plugin_params import comma_list, dotted_param
from aiobt.system.service import non_negative, positive

from .dense import Smoothing
from .graphs import graph_path
from .intent import IntentParams
from .operations import DEFAULT_OPERATIONS, OPERATIONS, RouteOperation
from .planning import RouteParams
from .plugins import Wiring, make_plugin
from .scorers import DEFAULT_SCORERS, SCORERS, EdgeScorer
from .tracker import TrackerParams

COLLISION_MONITOR_DEFAULTS = {"max_collision_dist": "3.0"}  # nav2_params.yaml (code: 5.0)


def _flag(text: str) -> bool:
    if text.lower() not in ("true", "false"):
        raise argparse.ArgumentTypeError(f"must be true or false, got {text}")
    return text.lower() == "true"


def add_route_arguments(group: argparse._ArgumentGroup) -> None:
    add = group.add_argument
    add("--graph-filepath", type=graph_path, default=None, metavar="PATH_OR_WORLD",
        help="GeoJSON route graph: a path, or a shipped world's name (office, small)")  # fmt: skip
    add("--path-density", type=positive, default=0.05, help="m between path points (%(default)s)")
    add("--max-iterations", type=int, default=0, help="search expansions, 0 = no limit")
    add(
        "--smooth-corners",
        type=_flag,
        default=False,
        help="round corners: true/false (%(default)s)",
    )
    add("--smoothing-radius", type=positive, default=1.0, help="m (%(default)s)")
    add("--smoothing-angle-threshold", type=positive, default=2.9, help="rad (%(default)s)")
    add("--max-planning-time", type=positive, default=2.0, help="s, warned over (%(default)s)")
    add("--edge-cost-functions", type=comma_list, default=",".join(DEFAULT_SCORERS),
        help=f"comma-separated, of {', '.join(SCORERS)} (default: %(default)s)")  # fmt: skip
    add("--operations", type=comma_list, default=",".join(DEFAULT_OPERATIONS),
        help=f"comma-separated, of {', '.join(OPERATIONS)} (default: %(default)s)")  # fmt: skip
    add("--param", type=dotted_param, action="append", default=[], metavar="PLUGIN.NAME=VALUE",
        help="a scorer's or operation's parameter, e.g. CostmapScorer.weight=2.0")  # fmt: skip
    add("--radius-to-achieve-node", type=positive, default=2.0, help="m (%(default)s)")
    add("--boundary-radius-to-achieve-node", type=positive, default=1.0, help="m (%(default)s)")
    add("--tracker-update-rate", type=positive, default=50.0, help="Hz (%(default)s)")
    add("--aggregate-blocked-ids", type=_flag, default=False, help="true/false (%(default)s)")
    add("--prune-goal", type=_flag, default=True, help="true/false (%(default)s)")
    add("--max-prune-dist-from-edge", type=non_negative, default=8.0, help="m (%(default)s)")
    add("--min-prune-dist-from-goal", type=non_negative, default=0.15, help="m (%(default)s)")
    add("--min-prune-dist-from-start", type=non_negative, default=0.10, help="m (%(default)s)")
    add("--enable-nn-search", type=_flag, default=True, help="true/false (%(default)s)")
    add("--num-nearest-nodes", type=int, default=5, help="(%(default)s)")
    add("--max-nn-search-iterations", type=int, default=10000, help="cells (%(default)s)")


def plugin_params(args: argparse.Namespace, name: str) -> dict[str, str]:
    given = {key: value for plugin, key, value in args.param if plugin == name}
    return (COLLISION_MONITOR_DEFAULTS if name == "CollisionMonitor" else {}) | given


def check_plugins(args: argparse.Namespace) -> None:
    """ValueError naming a --param for a plugin not loaded."""
    loaded = {*args.edge_cost_functions, *args.operations}
    for plugin, key, _ in args.param:
        if plugin not in loaded:
            raise ValueError(f"--param {plugin}.{key}: '{plugin}' is not among the "
                             f"edge_cost_functions or operations loaded")  # fmt: skip


def route_params(args: argparse.Namespace) -> RouteParams:
    intent = IntentParams(args.prune_goal, args.max_prune_dist_from_edge,
                          args.min_prune_dist_from_goal, args.min_prune_dist_from_start,
                          args.enable_nn_search, args.num_nearest_nodes,
                          args.max_nn_search_iterations)  # fmt: skip
    smoothing = Smoothing(args.smooth_corners, args.smoothing_radius,
                          args.smoothing_angle_threshold)  # fmt: skip
    return RouteParams(args.path_density, args.max_iterations, args.max_planning_time, intent,
                       smoothing)  # fmt: skip


def tracker_params(args: argparse.Namespace) -> TrackerParams:
    return TrackerParams(args.radius_to_achieve_node, args.boundary_radius_to_achieve_node,
                         args.tracker_update_rate, args.aggregate_blocked_ids)  # fmt: skip


def edge_scorer(args: argparse.Namespace, wiring: Wiring) -> EdgeScorer:
    return EdgeScorer([
        make_plugin(SCORERS, "edge_cost_functions", name, plugin_params(args, name), wiring)
        for name in args.edge_cost_functions
    ])  # fmt: skip


def operations(args: argparse.Namespace, wiring: Wiring) -> list[RouteOperation]:
    return [
        make_plugin(OPERATIONS, "operations", name, plugin_params(args, name), wiring)
        for name in args.operations
    ]


async def _not_wired(service: str, _request: Msg, _reply: type[Any], _timeout: float) -> Any:
    raise RuntimeError(f"service {service}: not wired (the parameters are being checked)")


INERT = Wiring(lambda: None, lambda _percent: None, _not_wired)
"""A wiring that does nothing, for :func:`args_problem` to build the plugins with."""


def args_problem(args: argparse.Namespace) -> str | None:
    """The first bad plugin or parameter of ``args`` (each plugin built once, with
    :data:`INERT`, which has no effect), or None: checked before the server starts."""
    try:
        check_plugins(args)
        edge_scorer(args, INERT)
        operations(args, INERT)
        route_params(args)
        tracker_params(args)
    except ValueError as exc:
        return str(exc)
    return None
