"""TimeScorer and SemanticScorer: Nav2's cases (nav2_route/test/test_edge_scorers.cpp),
their parameters by Nav2's names, and the errors for bad ones."""

from __future__ import annotations

import pytest

from aiobt_services.route.geojson import parse_graph
from aiobt_services.route.graph import GraphEdge
from aiobt_services.route.metadata_scorers import SemanticScorer, TimeScorer
from aiobt_services.route.plugins import Wiring, make_plugin
from aiobt_services.route.request import BY_IDS
from aiobt_services.route.scorers import SCORERS, DistanceScorer, EdgeScorer
from aiobt_services.route.search import find_route

from .helpers import Triggers, edge, node, square, text

WIRING = Wiring(lambda: None, lambda _: None, Triggers())


def one_edge(**props: object) -> GraphEdge:
    """Edge 10 from node 1 (1, 0) to node 2 (0, 0): 1 m, as Nav2's test."""
    graph = parse_graph(text(node(1, 1.0, 0.0), node(2, 0.0, 0.0), edge(10, 1, 2, **props)))
    return graph.edges[10]


def score(scorer: object, edge_: GraphEdge) -> float | None:
    return EdgeScorer([scorer]).score(edge_, BY_IDS, "NONE")  # type: ignore[list-item]


def scorer(name: str, **params: str) -> object:
    return make_plugin(SCORERS, "edge_cost_functions", name, params, WIRING)


def test_time_scorer_as_nav2s_test() -> None:
    time = TimeScorer()
    assert score(time, one_edge(metadata={"abs_time_taken": 10.0})) == 10.0
    assert score(time, one_edge()) == 2.0  # 1 m at max_vel 0.5 m/s
    assert score(time, one_edge(metadata={"abs_speed_limit": 0.85})) == pytest.approx(1.1764, 1e-3)
    both = one_edge(metadata={"abs_speed_limit": 0.85, "abs_time_taken": 10.0})
    assert score(time, both) == 10.0  # a time taken comes first
    assert score(time, one_edge(metadata={"abs_time_taken": 0.0, "abs_speed_limit": 0.0})) == 2.0
    assert score(time, one_edge(metadata={"abs_time_taken": "slow"})) == 2.0  # not a number


def test_time_scorer_parameters() -> None:
    made = scorer("TimeScorer", weight="2.0", max_vel="0.25", time_tag="t", speed_tag="v")
    assert isinstance(made, TimeScorer)
    assert score(made, one_edge()) == 8.0  # 2 x 1 m / 0.25 m/s
    assert score(made, one_edge(metadata={"t": 3.0, "abs_time_taken": 9.0})) == 6.0
    assert score(made, one_edge(metadata={"v": 1.0})) == 2.0
    with pytest.raises(ValueError, match=r"TimeScorer.max_vel must be > 0 m/s, got 0.0"):
        scorer("TimeScorer", max_vel="0")
    with pytest.raises(ValueError, match=r"TimeScorer.max_vel: bad value 'fast'"):
        scorer("TimeScorer", max_vel="fast")


def semantic(**params: str) -> object:
    classes = {"Test": "0.0", "Test1": "1.0", "Test2": "2.0"}
    return scorer("SemanticScorer", semantic_classes="[Test, Test1, Test2]", **classes, **params)


def test_semantic_scorer_by_the_class_key_as_nav2s_test() -> None:
    made = semantic()
    assert isinstance(made, SemanticScorer)
    assert made.class_costs == {"Test": 0.0, "Test1": 1.0, "Test2": 2.0}
    assert score(made, one_edge()) == 0.0  # nothing set
    assert score(made, one_edge(metadata={"class": "Test1"})) == 1.0
    graph = parse_graph(text(node(1, 1.0, 0.0), node(2, 0.0, 0.0, metadata={"class": "Test2"}),
                             edge(10, 1, 2, metadata={"class": "Test2"})))  # fmt: skip
    assert score(made, graph.edges[10]) == 4.0  # the edge's class and its end node's
    assert score(made, one_edge(metadata={"class": "Test4"})) == 0.0  # not a class
    assert score(made, one_edge(metadata={"class": 7})) == 0.0  # not a name
    weighted = semantic(weight="3.0", semantic_key="zone")
    assert score(weighted, one_edge(metadata={"class": "Test2", "zone": "Test1"})) == 3.0


def test_semantic_scorer_by_key_names_when_the_key_is_empty() -> None:
    made = semantic(semantic_key="")
    assert score(made, one_edge(metadata={"class": "Test1"})) == 0.0  # a value, not a key
    graph = parse_graph(text(node(1, 1.0, 0.0), node(2, 0.0, 0.0, metadata={"Test2": "x"}),
                             edge(10, 1, 2, metadata={"Test2": "Test2", "Test1": 5})))  # fmt: skip
    assert score(made, graph.edges[10]) == 5.0  # Test2 twice, Test1 once
    assert score(made, one_edge(metadata={"Test4": "Test4"})) == 0.0


def test_semantic_scorer_parameter_errors_name_the_parameter() -> None:
    with pytest.raises(ValueError, match=r"SemanticScorer.Test2: no cost given for the semantic "
                       "class 'Test2'"):  # fmt: skip
        scorer("SemanticScorer", semantic_classes="Test,Test2", Test="1.0")
    with pytest.raises(ValueError, match=r"SemanticScorer.highway: no such parameter \(known: "
                       r"weight, semantic_key, semantic_classes, and one cost"):  # fmt: skip
        scorer("SemanticScorer", semantic_classes="Test", Test="1.0", highway="2.0")
    with pytest.raises(ValueError, match=r"SemanticScorer.Test: bad value 'high'"):
        scorer("SemanticScorer", semantic_classes="Test", Test="high")
    assert score(scorer("SemanticScorer"), one_edge(metadata={"class": "x"})) == 0.0  # no classes
    with pytest.raises(ValueError, match=r"^Rooms \(a SemanticScorer\): SemanticScorer.kitchen: "
                       "no cost given"):  # fmt: skip
        scorer("Rooms", plugin="nav2_route::SemanticScorer", semantic_classes="kitchen")
    rooms = scorer("Rooms", plugin="SemanticScorer", semantic_classes="kitchen", kitchen="2")
    assert score(rooms, one_edge(metadata={"class": "kitchen"})) == 2.0


def test_time_and_semantic_scorers_steer_the_search() -> None:
    graph = square()  # 1 -> 3 by 2 (edges 10, 12) or by 4 (edges 14, 16), 8 m each
    graph.edges[12].metadata["abs_time_taken"] = 30.0  # the robot was slow there last time
    timed = EdgeScorer([TimeScorer()])
    one, three = graph.node(1), graph.node(3)
    assert one is not None
    assert three is not None
    assert [e.edgeid for e in find_route(graph, one, three, timed).edges] == [14, 16]
    graph.node(4).metadata["class"] = "kitchen"  # type: ignore[union-attr]
    avoid = EdgeScorer([DistanceScorer(), scorer("SemanticScorer",  # type: ignore[list-item]
                        semantic_classes="kitchen", kitchen="50.0")])  # fmt: skip
    assert [e.edgeid for e in find_route(graph, one, three, avoid).edges] == [10, 12]
