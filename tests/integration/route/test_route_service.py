"""The route server process over a real router: routes on the office graph, Nav2's
error codes, a graph that does not load, and a tracked route with its speed limits and
a reroute asked for over the wire (a fake robot publishes the pose)."""

from __future__ import annotations

import asyncio
import json
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from aiobt.msgs import OccupancyGrid, PoseStamped
from aiobt.msgs.remote_actions import ComputeAndTrackRoute, ComputeRoute
from aiobt.msgs.route_graph import DynamicEdges, RouteGraph, SetRouteGraph
from aiobt.msgs.speed_limit import SpeedLimit
from aiobt.msgs.std import Trigger
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings
from aiobt_services.robot.convert import occupancy_grid
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.worlds import OFFICE

from ..services import common, up

pytestmark = pytest.mark.integration
Spawn = Callable[[Sequence[str]], ServiceProcess]
Codes = ComputeRoute.ErrorCode


async def route(bus: Bus, goal: ComputeRoute.Goal) -> Any:
    client = bus.action_client(ComputeRoute.name, ComputeRoute)
    handle = await client.send_goal(goal, server_timeout=10.0)
    return await handle.result(timeout=10.0)


async def set_graph(bus: Bus, path: str) -> Any:
    request = SetRouteGraph.Request(graph_filepath=path)
    return await bus.call(SetRouteGraph.service_name, request, SetRouteGraph.Response)


async def start(spawn: Spawn, bus: Bus, settings: BusSettings, *flags: str) -> ServiceProcess:
    proc = spawn(["-m", "aiobt_services.route", *flags, *common(settings)])
    await up(bus, "route", proc)
    return proc


