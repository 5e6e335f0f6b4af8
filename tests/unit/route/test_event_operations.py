"""TimeMarker (edge times into the graph, for the TimeScorer) and TriggerEvent (a
std_srvs/Trigger service where the graph asks), driven through the OperationsManager as
the tracking drives them, and loaded by Nav2's names and parameters."""

from __future__ import annotations

import argparse
import re
from typing import Any

import pytest

from aiobt.msgs.std import Trigger
from aiobt_services.route import main
from aiobt_services.route.errors import RouteError
from aiobt_services.route.geojson import parse_graph
from aiobt_services.route.graph import Graph
from aiobt_services.route.intent import ReroutingState
from aiobt_services.route.metadata_scorers import TimeScorer
from aiobt_services.route.operations import OperationsManager, RouteOperation
from aiobt_services.route.options import (
    add_route_arguments,
    args_problem,
    check_plugins,
    operations,
)
from aiobt_services.route.plugins import Wiring
from aiobt_services.route.scorers import EdgeScorer
from aiobt_services.route.search import Route, find_route
from aiobt_services.route.time_marker import TimeMarker
from aiobt_services.route.tracker import RouteTracker, TrackerParams
from aiobt_services.route.trigger_event import CALL_TIMEOUT, TriggerEvent

from .helpers import Triggers, edge, node, text


def corridor(**edge_12: Any) -> Graph:
    """1 (0,0) -> 2 (4,0) -> 3 (8,0) -> 4 (12,0): edges 11, 12 (with ``edge_12``), 13."""
    return parse_graph(text(node(1, 0, 0), node(2, 4, 0), node(3, 8, 0), node(4, 12, 0),
                            edge(11, 1, 2), edge(12, 2, 3, **edge_12), edge(13, 3, 4)))  # fmt: skip


def timed_route(graph: Graph) -> Route:
    first, last = graph.node(1), graph.node(4)
    assert first is not None
    assert last is not None
    return find_route(graph, first, last, EdgeScorer([TimeScorer()]))


async def drive(graph: Graph, ops: list[Any], start: float = 5.0) -> list[str]:
    """Along the corridor at 1 m/s in 0.5 s ticks from robot time ``start`` (x = t - start);
    the operations triggered, in order."""
    manager = OperationsManager(ops)
    tracker = RouteTracker(timed_route(graph), TrackerParams(), ReroutingState())
    triggered: list[str] = []
    for tick in range(30):
        x = tick * 0.5
        changed, completed = tracker.update((x, 0.0))
        result = await manager.process(changed, tracker, (x, 0.0), start + x)
        triggered += result.operations_triggered
        if completed:
            return triggered
    raise AssertionError("the route was not completed")


def times(graph: Graph, tag: str = "abs_time_taken") -> dict[int, object]:
    return {e.edgeid: e.metadata.get(tag) for e in graph.edges.values()}


async def test_time_marker_writes_each_edge_s_time_for_the_time_scorer() -> None:
    graph = corridor()
    assert timed_route(graph).route_cost == pytest.approx(24.0)  # 12 m at max_vel 0.5 m/s
    assert await drive(graph, [TimeMarker()]) == ["TimeMarker"] * 4  # at each node achieved
    # nodes 1, 2, 3 are achieved at x 0, 4, 8 (their bisector lines), the last node 1 m short
    assert times(graph) == {11: 4.0, 12: 4.0, 13: 3.0}
    assert timed_route(graph).route_cost == pytest.approx(11.0)  # the times the robot took


async def test_time_marker_edge_cases_as_nav2() -> None:
    graph = corridor()
    await drive(graph, [TimeMarker(time_tag="took")], start=0.0)
    assert times(graph, "took") == {11: None, 12: 4.0, 13: 3.0}  # entered at robot time 0
    assert times(graph) == {11: None, 12: None, 13: None}
    marker = TimeMarker()
    marker.curr_edge, marker.edge_start_time = 99, 2.0  # an edge entered on an earlier route
    graph = corridor()
    manager = OperationsManager([marker])
    tracker = RouteTracker(timed_route(graph), TrackerParams(), ReroutingState())
    tracker.update((0.0, 0.0))
    tracker.update((4.0, 0.0))  # node 2 achieved: edge 11 exited, but it was not entered
    await manager.process(True, tracker, (4.0, 0.0), 9.0)
    assert times(graph)[11] is None
    assert marker.curr_edge == 12


def door(**metadata: Any) -> dict[str, Any]:
    """Edge 12's graph operation: OpenDoor on entering it, with ``metadata``."""
    return {"operations": {"door": {"type": "OpenDoor", "trigger": "ON_ENTER",
                                    "metadata": metadata}}}  # fmt: skip


