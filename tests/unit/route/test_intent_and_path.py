"""Which nodes a request starts and ends at, pruning, and the dense path."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt.costmap import CostGrid, GridGeometry
from aiobt_services.route.dense import densify, interpolate
from aiobt_services.route.errors import RouteError
from aiobt_services.route.intent import IntentParams, ReroutingState, find_ends, prune
from aiobt_services.route.request import RouteRequest
from aiobt_services.route.scorers import DistanceScorer, EdgeScorer
from aiobt_services.route.search import Route, find_route

from .helpers import line, square

PARAMS = IntentParams()


def full_route(xs: tuple[float, ...]) -> Route:
    graph = line(*xs)
    first, last = graph.node(1), graph.node(len(xs))
    assert first is not None
    assert last is not None
    return find_route(graph, first, last, EdgeScorer([DistanceScorer()]))


def test_ends_by_id_and_by_nearest_pose() -> None:
    graph = square()
    start, goal = find_ends(graph, RouteRequest(False, start_id=2, goal_id=4), PARAMS, None)
    assert (start.nodeid, goal.nodeid) == (2, 4)
    start, goal = find_ends(graph, RouteRequest(True, start=(0.4, 0.3), goal=(3.0, 3.9)),
                            PARAMS, None)  # fmt: skip
    assert (start.nodeid, goal.nodeid) == (1, 3)
    with pytest.raises(RouteError, match="goal_id 99 is not a node of route graph 'square'"):
        find_ends(graph, RouteRequest(False, start_id=1, goal_id=99), PARAMS, None)


def test_a_wall_between_pose_and_nearest_node_picks_a_reachable_one() -> None:
    costs = np.zeros((60, 60), dtype=np.uint8)
    costs[:, 15:18] = 254  # a wall at x 1.5-1.8 m, all along
    grid = CostGrid(GridGeometry(60, 60, 0.1), costs)
    graph = square()  # node 1 (0, 0) is nearest (1.9, 0.5) but behind the wall; node 2 (4, 0)
    start, _ = find_ends(graph, RouteRequest(True, start=(1.9, 0.5), goal=(4, 4)), PARAMS, grid)
    assert start.nodeid == 2
    blind = IntentParams(enable_nn_search=False)
    start, _ = find_ends(graph, RouteRequest(True, start=(1.9, 0.5), goal=(4, 4)), blind, grid)
    assert start.nodeid == 1


def test_the_search_takes_the_node_reached_first_round_a_wall() -> None:
    costs = np.zeros((60, 60), dtype=np.uint8)
    costs[3:, 15:18] = 254  # a wall at x 1.5-1.8 m, open below y 0.3 m
    grid = CostGrid(GridGeometry(60, 60, 0.1), costs)
    graph = square()  # node 1 (0, 0): behind the wall, 19 cells round it; node 2 (4, 0): 21
    request = RouteRequest(True, start=(1.9, 0.5), goal=(4, 4))
    start, _ = find_ends(graph, request, PARAMS, grid)
    assert start.nodeid == 1
    costs[:3, 15:18] = 254  # the gap closed: node 1 cannot be reached
    start, _ = find_ends(graph, request, PARAMS, grid)
    assert start.nodeid == 2
    cut_short = IntentParams(max_nn_search_iterations=10)  # reaches none: the nearest
    start, _ = find_ends(graph, request, cut_short, grid)
    assert start.nodeid == 1


def test_start_and_goal_along_the_end_edges_are_pruned() -> None:
    route = full_route((0.0, 2.0, 4.0, 6.0))
    request = RouteRequest(True, start=(0.5, 0.2), goal=(5.0, -0.1))
    pruned = prune(route, request, PARAMS, ReroutingState())
    assert [e.edgeid for e in pruned.edges] == [102]
    assert pruned.start_node.nodeid == 2
    assert pruned.route_cost == pytest.approx(2.0)
    # on the start node, or behind it: nothing to prune at the start
    kept = prune(route, RouteRequest(True, start=(-0.5, 0.0), goal=(6.0, 0.0)), PARAMS,
                 ReroutingState())  # fmt: skip
    assert [e.edgeid for e in kept.edges] == [101, 102, 103]
    no_goal_pruning = IntentParams(prune_goal=False)
    assert len(prune(route, request, no_goal_pruning, ReroutingState()).edges) == 2


def test_requests_by_id_are_not_pruned_until_a_reroute() -> None:
    route = full_route((0.0, 2.0, 4.0))
    state = ReroutingState()
    by_id = RouteRequest(False, start=(1.0, 0.0), start_id=1, goal_id=3)
    assert len(prune(route, by_id, PARAMS, state).edges) == 2
    state.curr_edge = route.edges[0]  # rerouting while on edge 101
    rerouted = prune(route, by_id, PARAMS, state)
    assert [e.edgeid for e in rerouted.edges] == [102]
    assert state.curr_edge is route.edges[0]
    assert state.closest_pt_on_edge == (1.0, 0.0)


def test_dense_path_points_spacing_and_headings() -> None:
    graph = square()
    one, three = graph.node(1), graph.node(3)
    assert one is not None
    assert three is not None
    route = find_route(graph, one, three, EdgeScorer([DistanceScorer()]), blocked=[14])
    poses = densify(route, ReroutingState(), 0.3)
    steps = np.hypot(*np.diff(poses[:, :2], axis=0).T)
    assert steps.max() <= 0.3 + 1e-9
    assert steps.min() > 0.25
    assert tuple(poses[0, :2]) == (0.0, 0.0)
    assert tuple(poses[-1, :2]) == (4.0, 4.0)
    assert poses[0, 2] == pytest.approx(0.0)
    assert poses[-1, 2] == pytest.approx(math.pi / 2)
    assert len(interpolate((0, 0), (0, 0), 0.05)) == 0
    single = densify(Route(three), ReroutingState(), 0.05)
    assert single.tolist() == [[4.0, 4.0, 0.0]]


def test_a_reroute_along_the_same_edge_starts_the_path_on_it() -> None:
    route = full_route((0.0, 2.0, 4.0))
    state = ReroutingState(curr_edge=route.edges[0], closest_pt_on_edge=(1.2, 0.0))
    poses = densify(Route(route.edges[1].start, route.edges[1:]), state, 0.1)
    assert poses[0, 0] == pytest.approx(1.2)
    assert poses[-1, 0] == pytest.approx(4.0)
    assert np.all(np.diff(poses[:, 0]) > 0)
