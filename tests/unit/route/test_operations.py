"""Route operations: speed limits from edge metadata, collision ahead -> reroute, graph
operations, the rerouting service."""

from __future__ import annotations

import numpy as np
import pytest

from aiobt.costmap import CostGrid, GridGeometry
from aiobt_services.route.errors import RouteError
from aiobt_services.route.geojson import parse_graph
from aiobt_services.route.intent import ReroutingState
from aiobt_services.route.operation_event import OperationResult, ProcessType
from aiobt_services.route.operations import (
    AdjustSpeedLimit,
    CollisionMonitor,
    OperationsManager,
    ReroutingService,
)
from aiobt_services.route.scorers import DistanceScorer, EdgeScorer
from aiobt_services.route.search import Route, find_route
from aiobt_services.route.tracker import RouteTracker, TrackerParams

from .helpers import edge, node, text


def route_of(*features: dict[str, object]) -> Route:
    graph = parse_graph(text(*features))
    first, last = graph.nodes[0], graph.nodes[-1]
    return find_route(graph, first, last, EdgeScorer([DistanceScorer()]))


def straight(**edge_props: object) -> Route:
    """1 (0,0) -> 2 (4,0) -> 3 (8,0), edges 11 and 12 (with ``edge_props`` on 12)."""
    return route_of(node(1, 0, 0), node(2, 4, 0), node(3, 8, 0), edge(11, 1, 2),
                    edge(12, 2, 3, **edge_props))  # fmt: skip


async def test_speed_limit_from_each_edge_entered() -> None:
    limits: list[float] = []
    manager = OperationsManager([AdjustSpeedLimit(limits.append)])
    route = straight(metadata={"speed_limit": 40.0})
    tracker = RouteTracker(route, TrackerParams(), ReroutingState())
    for x in (0.0, 1.0, 3.5, 4.0, 6.0):
        changed, _ = tracker.update((x, 0.0))
        result = await manager.process(changed, tracker, (x, 0.0), 0.0)
        assert result.operations_triggered == (["AdjustSpeedLimit"] if changed else [])
    assert limits == [100.0, 40.0]  # edge 11 has none: no limit (100 %); edge 12 says 40 %


def grid_blocked_at(x: float) -> CostGrid:
    costs = np.zeros((40, 200), dtype=np.uint8)
    col = int(x / 0.05)
    costs[:, col : col + 2] = 254
    return CostGrid(GridGeometry(200, 40, 0.05, 0.0, -1.0), costs)


async def test_collision_ahead_blocks_that_edge_within_range_and_rate() -> None:
    route = straight()
    grid = grid_blocked_at(6.0)  # on edge 12
    monitor = CollisionMonitor(lambda: grid, max_collision_dist=3.0)
    manager = OperationsManager([monitor])
    tracker = RouteTracker(route, TrackerParams(), ReroutingState())
    tracker.update((0.0, 0.0))
    assert not (await manager.process(False, tracker, (1.0, 0.0), now=0.0)).reroute  # 5 m away
    assert not (await manager.process(False, tracker, (3.5, 0.0), now=0.5)).reroute  # not due
    result = await manager.process(False, tracker, (3.5, 0.0), now=1.0)  # 2.5 m ahead, across edges
    assert result.reroute
    assert result.blocked_ids == [12]
    assert result.operations_triggered == ["CollisionMonitor"]


async def test_collision_without_rerouting_fails_the_task() -> None:
    grid = grid_blocked_at(2.0)
    monitor = CollisionMonitor(lambda: grid, reroute_on_collision=False)
    tracker = RouteTracker(straight(), TrackerParams(), ReroutingState())
    tracker.update((0.0, 0.0))
    with pytest.raises(RouteError) as caught:
        await OperationsManager([monitor]).process(False, tracker, (0.5, 0.0), now=5.0)
    assert caught.value.reason == "OPERATION_FAILED"
    assert caught.value.code == 406


async def test_graph_operations_run_by_name_and_an_unknown_one_fails() -> None:
    seen: list[dict[str, object]] = []

    class OpenDoor:
        name = "open_door"
        process_type: ProcessType = "ON_GRAPH"

        async def perform(self, event: object) -> OperationResult:
            seen.append(event.metadata)  # type: ignore[attr-defined]
            return OperationResult()

    route = straight(operations={"door": {"type": "open_door", "trigger": "ON_ENTER",
                                          "metadata": {"door_id": 54}}})  # fmt: skip
    tracker = RouteTracker(route, TrackerParams(), ReroutingState())
    manager = OperationsManager([OpenDoor()])
    for x in (0.0, 2.0, 4.0):
        changed, _ = tracker.update((x, 0.0))
        await manager.process(changed, tracker, (x, 0.0), 0.0)
    assert seen == [{"door_id": 54}]
    tracker = RouteTracker(route, TrackerParams(), ReroutingState())
    for x in (0.0, 2.0):
        tracker.update((x, 0.0))
    tracker.update((4.0, 0.0))
    with pytest.raises(RouteError, match="operation 'open_door'"):
        await OperationsManager([]).process(True, tracker, (4.0, 0.0), 0.0)


async def test_rerouting_service_asks_once() -> None:
    service = ReroutingService()
    tracker = RouteTracker(straight(), TrackerParams(), ReroutingState())
    manager = OperationsManager([service])
    assert not (await manager.process(False, tracker, (0.0, 0.0), 0.0)).reroute
    service.requested = True
    assert (await manager.process(False, tracker, (0.0, 0.0), 0.0)).reroute
    assert not (await manager.process(False, tracker, (0.0, 0.0), 0.0)).reroute
