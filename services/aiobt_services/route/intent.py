"""Nav2's ``GoalIntentExtractor``: which graph nodes a request starts and ends at, and
the pruning of a first or last edge the robot or goal is already along.

By ids (``use_poses`` false) the nodes are the request's. By poses, each end is
the nearest node; with ``enable_nn_search``, when the straight line to it is
blocked in the costmap, the first of the ``num_nearest_nodes`` nearest that a
breadth-first search over the free cells reaches (``max_nn_search_iterations``
cells at most; none reached: the nearest), as Nav2 does.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from aiobt.costmap import CostGrid

from .errors import RouteError
from .graph import Graph, GraphEdge, GraphNode
from .reach import reachable_first, sight_blocked
from .request import RouteRequest
from .search import Route
from .vectors import XY, closest_point, distance, normalized_dot

EPSILON = 1e-6


@dataclass(frozen=True, slots=True)
class IntentParams:
    prune_goal: bool = True
    max_prune_dist_from_edge: float = 8.0
    min_prune_dist_from_goal: float = 0.15
    min_prune_dist_from_start: float = 0.10
    enable_nn_search: bool = True
    num_nearest_nodes: int = 5
    max_nn_search_iterations: int = 10000


@dataclass(slots=True)
class ReroutingState:
    """What a reroute carries over (Nav2's ``ReroutingState``)."""

    blocked_ids: list[int] = field(default_factory=list)
    start_id: int | None = None  # the last node passed, to route from
    start_pose: XY | None = None
    start_yaw: float = 0.0  # the robot's heading at start_pose
    curr_edge: GraphEdge | None = None  # the edge the robot was on
    closest_pt_on_edge: XY = (0.0, 0.0)
    first_time: bool = True


def find_ends(
    graph: Graph, request: RouteRequest, params: IntentParams, costmap: CostGrid | None
) -> tuple[GraphNode, GraphNode]:
    """The start and goal nodes of ``request``."""
    if not request.use_poses:
        return _by_id(graph, request.start_id, "start_id"), _by_id(
            graph, request.goal_id, "goal_id"
        )
    return (
        _nearest(graph, request.start, params, costmap, "start"),
        _nearest(graph, request.goal, params, costmap, "goal"),
    )


def _by_id(graph: Graph, nodeid: int, what: str) -> GraphNode:
    node = graph.node(nodeid)
    if node is None:  # Nav2 fails the id look-up with UNKNOWN
        raise RouteError("UNKNOWN", f"{what} {nodeid} is not a node of route graph '{graph.name}'")
    return node


def _nearest(
    graph: Graph, xy: XY, params: IntentParams, costmap: CostGrid | None, what: str
) -> GraphNode:
    candidates = graph.nearest(
        *xy, count=params.num_nearest_nodes if params.enable_nn_search else 1
    )
    if not candidates:
        raise RouteError("INDETERMINANT_NODES_ON_GRAPH",
                         f"no graph node found near the {what} pose {xy}")  # fmt: skip
    nearest = candidates[0]
    if costmap is None or len(candidates) < 2 or not sight_blocked(costmap, xy, _xy(nearest)):
        return nearest
    points = [_xy(node) for node in candidates]
    found = reachable_first(costmap, xy, points, params.max_nn_search_iterations)
    return nearest if found is None else candidates[found]


def prune(
    route: Route, request: RouteRequest, params: IntentParams, state: ReroutingState
) -> Route:
    """Nav2's ``pruneStartandGoal``: drop the first edge when the start is already along
    it, the last when the goal is short of its end (poses only; by ids, only reroutes
    prune). Sets ``state.curr_edge`` when the pruned first edge is the one the robot was
    on before a reroute, so tracking goes on along it."""
    last_curr_edge, state.curr_edge = state.curr_edge, None
    first_time, state.first_time = state.first_time, False
    if not route.edges or (not request.use_poses and first_time):
        return route
    edges, costs, cost = list(route.edges), list(route.edge_costs), route.route_cost
    start_node, first = route.start_node, route.edges[0]
    start = request.start
    if _along(start, start_node, first.end, params.min_prune_dist_from_start, params):
        if last_curr_edge is not None and last_curr_edge.edgeid == first.edgeid:
            state.curr_edge = first
            state.closest_pt_on_edge = closest_point(start, _xy(start_node), _xy(first.end))
        start_node = first.end
        cost -= costs[0] if costs else 0.0
        edges, costs = edges[1:], costs[1:]
    if not params.prune_goal or not request.use_poses or not edges:
        return Route(start_node, edges, cost, costs)
    last = edges[-1]
    if _along(request.goal, last.end, last.start, params.min_prune_dist_from_goal, params):
        cost -= costs[-1] if costs else 0.0
        edges, costs = edges[:-1], costs[:-1]
    return Route(start_node, edges, cost, costs)


def _along(
    point: XY, node: GraphNode, other: GraphNode, min_dist: float, params: IntentParams
) -> bool:
    """Whether ``point`` lies past ``node`` towards ``other`` (a projection onto the edge),
    farther than ``min_dist`` from ``node`` and within ``max_prune_dist_from_edge``."""
    vx, vy = other.x - node.x, other.y - node.y
    px, py = point[0] - node.x, point[1] - node.y
    on_edge = closest_point(point, _xy(node), _xy(other))
    return (
        normalized_dot(vx, vy, px, py) > EPSILON
        and distance(point, _xy(node)) > min_dist
        and distance(on_edge, point) <= params.max_prune_dist_from_edge
    )


def _xy(node: GraphNode) -> XY:
    return (node.x, node.y)
