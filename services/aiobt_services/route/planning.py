"""One route request end to end, without I/O: ends, search, pruning, dense path.

Nav2's ``RouteServer::findRoute``: the request's start and goal nodes (a reroute
starts from the last node passed, at the robot's pose), one node when they are
the same, else the search; then the pruning of the ends and the dense path.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace

from aiobt.costmap import CostGrid

from .dense import Poses, Smoothing, densify
from .errors import RouteError
from .graph import Graph
from .intent import IntentParams, ReroutingState, find_ends, prune
from .request import RouteRequest
from .scorers import EdgeScorer
from .search import Route, find_route


@dataclass(frozen=True, slots=True)
class RouteParams:
    path_density: float = 0.05
    max_iterations: int = 0
    max_planning_time: float = 2.0
    intent: IntentParams = field(default_factory=IntentParams)
    smoothing: Smoothing = field(default_factory=Smoothing)

    def __post_init__(self) -> None:
        if not self.path_density > 0.0:
            raise ValueError(f"path_density must be > 0 m, got {self.path_density!r}")
        if not self.smoothing.smoothing_radius > 0.0:
            raise ValueError(f"smoothing_radius must be > 0 m, got "
                             f"{self.smoothing.smoothing_radius!r}")  # fmt: skip


class RoutePlanner:
    """The graph (None until one is set), the scorers and the parameters."""

    def __init__(
        self,
        graph: Graph | None,
        scorer: EdgeScorer,
        params: RouteParams,
        costmap: Callable[[], CostGrid | None],
        no_graph: str = "no route graph set (graph_filepath is empty)",
    ) -> None:
        self.no_graph = no_graph  # why there is no graph
        self.graph = graph
        self.scorer = scorer
        self.params = params
        self.costmap = costmap

    def plan(self, request: RouteRequest, rerouting: ReroutingState) -> tuple[Route, Poses]:
        """The (pruned) route for ``request`` and its dense path (x, y, yaw rows)."""
        graph = self.graph
        if graph is None:
            raise RouteError("NO_VALID_GRAPH", self.no_graph)
        start, goal = find_ends(graph, request, self.params.intent, self.costmap())
        if rerouting.start_id is not None:
            rerouted = graph.node(rerouting.start_id)
            if rerouted is None:
                raise RouteError("UNKNOWN", f"reroute start node {rerouting.start_id} is gone")
            start = rerouted
            if rerouting.start_pose is not None:  # Nav2's overrideStart: the robot's pose
                request = replace(request, start=rerouting.start_pose,
                                  start_yaw=rerouting.start_yaw)  # fmt: skip
        route = find_route(graph, start, goal, self.scorer, rerouting.blocked_ids,
                           self.params.max_iterations, request)  # fmt: skip
        route = prune(route, request, self.params.intent, rerouting)
        poses = densify(route, rerouting, self.params.path_density, self.params.smoothing)
        return route, poses
