"""The route server's graph and routes as the page gets them (Sources.flush)."""

from __future__ import annotations

import json

from aiobt.msgs import Header, Path, PoseStamped
from aiobt.msgs.geometry import Point
from aiobt.msgs.remote_actions import ComputeRoute
from aiobt.msgs.route import RouteEdge, RouteNode
from aiobt.msgs.route_graph import RouteGraph
from aiobt.transport import Bus
from aiobt.web.coalesce import Hub
from aiobt.web.sources import Sources


def _graph() -> RouteGraph:
    a, b, c = Point(x=1.0, y=2.0), Point(x=3.0, y=2.0), Point(x=3.0, y=4.00049)
    return RouteGraph(
        name="lanes",
        nodes=[
            RouteNode(nodeid=1, position=a),
            RouteNode(nodeid=2, position=b),
            RouteNode(nodeid=3, position=c),
        ],
        edges=[
            RouteEdge(edgeid=10, start=a, end=b),
            RouteEdge(edgeid=11, start=b, end=a),
            RouteEdge(edgeid=12, start=b, end=c),
        ],
    )


async def test_the_graph_is_sent_once_per_lane(local_bus: Bus) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    sources.raw.set("route_graph", _graph())
    sources.flush()
    payload = json.loads(hub.latest["route_graph"])
    assert payload["name"] == "lanes"
    assert payload["nodes"] == [[1.0, 2.0, 1], [3.0, 2.0, 2], [3.0, 4.0, 3]]
    assert payload["edges"] == [[1.0, 2.0, 3.0, 2.0], [3.0, 2.0, 3.0, 4.0]]  # 10 and 11: one
    sources.close()


async def test_a_computed_route_is_drawn_and_a_failed_one_is_not(local_bus: Bus) -> None:
    hub = Hub()
    sources = Sources(local_bus, hub)
    path = Path(header=Header(frame_id="map"),
                poses=[PoseStamped.from_xy_yaw(x, 2.0, 0.0) for x in (1.0, 2.0, 3.0)])  # fmt: skip
    sources.raw.set("route", ComputeRoute.Result(error_code=405, error_msg="no route"))
    sources.flush()
    assert "route" not in hub.latest
    sources.raw.set("route", ComputeRoute.Result(path=path))
    sources.flush()
    assert json.loads(hub.latest["route"]) == [[1.0, 2.0], [2.0, 2.0], [3.0, 2.0]]
    sources.close()
