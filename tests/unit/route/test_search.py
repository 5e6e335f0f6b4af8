"""The route search: cheapest by the scorers, blocked ids, fixed costs, Nav2's errors."""

from __future__ import annotations

import numpy as np
import pytest

from aiobt.costmap import CostGrid, GridGeometry
from aiobt_services.route.errors import RouteError
from aiobt_services.route.geojson import parse_graph
from aiobt_services.route.graph import Graph, GraphNode
from aiobt_services.route.operations import OPERATIONS, AdjustSpeedLimit, CollisionMonitor
from aiobt_services.route.plugins import Wiring, make_plugin
from aiobt_services.route.request import BY_IDS
from aiobt_services.route.scorers import (
    SCORERS,
    CostmapScorer,
    DistanceScorer,
    DynamicEdgesScorer,
    EdgeScorer,
    PenaltyScorer,
)
from aiobt_services.route.search import find_route

from .helpers import Triggers, edge, node, square, text, two_way

DISTANCE = EdgeScorer([DistanceScorer()])


def ids(graph: Graph, a: int, b: int, scorer: EdgeScorer = DISTANCE, **kw: object) -> list[int]:
    route = find_route(graph, _n(graph, a), _n(graph, b), scorer, **kw)  # type: ignore[arg-type]
    return [e.edgeid for e in route.edges]


def _n(graph: Graph, nodeid: int) -> GraphNode:
    found = graph.node(nodeid)
    assert found is not None
    return found


def test_the_shorter_way_is_taken_and_its_cost_summed() -> None:
    graph = parse_graph(text(node(1, 0, 0), node(2, 4, 0), node(3, 2, 3),
                             edge(10, 1, 2), edge(11, 1, 3), edge(12, 3, 2)))  # fmt: skip
    route = find_route(graph, _n(graph, 1), _n(graph, 2), DISTANCE)
    assert [e.edgeid for e in route.edges] == [10]
    assert route.route_cost == pytest.approx(4.0)
    assert route.edge_costs == [pytest.approx(4.0)]
    assert [n.nodeid for n in route.nodes] == [1, 2]


def test_edges_are_one_way() -> None:
    graph = parse_graph(text(node(1, 0, 0), node(2, 1, 0), edge(10, 1, 2)))
    assert ids(graph, 1, 2) == [10]
    with pytest.raises(RouteError) as caught:
        ids(graph, 2, 1)
    assert (caught.value.reason, caught.value.code) == ("NO_VALID_ROUTE", 405)


def test_a_blocked_edge_or_node_is_routed_around() -> None:
    graph = square()
    assert ids(graph, 1, 3) in ([10, 12], [14, 16])
    assert ids(graph, 1, 3, blocked=[10]) == [14, 16]
    assert ids(graph, 1, 3, blocked=[4]) == [10, 12]  # a node id blocks the edges into it
    with pytest.raises(RouteError, match=r"blocked: \[10, 14\]"):
        ids(graph, 1, 3, blocked=[10, 14])


def test_penalty_and_speed_limit_metadata_steer_the_route() -> None:
    graph = parse_graph(text(
        node(1, 0, 0), node(2, 4, 0), node(3, 4, 4), node(4, 0, 4),
        edge(10, 1, 2, metadata={"penalty": 5.0}), edge(12, 2, 3), edge(14, 1, 4), edge(16, 4, 3),
    ))  # fmt: skip
    both = EdgeScorer([DistanceScorer(), PenaltyScorer()])
    assert ids(graph, 1, 3, both) == [14, 16]
    # Nav2's DistanceScorer divides the length by the edge's speed_limit value
    fast = parse_graph(text(node(1, 0, 0), node(2, 4, 0), node(3, 4, 4), node(4, 0, 4),
                            edge(10, 1, 2, metadata={"speed_limit": 2.0}), edge(12, 2, 3),
                            edge(14, 1, 4), edge(16, 4, 3)))  # fmt: skip
    route = find_route(fast, _n(fast, 1), _n(fast, 3), DISTANCE)
    assert [e.edgeid for e in route.edges] == [10, 12]
    assert route.route_cost == pytest.approx(6.0)


def test_fixed_costs_when_not_overridable_or_no_scorer() -> None:
    graph = parse_graph(text(node(1, 0, 0), node(2, 4, 0), node(3, 2, 1),
                             edge(10, 1, 2, cost=1.0, overridable=False),
                             edge(11, 1, 3), edge(12, 3, 2)))  # fmt: skip
    assert ids(graph, 1, 2) == [10]
    with pytest.raises(RouteError) as caught:
        ids(graph, 1, 2, EdgeScorer([]))  # edge 11 has no cost of its own
    assert caught.value.reason == "NO_VALID_GRAPH"
    assert "edge 11" in caught.value.message


