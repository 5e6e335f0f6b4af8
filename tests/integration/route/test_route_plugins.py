"""The route server process with Nav2's TimeMarker, TimeScorer and a TriggerEvent loaded
under its own name: a tracked route calls the door's std_srvs/Trigger service on the bus
where the graph asks, and the times the robot took then price the next route."""

from __future__ import annotations

import asyncio
from pathlib import Path
from typing import Any

import pytest

from aiobt.msgs import OccupancyGrid, PoseStamped
from aiobt.msgs.remote_actions import ComputeAndTrackRoute, ComputeRoute
from aiobt.msgs.std import Trigger
from aiobt.transport import Bus, BusSettings
from aiobt_services.robot.convert import occupancy_grid
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.worlds import OFFICE

from .test_route_service import Spawn, corridor_graph, route, start

pytestmark = pytest.mark.integration

DOOR = {"door1": {"type": "OpenDoor", "trigger": "ON_ENTER",
                  "metadata": {"service_name": "/doors/door1"}}}  # fmt: skip
"""Edge 12's graph operation: entering it opens door 1."""


async def test_a_door_opened_on_the_way_and_the_times_taken_price_the_next_route(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings, tmp_path: Path
) -> None:
    bus.latched_publisher("map", OccupancyGrid).put(occupancy_grid(load_map(OFFICE)))
    opened: list[float] = []
    poses = bus.publisher("pose", PoseStamped)
    x = 2.0

    def open_door(_req: Trigger.Request) -> Trigger.Response:
        opened.append(x)
        return Trigger.Response(success=True, message="door 1 open")

    bus.serve("doors/door1", Trigger.Request, Trigger.Response, open_door)
    graph = corridor_graph(tmp_path / "d.json", operations=DOOR)
    await start(spawn, bus, bus_settings, "--graph-filepath", str(graph),
                "--edge-cost-functions", "TimeScorer", "--operations", "TimeMarker,OpenDoor",
                "--param", "OpenDoor.plugin=nav2_route::TriggerEvent")  # fmt: skip
    before = await route(bus, ComputeRoute.Goal(start_id=1, goal_id=3))
    assert before.error_code == 0, before.error_msg
    assert before.route.route_cost == pytest.approx(16.0)  # 8 m at max_vel 0.5 m/s
    feedback: list[Any] = []
    client = bus.action_client(ComputeAndTrackRoute.name, ComputeAndTrackRoute)
    poses.put(PoseStamped.from_xy_yaw(x, 9.75, 0.0))
    handle = await client.send_goal(ComputeAndTrackRoute.Goal(start_id=1, goal_id=3),
                                    server_timeout=10.0, on_feedback=feedback.append)  # fmt: skip
    async with asyncio.timeout(30.0):
        while not handle.done:
            poses.put(PoseStamped.from_xy_yaw(x, 9.75, 0.0))
            await asyncio.sleep(0.02)
            if feedback:  # the robot sets off once the route is being tracked
                x = min(10.0, x + 0.04)  # 2 m/s, if the loop keeps its pace
    result = await handle.result(timeout=5.0)
    assert result.error_code == 0, result.error_msg
    assert len(opened) == 1  # once, on entering edge 12 (node 2 achieved: x within 2 m of 6)
    assert 4.0 <= opened[0] <= 8.0
    assert any("OpenDoor" in f.operations_triggered for f in feedback)
    after = await route(bus, ComputeRoute.Goal(start_id=1, goal_id=3))
    assert after.error_code == 0, after.error_msg
    # TimeMarker wrote each edge's time, the TimeScorer now prices the route by them: the
    # robot drove 8 m in about 4 s of wall time (more if this machine is loaded)
    assert 1.0 < after.route.route_cost < result.execution_duration + 0.1
    assert after.route.route_cost < 16.0
