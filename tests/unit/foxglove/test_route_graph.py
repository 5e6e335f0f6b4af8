"""The route server's graph as a Foxglove scene: lanes as lines, nodes as dots, in map."""

from __future__ import annotations

from aiobt.foxglove import convert
from aiobt.msgs.geometry import Header, Point
from aiobt.msgs.route import RouteEdge, RouteNode
from aiobt.msgs.route_graph import RouteGraph

from .test_convert import decoded


def test_lanes_and_nodes_in_the_map_frame() -> None:
    a, b = Point(x=1.0, y=2.0), Point(x=4.0, y=2.0)
    graph = RouteGraph(
        header=Header(stamp=3.0, frame_id="map"),
        nodes=[RouteNode(nodeid=1, position=a), RouteNode(nodeid=2, position=b)],
        edges=[RouteEdge(edgeid=10, start=a, end=b), RouteEdge(edgeid=11, start=b, end=a)],
    )
    [entity] = decoded(convert.route_graph(graph)).entities
    assert entity.frame_id == "map"
    assert not entity.frame_locked
    lanes, dots = entity.lines
    assert [(p.x, p.y) for p in lanes.points] == [(1.0, 2.0), (4.0, 2.0), (4.0, 2.0), (1.0, 2.0)]
    assert {(p.x, p.y) for p in dots.points} == {(1.0, 2.0), (4.0, 2.0)}
    assert len(dots.points) == 4  # a zero-length line per node, drawn as a thick dot


def test_no_graph_is_an_empty_scene() -> None:
    [entity] = decoded(convert.route_graph(RouteGraph())).entities
    assert [len(line.points) for line in entity.lines] == [0, 0]
