"""Nav2's route search (``RoutePlanner``): Dijkstra over the graph's directed edges.

An edge is skipped when its id or its end node's id is blocked, or when the
scorers close it. The scorers see the request and the edge's type: START for an
edge leaving the start node, else END for one reaching the goal node, else NONE.
An edge the scorers may not score (``overridable`` false) or any edge when no
scorer is set costs its file ``cost``, which must be > 0 (NO_VALID_GRAPH
otherwise, as Nav2). No route: NO_VALID_ROUTE; more than
``max_iterations`` expansions: TIMEOUT.
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Collection
from dataclasses import dataclass, field

from .errors import RouteError
from .graph import Graph, GraphEdge, GraphNode
from .request import BY_IDS, EdgeType, RouteRequest
from .scorers import EdgeScorer


@dataclass(slots=True)
class Route:
    """A start node, the edges from it in order, their summed cost, and each edge's own
    (``edge_costs``, in step with ``edges``; used when the route is pruned)."""

    start_node: GraphNode
    edges: list[GraphEdge] = field(default_factory=list)
    route_cost: float = 0.0
    edge_costs: list[float] = field(default_factory=list)

    @property
    def nodes(self) -> list[GraphNode]:
        return [self.start_node, *(edge.end for edge in self.edges)]


def edge_cost(
    edge: GraphEdge, scorer: EdgeScorer, request: RouteRequest, edge_type: EdgeType
) -> float | None:
    if not edge.overridable or len(scorer) == 0:
        if edge.cost <= 0.0:
            raise RouteError("NO_VALID_GRAPH", f"edge {edge.edgeid} has no cost of its own "
                             "(cost > 0) and no scorer may score it")  # fmt: skip
        return edge.cost
    return scorer.score(edge, request, edge_type)


def edge_type(edge: GraphEdge, start: GraphNode, goal: GraphNode) -> EdgeType:
    """Nav2's ``classifyEdge``: START before END, so a start-to-goal edge is START."""
    if edge.start is start:
        return "START"
    return "END" if edge.end is goal else "NONE"


def find_route(
    graph: Graph,
    start: GraphNode,
    goal: GraphNode,
    scorer: EdgeScorer,
    blocked: Collection[int] = (),
    max_iterations: int = 0,
    request: RouteRequest = BY_IDS,
) -> Route:
    """The cheapest route from ``start`` to ``goal`` (a single-node route when they are
    the same node) for ``request``. ``max_iterations`` <= 0 means no limit, as in Nav2."""
    if len(graph) == 0:
        raise RouteError("NO_VALID_GRAPH", "the route graph is empty")
    if start is goal:
        return Route(start)
    limit = max_iterations if max_iterations > 0 else math.inf
    scorer.prepare()
    best: dict[int, float] = {start.nodeid: 0.0}
    parent: dict[int, tuple[GraphEdge, float]] = {}
    order = itertools.count()  # ties leave the queue in insertion order
    queue: list[tuple[float, int, GraphNode]] = [(0.0, next(order), start)]
    iterations = 0
    while queue and iterations < limit:
        iterations += 1
        cost, _, node = heapq.heappop(queue)
        if cost != best.get(node.nodeid):
            continue  # a stale entry: the node was reached cheaper since
        if node is goal:
            return _unwind(start, goal, parent, cost)
        for edge in node.edges:
            if edge.edgeid in blocked or edge.end.nodeid in blocked:
                continue
            step = edge_cost(edge, scorer, request, edge_type(edge, start, goal))
            if step is None:
                continue
            total = cost + step
            if total < best.get(edge.end.nodeid, math.inf):
                best[edge.end.nodeid] = total
                parent[edge.end.nodeid] = (edge, step)
                heapq.heappush(queue, (total, next(order), edge.end))
    if queue:
        raise RouteError("TIMEOUT", f"max_iterations ({max_iterations}) exceeded searching "
                         f"from node {start.nodeid} to node {goal.nodeid}")  # fmt: skip
    raise RouteError("NO_VALID_ROUTE", f"no route from node {start.nodeid} to node "
                     f"{goal.nodeid} on open edges" + (f" (blocked: {sorted(blocked)})"
                                                      if blocked else ""))  # fmt: skip


def _unwind(
    start: GraphNode, goal: GraphNode, parent: dict[int, tuple[GraphEdge, float]], cost: float
) -> Route:
    edges: list[GraphEdge] = []
    costs: list[float] = []
    node = goal
    while node is not start:
        edge, step = parent[node.nodeid]
        edges.append(edge)
        costs.append(step)
        node = edge.start
    edges.reverse()
    costs.reverse()
    return Route(start, edges, cost, costs)