async def test_routes_on_the_office_graph_and_error_codes(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    bus.latched_publisher("map", OccupancyGrid).put(occupancy_grid(load_map(OFFICE)))
    bus.publisher("pose", PoseStamped).put(PoseStamped.from_xy_yaw(2.0, 9.75, 0.0))
    scorers = "DistanceScorer,CostmapScorer,DynamicEdgesScorer"
    await start(spawn, bus, bus_settings, "--graph-filepath", "office",
                "--edge-cost-functions", scorers)  # fmt: skip

    by_ids = await route(bus, ComputeRoute.Goal(start_id=1, goal_id=22))
    assert by_ids.error_code == 0, by_ids.error_msg
    nodes = [n.nodeid for n in by_ids.route.nodes]
    assert nodes[0] == 1
    assert nodes[-1] == 22
    assert 7 in nodes  # along the corridor
    xy = by_ids.path.xy_array()
    assert np.hypot(*np.diff(xy, axis=0).T).max() <= 0.05 + 1e-6  # Nav2's path_density
    assert tuple(xy[-1]) == (16.5, 7.0)

    # a fleet manager closes the corridor east of node 5: the route goes by the middle room
    corridor = [e.edgeid for e in by_ids.route.edges if e.start.x == 10.0 and e.end.x == 14.0]
    assert corridor, [e.edgeid for e in by_ids.route.edges]
    closing = DynamicEdges.Request(closed_edges=corridor)
    assert (await bus.call(DynamicEdges.service_name, closing, DynamicEdges.Response)).success
    around = await route(bus, ComputeRoute.Goal(start_id=1, goal_id=22))
    assert around.error_code == 0, around.error_msg
    assert 17 in [n.nodeid for n in around.route.nodes]
    assert not set(corridor) & {e.edgeid for e in around.route.edges}

    goal = PoseStamped.from_xy_yaw(1.0, 18.3, 0.0)  # past node 29, in the open plan
    for _ in range(50):  # until the server has the pose
        by_pose = await route(bus, ComputeRoute.Goal(use_poses=True, goal=goal))
        if by_pose.error_code != Codes.TF_ERROR:
            break
        bus.publisher("pose", PoseStamped).put(PoseStamped.from_xy_yaw(2.0, 9.75, 0.0))
        await asyncio.sleep(0.1)
    assert by_pose.error_code == 0, by_pose.error_msg
    assert by_pose.route.nodes[-1].nodeid == 29

    unknown = await route(bus, ComputeRoute.Goal(start_id=1, goal_id=999))
    assert unknown.error_code == Codes.UNKNOWN
    assert "goal_id 999" in unknown.error_msg
    odom = PoseStamped.from_xy_yaw(5.0, 5.0, 0.0, frame_id="odom")
    wrong = await route(bus, ComputeRoute.Goal(use_poses=True, goal=odom))
    assert wrong.error_code == Codes.TF_ERROR


async def test_a_graph_that_does_not_load_fails_requests_and_the_server_runs(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings, tmp_path: Path
) -> None:
    bad = tmp_path / "bad.geojson"
    nodes = [{"type": "Feature", "properties": {"id": 1}, "geometry": {"type": "Point",
              "coordinates": [0, 0]}}]  # fmt: skip
    edge = {"type": "Feature", "properties": {"id": 2, "startid": 1, "endid": 7},
            "geometry": {"type": "LineString", "coordinates": [[0, 0], [1, 0]]}}  # fmt: skip
    bad.write_text(json.dumps({"type": "FeatureCollection", "features": [*nodes, edge]}))
    proc = await start(spawn, bus, bus_settings, "--graph-filepath", str(bad))
    for _ in range(2):
        result = await route(bus, ComputeRoute.Goal(start_id=1, goal_id=1))
        assert result.error_code == Codes.NO_VALID_GRAPH
        assert str(bad) in result.error_msg
        assert "feature 1 (edge id 2)" in result.error_msg
        assert "endid 7 is not a node" in result.error_msg
    assert proc.running
    # set_route_graph: the office graph, then the bad one again (as Nav2: no graph after)
    bus.latched_publisher("map", OccupancyGrid).put(occupancy_grid(load_map(OFFICE)))
    office_graph = asyncio.Event()
    graphs: list[RouteGraph] = []

    def on_graph(msg: RouteGraph) -> None:
        graphs.append(msg)
        if len(msg.nodes) == 36:
            office_graph.set()

    bus.subscribe("route_graph", RouteGraph, on_graph, latched=True)
    reply = await set_graph(bus, "office")
    assert reply.success, reply.message
    async with asyncio.timeout(5.0):
        await office_graph.wait()
    assert len(graphs[-1].edges) == 84
    assert graphs[-1].name == "office_graph"
    for _ in range(20):  # the map comes to the server's costmap (the CostmapScorer's)
        result = await route(bus, ComputeRoute.Goal(start_id=1, goal_id=8))
        if result.error_code != Codes.NO_VALID_ROUTE:
            break
        await asyncio.sleep(0.1)  # polled, bounded: 20 tries
    assert result.error_code == 0, result.error_msg
    reply = await set_graph(bus, str(bad))
    assert not reply.success
    assert "endid 7 is not a node" in reply.message
    again = await route(bus, ComputeRoute.Goal(start_id=1, goal_id=8))
    assert again.error_code == Codes.NO_VALID_GRAPH


def corridor_graph(path: Path, **edge_12: Any) -> Path:
    """1 (2, 9.75) -> 2 (6, 9.75) -> 3 (10, 9.75), edge 12 with a 50 % speed limit (and
    ``edge_12``'s properties)."""

    def point(i: int, x: float) -> dict[str, Any]:
        return {"type": "Feature", "properties": {"id": i},
                "geometry": {"type": "Point", "coordinates": [x, 9.75]}}  # fmt: skip

    def line(i: int, a: int, b: int, **props: Any) -> dict[str, Any]:
        return {"type": "Feature", "properties": {"id": i, "startid": a, "endid": b, **props},
                "geometry": {"type": "LineString", "coordinates": []}}  # fmt: skip

    features = [point(1, 2.0), point(2, 6.0), point(3, 10.0), line(11, 1, 2),
                line(12, 2, 3, metadata={"speed_limit": 50.0}, **edge_12)]  # fmt: skip
    path.write_text(json.dumps({"type": "FeatureCollection", "features": features}))
    return path


async def test_tracked_route_speed_limits_and_a_reroute_asked_for(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings, tmp_path: Path
) -> None:
    bus.latched_publisher("map", OccupancyGrid).put(occupancy_grid(load_map(OFFICE)))
    poses = bus.publisher("pose", PoseStamped)
    limits: list[float] = []
    bus.subscribe("speed_limit", SpeedLimit, lambda m: limits.append(m.speed_limit))
    graph = str(corridor_graph(tmp_path / "c.geojson"))
    await start(spawn, bus, bus_settings, "--graph-filepath", graph, "--edge-cost-functions",
                "DistanceScorer", "--operations", "AdjustSpeedLimit,ReroutingService")  # fmt: skip
    feedback: list[Any] = []
    client = bus.action_client(ComputeAndTrackRoute.name, ComputeAndTrackRoute)
    x = 2.0
    poses.put(PoseStamped.from_xy_yaw(x, 9.75, 0.0))
    handle = await client.send_goal(ComputeAndTrackRoute.Goal(start_id=1, goal_id=3),
                                    server_timeout=10.0, on_feedback=feedback.append)  # fmt: skip
    asked = False
    async with asyncio.timeout(30.0):
        while not handle.done:
            poses.put(PoseStamped.from_xy_yaw(x, 9.75, 0.0))
            await asyncio.sleep(0.02)
            if feedback:  # the robot sets off once the route is being tracked
                x = min(10.0, x + 0.04)  # 2 m/s
            if x > 7.0 and not asked:
                reply = await bus.call("route_server/ReroutingService/reroute",
                                       Trigger.Request(), Trigger.Response)  # fmt: skip
                assert reply.success
                asked = True
    result = await handle.result(timeout=5.0)
    assert result.error_code == 0, result.error_msg
    assert result.execution_duration > 1.0
    rerouted = [f for f in feedback if f.rerouted]
    assert len(rerouted) == 2  # the start, and the reroute asked for
    assert [n.nodeid for n in rerouted[1].route.nodes] == [3]  # from the edge being driven
    assert 6.5 < rerouted[1].path.poses[0].x < 8.5  # the path goes on from where it was
    assert limits[:2] == [100.0, 50.0]  # edge 11 has no limit, edge 12 is at 50 %
