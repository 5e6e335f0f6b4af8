"""Nav2's RouteOperationClient: a service operation of your own type, its request made
from the graph operation's metadata and its answer turned into the route's result."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import pytest

from aiobt.msgs import Msg
from aiobt_services.route.errors import RouteError
from aiobt_services.route.graph import Metadata
from aiobt_services.route.intent import ReroutingState
from aiobt_services.route.operation_client import CALL_TIMEOUT, RouteOperationClient
from aiobt_services.route.operation_event import OperationResult
from aiobt_services.route.operations import OperationsManager, OperationsResult
from aiobt_services.route.tracker import RouteTracker, TrackerParams

from .test_event_operations import corridor, door, timed_route


class OpenDoorRequest(Msg):
    door: str = ""


class OpenDoorResponse(Msg):
    opened: bool = True


@dataclass(slots=True)
class OpenDoor(RouteOperationClient[OpenDoorRequest, OpenDoorResponse]):
    """A door that may stay shut: the route is planned again around its edge."""

    REQUEST: ClassVar[type[Msg]] = OpenDoorRequest
    RESPONSE: ClassVar[type[Msg]] = OpenDoorResponse

    name: str = "OpenDoor"
    edge: int = 0  # the door's edge, from the metadata

    def populate_request(self, metadata: Metadata) -> OpenDoorRequest:
        self.edge = int(str(metadata.get("edge", 0)))
        return OpenDoorRequest(door=str(metadata.get("door", "")))

    def process_response(self, response: OpenDoorResponse) -> OperationResult:
        return OperationResult() if response.opened else OperationResult(True, [self.edge])


class Doors:
    """The doors' services, faked: the requests by service name, each door's answer."""

    def __init__(self, shut: set[str]) -> None:
        self.shut = shut
        self.requests: list[tuple[str, Msg, float]] = []

    async def __call__(self, service: str, request: Msg, reply: type[Any], wait: float) -> Any:
        assert reply is OpenDoorResponse
        self.requests.append((service, request, wait))
        if service == "doors/missing":
            raise TimeoutError(f"{service}: no server within {wait} s")
        return reply(opened=service not in self.shut)


async def drive(op: OpenDoor, **metadata: Any) -> OperationsResult:
    """Along the corridor until OpenDoor ran on entering edge 12 (at node 2)."""
    manager = OperationsManager([op])
    tracker = RouteTracker(timed_route(corridor(**door(**metadata))), TrackerParams(),
                           ReroutingState())  # fmt: skip
    for tick in range(30):
        x = tick * 0.5
        changed, _ = tracker.update((x, 0.0))
        result = await manager.process(changed, tracker, (x, 0.0), x)
        if result.operations_triggered:
            return result
    raise AssertionError("OpenDoor never ran")


async def test_the_request_comes_from_the_metadata_and_the_answer_makes_the_result() -> None:
    doors = Doors(shut={"doors/d2"})
    opened = await drive(OpenDoor(doors), service_name="doors/d1", door="d1", edge=12)
    assert (opened.reroute, opened.blocked_ids) == (False, [])
    shut = await drive(OpenDoor(doors), service_name="doors/d2", door="d2", edge=12)
    assert (shut.reroute, shut.blocked_ids, shut.operations_triggered) == (True, [12], ["OpenDoor"])
    asked = [(s, r.model_dump(), w) for s, r, w in doors.requests]
    assert asked == [("doors/d1", {"door": "d1"}, CALL_TIMEOUT),
                     ("doors/d2", {"door": "d2"}, CALL_TIMEOUT)]  # fmt: skip


async def test_one_service_for_all_from_the_parameter_and_failures_named() -> None:
    doors = Doors(shut=set())
    await drive(OpenDoor(doors, service_name="doors/all"), door="d3")
    assert doors.requests[0][0] == "doors/all"  # centralised: the parameter's service
    with pytest.raises(RouteError, match="OpenDoor at node 2: calling service 'doors/missing'"):
        await drive(OpenDoor(doors), service_name="doors/missing")
    with pytest.raises(RouteError, match="OpenDoor at node 2: no service to call"):
        await drive(OpenDoor(doors))
