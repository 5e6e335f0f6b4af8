"""Nav2 GeoJSON graphs parse, and every bad file is an error naming the file and feature."""

from __future__ import annotations

import pytest

from aiobt_services.route.errors import GraphError
from aiobt_services.route.geojson import load_graph, parse_graph
from aiobt_services.route.graphs import OFFICE

from .helpers import edge, node, text, two_way


def test_nodes_edges_metadata_and_operations() -> None:
    graph = parse_graph(text(
        node(1, 0.5, 1.0, metadata={"class": "hall"},
             operations={"pause": {"type": "stop", "trigger": "NODE", "metadata": {"wait": 5}}}),
        node(2, 3.5, 5.0),
        edge(3, 1, 2, cost=6.0, overridable=False, metadata={"speed_limit": 85}),
    ), "g.geojson")  # fmt: skip
    first, second = graph.node(1), graph.node(2)
    assert first is not None
    assert second is not None
    assert (first.x, first.y, first.metadata) == (0.5, 1.0, {"class": "hall"})
    assert first.operations[0].type == "stop"
    assert first.operations[0].metadata == {"wait": 5}
    (out,) = first.edges
    assert (out.edgeid, out.end, out.cost, out.overridable) == (3, second, 6.0, False)
    assert out.metadata == {"speed_limit": 85}
    assert out.length == pytest.approx(5.0)
    assert second.edges == []


def test_nav2s_own_sample_format_loads_the_shipped_office_graph() -> None:
    graph = load_graph(OFFICE)
    assert len(graph) == 36
    assert len(graph.edges) == 84
    assert [n.nodeid for n in graph.nearest(9.9, 9.7, count=2)] == [5, 4]


@pytest.mark.parametrize(
    ("content", "where", "problem"),
    [
        ("{not json", "line 1 column 2", "not JSON"),
        ('{"type": "Feature"}', "top level", "no 'features' list"),
        (
            text(node(1, 0, 0), node(2, 1, 0), edge(3, 1, 9)),
            "feature 2 (edge id 3)",
            "endid 9 is not a node",
        ),
        (
            text(node(1, 0, 0), node(1, 1, 0), edge(3, 1, 1)),
            "feature 1 (node id 1)",
            "duplicate id: feature 0 (node id 1)",
        ),
        (
            text(node(1, 0, 0), node(2, 1, 0), edge(2, 1, 2)),
            "feature 2 (edge id 2)",
            "duplicate id: feature 1 (node id 2)",
        ),
        (text(node(1, 0, 0), node(2, 1, 0)), "features", "0 edges"),
        (text(node(-1, 0, 0)), "feature 0 (node)", "'id' must be an integer"),
        (
            text(node(1, 0, 0, frame="odom"), node(2, 1, 0), edge(3, 1, 2)),
            "feature 0 (node id 1)",
            "frame 'odom'",
        ),
        (
            text(node(1, 0, 0), node(2, 1, 0), edge(3, 1, 2, cost="high")),
            "feature 2 (edge id 3)",
            "cost must be a number",
        ),
        (
            text(
                node(1, 0, 0, operations=[{"type": "x", "trigger": "LATER"}]),
                node(2, 1, 0),
                edge(3, 1, 2),
            ),
            "feature 0 (node id 1) operation 0",
            "needs a 'type' and a 'trigger'",
        ),
    ],
)
def test_bad_graphs_name_the_file_and_the_feature(content: str, where: str, problem: str) -> None:
    with pytest.raises(GraphError) as caught:
        parse_graph(content, "/maps/bad.geojson")
    assert caught.value.reason == "NO_VALID_GRAPH"
    assert caught.value.code == 402
    assert caught.value.where == where
    assert str(caught.value).startswith(f"route graph /maps/bad.geojson: {where}: ")
    assert problem in str(caught.value)


def test_a_missing_file_is_named(tmp_path: object) -> None:
    with pytest.raises(GraphError, match=r"route graph /nowhere/g.geojson: file: cannot be read"):
        load_graph("/nowhere/g.geojson")


def test_two_way_lanes_are_two_edges() -> None:
    graph = parse_graph(text(node(1, 0, 0), node(2, 2, 0), *two_way(5, 1, 2)))
    assert sorted(graph.edges) == [5, 6]
    assert graph.edges[6].start.nodeid == 2
    assert graph.edges[6].end.nodeid == 1
