"""Every shipped route graph lies along its world's free space: no edge passes within
``CLEARANCE`` of a wall or piece of furniture (the robot's radius plus a margin)."""

from __future__ import annotations

import pytest

from aiobt.costmap.collision import segment_points
from aiobt_services.robot.mapfile import OCCUPIED, load_map
from aiobt_services.robot.worlds import WORLDS_DIR
from aiobt_services.route.geojson import load_graph
from aiobt_services.route.graphs import GRAPHS_DIR, graph_path
from aiobt_services.route.graphs.generate import GRAPHS, geojson

CLEARANCE = 0.4  # m: robot radius 0.22, plus room for the controller's tracking error
WORLDS = sorted(path.stem for path in WORLDS_DIR.glob("*.yaml"))


def test_every_world_has_a_graph() -> None:
    assert WORLDS, "no shipped worlds found"
    assert sorted(GRAPHS) == WORLDS
    for world in WORLDS:
        assert graph_path(world) == GRAPHS_DIR / f"{world}.geojson"


@pytest.mark.parametrize("world", WORLDS)
def test_graph_file_is_what_the_generator_writes(world: str) -> None:
    graph = load_graph(graph_path(world))
    nodes, lanes = GRAPHS[world]
    assert {n.nodeid for n in graph} == set(nodes)
    assert (
        len(graph.edges)
        == 2 * len(lanes)
        == len(geojson(world, nodes, lanes)["features"]) - len(nodes)
    )


@pytest.mark.parametrize("world", WORLDS)
def test_no_edge_passes_near_an_obstacle(world: str) -> None:
    info = load_map(WORLDS_DIR / f"{world}.yaml")
    graph = load_graph(graph_path(world))
    too_close = []
    for edge in graph.edges.values():
        points = segment_points(edge.start.x, edge.start.y, edge.end.x, edge.end.y, 0.025)
        if any(info.disc_blocked(x, y, CLEARANCE) or not info.contains(x, y) for x, y in points):
            too_close.append(edge.edgeid)
    assert too_close == []


def test_the_check_finds_an_edge_through_a_wall() -> None:
    """The check above can fail: a segment across the office's corridor wall is caught."""
    info = load_map(WORLDS_DIR / "office.yaml")
    points = segment_points(5.5, 9.75, 5.5, 7.0, 0.025)  # through the wall at y 8.5, no door
    assert any(info.disc_blocked(x, y, CLEARANCE) for x, y in points)
    assert info.occupancy_at(5.5, 8.5) == OCCUPIED
