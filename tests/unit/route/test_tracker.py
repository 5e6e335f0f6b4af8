"""Tracking a route: node achievement (radius, bisector), edges entered, completion."""

from __future__ import annotations

from aiobt_services.route.geojson import parse_graph
from aiobt_services.route.intent import ReroutingState
from aiobt_services.route.scorers import DistanceScorer, EdgeScorer
from aiobt_services.route.search import Route, find_route
from aiobt_services.route.tracker import RouteTracker, TrackerParams

from .helpers import edge, node, text


def l_route() -> Route:
    """1 (0,0) -> 2 (6,0) -> 3 (6,6) -> 4 (12,6): edges 11, 12, 13."""
    graph = parse_graph(text(node(1, 0, 0), node(2, 6, 0), node(3, 6, 6), node(4, 12, 6),
                             edge(11, 1, 2), edge(12, 2, 3), edge(13, 3, 4)))  # fmt: skip
    first, last = graph.node(1), graph.node(4)
    assert first is not None
    assert last is not None
    return find_route(graph, first, last, EdgeScorer([DistanceScorer()]))


def drive(tracker: RouteTracker, points: list[tuple[float, float]]) -> list[tuple[int, int]]:
    """(index of the point, node achieved) for each achievement along ``points``."""
    achieved = []
    for i, point in enumerate(points):
        changed, _ = tracker.update(point)
        if changed:
            assert tracker.last_node is not None
            achieved.append((i, tracker.last_node.nodeid))
    return achieved


def test_nodes_are_achieved_in_order_and_the_route_completes() -> None:
    tracker = RouteTracker(l_route(), TrackerParams(), ReroutingState())
    path = [(x / 10, 0.0) for x in range(61)] + [(6.0, y / 10) for y in range(61)]
    path += [(6.0 + x / 10, 6.0) for x in range(61)]
    achieved = drive(tracker, path)
    assert [n for _, n in achieved] == [1, 2, 3, 4]
    index = {n: i for i, n in achieved}
    # the start within the boundary radius (1 m); the corner at the bisector, level with
    # the node (the robot passes it exactly); the goal within the boundary radius
    assert index[1] == 0
    assert 56 <= index[2] <= 61
    assert 118 <= index[3] <= 122
    assert path[index[4]][0] >= 11.0
    assert tracker.next_node is None
    assert tracker.current_edge is None


def test_a_corner_cut_wide_is_achieved_at_the_bisector() -> None:
    tracker = RouteTracker(l_route(), TrackerParams(), ReroutingState())
    tracker.update((0.0, 0.0))  # the start node
    assert tracker.current_edge is not None
    assert tracker.current_edge.edgeid == 11
    before = [(4.5, 0.4), (5.0, 0.6), (5.3, 0.6)]  # within 2 m of (6, 0), x + y < 6
    assert [tracker.update(p)[0] for p in before] == [False, False, False]
    changed, done = tracker.update((5.3, 0.8))  # past x + y = 6, the line through the node
    assert changed
    assert not done
    assert tracker.current_edge is not None
    assert tracker.current_edge.edgeid == 12
    assert tracker.edge_exited is not None
    assert tracker.edge_exited.edgeid == 11


def test_leaving_the_radius_achieves_the_node() -> None:
    tracker = RouteTracker(l_route(), TrackerParams(radius_to_achieve_node=0.5), ReroutingState())
    tracker.update((0.0, 0.0))
    assert tracker.update((5.9, -0.3)) == (False, False)  # within 0.5 m of node 2
    assert tracker.update((5.9, -0.9)) == (True, False)  # out again: passed it


def test_a_reroute_along_the_same_edge_keeps_tracking_it() -> None:
    route = l_route()
    state = ReroutingState(curr_edge=route.edges[0])
    rest = Route(route.edges[1].start, route.edges[1:])
    tracker = RouteTracker(rest, TrackerParams(), state)
    assert tracker.current_edge is route.edges[0]
    assert tracker.last_node is route.start_node
    assert tracker.update((3.0, 0.0)) == (
        False,
        False,
    )  # not the start radius rule: node 2 is ahead
    assert tracker.update((6.0, 1.1))[0]
    assert tracker.edge_exited is route.edges[0]
