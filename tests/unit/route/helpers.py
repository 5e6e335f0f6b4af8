"""Small graphs for the route tests, written as Nav2 GeoJSON text."""

from __future__ import annotations

import json
from typing import Any

from aiobt.msgs import Msg
from aiobt.msgs.std import Trigger
from aiobt_services.route.geojson import parse_graph
from aiobt_services.route.graph import Graph


def node(nodeid: int, x: float, y: float, **props: Any) -> dict[str, Any]:
    return {"type": "Feature", "properties": {"id": nodeid, **props},
            "geometry": {"type": "Point", "coordinates": [x, y]}}  # fmt: skip


def edge(edgeid: int, start: int, end: int, **props: Any) -> dict[str, Any]:
    props = {"id": edgeid, "startid": start, "endid": end, **props}
    geometry = {"type": "MultiLineString", "coordinates": [[[0, 0], [1, 1]]]}
    return {"type": "Feature", "properties": props, "geometry": geometry}


def text(*features: dict[str, Any]) -> str:
    return json.dumps({"type": "FeatureCollection", "features": list(features)})


def two_way(first_id: int, a: int, b: int, **props: Any) -> list[dict[str, Any]]:
    return [edge(first_id, a, b, **props), edge(first_id + 1, b, a, **props)]


def square() -> Graph:
    """1 (0,0) - 2 (4,0) - 3 (4,4) and 1 - 4 (0,4) - 3: two ways round, 8 m each;
    edges 10-17, two-way."""
    return parse_graph(text(
        node(1, 0, 0), node(2, 4, 0), node(3, 4, 4), node(4, 0, 4),
        *two_way(10, 1, 2), *two_way(12, 2, 3), *two_way(14, 1, 4), *two_way(16, 4, 3),
    ), "square.geojson")  # fmt: skip


def line(*xs: float) -> Graph:
    """Nodes 1..n at (x, 0), one-way edges 101.. from each to the next."""
    nodes = [node(i + 1, x, 0.0) for i, x in enumerate(xs)]
    edges = [edge(101 + i, i + 1, i + 2) for i in range(len(xs) - 1)]
    return parse_graph(text(*nodes, *edges), "line.geojson")


class Triggers:
    """The server's service caller, faked for std_srvs/Trigger: the calls made (service,
    timeout); each answers ``response``, or raises ``fail``."""

    def __init__(self, fail: Exception | None = None, response: Trigger.Response | None = None):
        self.calls: list[tuple[str, float]] = []
        self.fail = fail
        self.response = response or Trigger.Response(success=True, message="done")

    async def __call__(self, service: str, request: Msg, reply: type[Any],
                       wait: float) -> Trigger.Response:  # fmt: skip
        assert (type(request), reply) == (Trigger.Request, Trigger.Response)
        self.calls.append((service, wait))
        if self.fail is not None:
            raise self.fail
        return self.response