async def test_trigger_event_calls_the_service_the_graph_names() -> None:
    calls = Triggers()
    opener = TriggerEvent(calls, name="OpenDoor", service_name="doors/all")
    triggered = await drive(corridor(**door(service_name="doors/door1")), [opener])
    assert calls.calls == [("doors/door1", CALL_TIMEOUT)]  # the graph's name before the param
    assert triggered == ["OpenDoor"]
    assert CALL_TIMEOUT == 0.5  # Nav2's 500 ms
    calls.calls.clear()
    await drive(corridor(**door()), [opener])
    assert calls.calls == [("doors/all", CALL_TIMEOUT)]  # the parameter's, for every door


async def test_trigger_event_failures_fail_the_goal_naming_what_and_where() -> None:
    with pytest.raises(RouteError) as caught:
        await drive(corridor(**door()), [TriggerEvent(Triggers(), name="OpenDoor")])
    assert caught.value.reason == "OPERATION_FAILED"
    assert "route operation OpenDoor at node 2: no service to call" in caught.value.message
    down = Triggers(fail=TimeoutError("doors/door1: no server within 0.5 s"))
    with pytest.raises(RouteError) as caught:
        await drive(corridor(**door(service_name="doors/door1")), [TriggerEvent(down, "OpenDoor")])
    assert caught.value.reason == "OPERATION_FAILED"
    assert caught.value.message == (
        "route operation OpenDoor at node 2: calling service 'doors/door1' failed: "
        "doors/door1: no server within 0.5 s"
    )
    refused = Triggers(response=Trigger.Response(success=False, message="jammed"))
    opener = TriggerEvent(refused, name="OpenDoor", service_name="doors/all")
    assert await drive(corridor(**door()), [opener]) == ["OpenDoor"]  # Nav2 reads no answer


def parse(*argv: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser()
    add_route_arguments(parser.add_argument_group("route"))
    return parser.parse_args(list(argv))


async def test_operations_load_under_their_names_with_nav2_s_plugin_parameter() -> None:
    calls = Triggers()
    wiring = Wiring(lambda: None, lambda _: None, calls)
    args = parse("--operations", "TimeMarker,OpenDoor,CallLift",
                 "--param", "OpenDoor.plugin=nav2_route::TriggerEvent",
                 "--param", "OpenDoor.service_name=doors/main",
                 "--param", "CallLift.plugin=TriggerEvent",
                 "--param", "TimeMarker.time_tag=took")  # fmt: skip
    check_plugins(args)
    marker, opener, lift = made = operations(args, wiring)
    assert isinstance(marker, TimeMarker)
    assert marker.time_tag == "took"
    assert isinstance(opener, TriggerEvent)
    assert isinstance(lift, TriggerEvent)
    assert (opener.name, opener.service_name, lift.name, lift.service_name) == (
        "OpenDoor",
        "doors/main",
        "CallLift",
        "",
    )
    graph = corridor(**door())
    ops: list[RouteOperation] = list(made)
    triggered = await drive(graph, ops)  # the graph's operations first at a node, as Nav2
    assert triggered == ["TimeMarker", "OpenDoor", "TimeMarker", "TimeMarker", "TimeMarker"]
    assert calls.calls == [("doors/main", CALL_TIMEOUT)]
    assert times(graph, "took")[11] == 4.0


@pytest.mark.parametrize(
    ("argv", "error"),
    [
        (["--operations", "OpenDoor", "--param", "OpenDoor.plugin=DoorOpener"],
         "operations: unknown plugin 'DoorOpener' (OpenDoor.plugin) (known: AdjustSpeedLimit"),
        (["--operations", "OpenDoor"], "operations: unknown plugin 'OpenDoor' (known: "),
        (["--operations", "TriggerEvent", "--param", "TriggerEvent.name=x"],
         "TriggerEvent.name: no such parameter (known: service_name)"),
        (["--operations", "TimeMarker", "--param", "TimeMarker.time=x"],
         "TimeMarker.time: no such parameter (known: time_tag)"),
    ],
)  # fmt: skip
def test_bad_operation_parameters_are_named(argv: list[str], error: str) -> None:
    wiring = Wiring(lambda: None, lambda _: None, Triggers())
    with pytest.raises(ValueError, match=re.escape(error)):
        operations(parse(*argv), wiring)


def test_a_bad_plugin_parameter_stops_the_server_before_the_bus(
    caplog: pytest.LogCaptureFixture,
) -> None:
    parser = argparse.ArgumentParser()
    main.add_arguments(parser)
    good = parser.parse_args(["--operations", "OpenDoor", "--param",
                              "OpenDoor.plugin=TriggerEvent"])  # fmt: skip
    assert args_problem(good) is None
    bad = parser.parse_args(["--connect", "tcp/127.0.0.1:1", "--edge-cost-functions",
                             "TimeScorer", "--param", "TimeScorer.max_vel=-1"])  # fmt: skip
    assert main.run(bad) == 2  # at once: no bus is tried (no router listens on port 1)
    assert "route: TimeScorer.max_vel must be > 0 m/s, got -1.0" in caplog.text