def test_max_iterations_is_a_timeout() -> None:
    graph = square()
    with pytest.raises(RouteError) as caught:
        ids(graph, 1, 3, max_iterations=1)
    assert caught.value.reason == "TIMEOUT"
    assert caught.value.code == 404
    assert ids(graph, 1, 1) == []  # start is goal: a one-node route, no search


def grid_with_wall() -> CostGrid:
    """10 x 10 m at 0.1 m; a lethal wall 0.2 m thick at x = 2 for y in 0..3, cost 100 at x = 8."""
    costs = np.zeros((100, 100), dtype=np.uint8)
    costs[0:30, 20:22] = 254  # two cells: check_resolution 2 looks at every other one
    costs[:, 80:82] = 100
    return CostGrid(GridGeometry(100, 100, 0.1), costs)


def test_costmap_scorer_closes_blocked_edges_and_scores_cost() -> None:
    grid = grid_with_wall()
    graph = parse_graph(text(node(1, 0.5, 1.0), node(2, 3.5, 1.0), node(3, 0.5, 5.0),
                             node(4, 9.5, 5.0), node(5, 20.0, 5.0), *two_way(10, 1, 2),
                             *two_way(12, 3, 4), *two_way(14, 4, 5)))  # fmt: skip
    scorer = CostmapScorer(lambda: grid)
    scorer.prepare()
    assert scorer.score(graph.edges[10], BY_IDS, "NONE") is None  # through the wall
    assert scorer.score(graph.edges[12], BY_IDS, "NONE") == pytest.approx(
        100 / 253
    )  # the worst cell
    assert scorer.score(graph.edges[14], BY_IDS, "NONE") is None  # off the map
    mean = CostmapScorer(lambda: grid, use_maximum=False, check_resolution=1)
    mean.prepare()
    assert 0.0 < (mean.score(graph.edges[12], BY_IDS, "NONE") or 0.0) < 100 / 253 / 10
    blind = CostmapScorer(lambda: None)
    blind.prepare()
    assert blind.score(graph.edges[12], BY_IDS, "NONE") is None  # no costmap: no edge, as Nav2


def test_dynamic_edges_close_reopen_and_cost() -> None:
    graph = square()
    dynamic = DynamicEdgesScorer()
    scorer = EdgeScorer([DistanceScorer(), dynamic])
    dynamic.adjust(closed=[10, 14], opened=[], costs={})
    with pytest.raises(RouteError, match="no route from node 1 to node 3"):
        ids(graph, 1, 3, scorer)
    dynamic.adjust(closed=[], opened=[14], costs={12: 100.0})
    assert ids(graph, 1, 3, scorer) == [14, 16]
    dynamic.adjust(closed=[], opened=[10], costs={16: 200.0})
    assert ids(graph, 1, 3, scorer) == [10, 12]  # 8 + 100 against 8 + 200


def test_plugins_by_name_with_nav2_parameters_and_the_server_wired_in() -> None:
    speed_limits: list[float] = []
    grid = grid_with_wall()
    wiring = Wiring(lambda: grid, speed_limits.append, Triggers())

    def scorer(name: str, **params: str) -> object:
        return make_plugin(SCORERS, "edge_cost_functions", name, params, wiring)

    costmap = scorer("CostmapScorer", weight="2.5", use_maximum="false")
    assert isinstance(costmap, CostmapScorer)
    assert (costmap.weight, costmap.use_maximum, costmap.check_resolution) == (2.5, False, 2)
    costmap.prepare()
    assert costmap._grid is grid  # the server's costmap, not a parameter
    with pytest.raises(ValueError, match="edge_cost_functions: unknown plugin 'LaneScorer'"):
        scorer("LaneScorer")
    with pytest.raises(ValueError, match=r"DistanceScorer.speed: no such parameter"):
        scorer("DistanceScorer", speed="1")
    with pytest.raises(ValueError, match=r"PenaltyScorer.weight: bad value 'x'"):
        scorer("PenaltyScorer", weight="x")
    with pytest.raises(ValueError, match=r"CostmapScorer.costmap: no such parameter"):
        scorer("CostmapScorer", costmap="x")
    params = {"max_collision_dist": "3.0", "reroute_on_collision": "false"}
    monitor = make_plugin(OPERATIONS, "operations", "CollisionMonitor", params, wiring)
    assert isinstance(monitor, CollisionMonitor)
    assert (monitor.max_collision_dist, monitor.reroute_on_collision) == (3.0, False)
    adjust = make_plugin(OPERATIONS, "operations", "AdjustSpeedLimit", {}, wiring)
    assert isinstance(adjust, AdjustSpeedLimit)
    adjust.publish(40.0)
    assert speed_limits == [40.0]
    with pytest.raises(ValueError, match=r"ReroutingService.requested: no such parameter"):
        make_plugin(OPERATIONS, "operations", "ReroutingService", {"requested": "true"}, wiring)
