"""Nav2's route operations, their manager (``OperationsManager``) and the registry of
every operation (:mod:`.time_marker`'s and :mod:`.trigger_event`'s too).

Operations run while a route is tracked: those the graph names at a node
(``NODE``) or edge (``ON_ENTER``/``ON_EXIT``) when the robot achieves that node,
by the operation's name (``TriggerEvent``); ``AdjustSpeedLimit`` and ``TimeMarker``
at every node achieved (status change); ``CollisionMonitor`` and
``ReroutingService`` at every tracker update (query). One may ask for a reroute,
with ids to block. A graph operation no loaded operation serves is
OPERATION_FAILED, as in Nav2. ``perform`` is a coroutine, so that an operation may
wait on a service (TriggerEvent) while the tracking waits for it, as Nav2's does.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Protocol

from aiobt.costmap import NO_INFORMATION, CostGrid, points_cost
from aiobt.costmap.collision import segment_points

from .errors import RouteError
from .graph import GraphEdge, GraphNode, Metadata, Operation, Trigger, metadata_float
from .operation_event import Event, OperationResult, ProcessType
from .time_marker import TimeMarker
from .tracker import RouteTracker
from .trigger_event import TriggerEvent
from .vectors import XY, closest_point, distance


class RouteOperation(Protocol):
    name: str
    process_type: ProcessType

    async def perform(self, event: Event) -> OperationResult: ...


@dataclass(slots=True)
class AdjustSpeedLimit:
    """On entering an edge, publish its ``speed_tag`` metadata (a percentage, 100 when
    absent) as the speed limit."""

    publish: Callable[[float], None]
    name: str = "AdjustSpeedLimit"  # the name it is loaded under
    speed_tag: str = "speed_limit"
    process_type: ProcessType = field(default="ON_STATUS_CHANGE", init=False)

    async def perform(self, event: Event) -> OperationResult:
        if event.edge_entered is not None:
            self.publish(metadata_float(event.edge_entered, self.speed_tag, 100.0))
        return OperationResult()


@dataclass(slots=True)
class ReroutingService:
    """A reroute asked for from outside (``route_server/ReroutingService/reroute``)."""

    name: str = "ReroutingService"  # the name it is loaded under
    process_type: ProcessType = field(default="ON_QUERY", init=False)
    requested: bool = field(default=False, init=False)

    async def perform(self, event: Event) -> OperationResult:
        asked, self.requested = self.requested, False
        return OperationResult(reroute=asked)


@dataclass(slots=True)
class CollisionMonitor:
    """Every 1/``rate`` robot s, check the route ``max_collision_dist`` ahead of the
    robot in the costmap; a cell at or over ``max_cost`` (unknown excluded) blocks the
    edge it lies on: reroute around it (``reroute_on_collision``) or fail the task."""

    costmap: Callable[[], CostGrid | None]
    name: str = "CollisionMonitor"  # the name it is loaded under
    rate: float = 1.0
    max_cost: float = 253.0
    max_collision_dist: float = 5.0
    check_resolution: int = 1
    reroute_on_collision: bool = True
    process_type: ProcessType = field(default="ON_QUERY", init=False)
    last_check: float = field(default=float("-inf"), init=False)

    async def perform(self, event: Event) -> OperationResult:
        edge = event.edge_entered
        if edge is None or event.now - self.last_check < 1.0 / self.rate:
            return OperationResult()
        self.last_check = event.now
        grid = self.costmap()
        if grid is None:
            raise RouteError("OPERATION_FAILED", f"{self.name}: no costmap received yet")
        blocked = self._first_blocked(grid, edge, event)
        if blocked is None:
            return OperationResult()
        if not self.reroute_on_collision:
            raise RouteError("OPERATION_FAILED", f"{self.name}: edge {blocked} is blocked and "
                             "reroute_on_collision is false")  # fmt: skip
        return OperationResult(reroute=True, blocked_ids=[blocked])

    def _first_blocked(self, grid: CostGrid, edge: GraphEdge, event: Event) -> int | None:
        ahead = self.max_collision_dist if self.max_collision_dist > 0 else float("inf")
        edges = event.route.edges
        index = next((i for i, e in enumerate(edges) if e is edge), len(edges))
        segment_start = closest_point(event.pose, (edge.start.x, edge.start.y),
                                      (edge.end.x, edge.end.y))  # fmt: skip
        for current in [edge, *edges[index + 1 :]]:
            end = (current.end.x, current.end.y)
            length = distance(segment_start, end)
            if length > ahead:
                scale = ahead / length
                end = (segment_start[0] + (end[0] - segment_start[0]) * scale,
                       segment_start[1] + (end[1] - segment_start[1]) * scale)  # fmt: skip
            if self._hits(grid, segment_start, end):
                return current.edgeid
            ahead -= length
            if ahead <= 0.0:
                return None
            segment_start = end
        return None

    def _hits(self, grid: CostGrid, start: XY, end: XY) -> bool:
        spacing = grid.geometry.resolution * self.check_resolution
        points = segment_points(*start, *end, spacing)
        on_map = [grid.geometry.contains_world(x, y) for x, y in points]
        costs = points_cost(grid, points[:, 0], points[:, 1])[on_map]
        return bool(((costs >= self.max_cost) & (costs != NO_INFORMATION)).any())


@dataclass(slots=True)
class OperationsResult:
    reroute: bool = False
    blocked_ids: list[int] = field(default_factory=list)
    operations_triggered: list[str] = field(default_factory=list)

    def add(self, name: str, result: OperationResult) -> None:
        self.reroute = self.reroute or result.reroute
        self.blocked_ids.extend(result.blocked_ids)
        self.operations_triggered.append(name)


class OperationsManager:
    def __init__(self, operations: Sequence[RouteOperation]) -> None:
        self.on_graph = {op.name: op for op in operations if op.process_type == "ON_GRAPH"}
        self.on_change = [op for op in operations if op.process_type == "ON_STATUS_CHANGE"]
        self.on_query = [op for op in operations if op.process_type == "ON_QUERY"]

    async def process(
        self, status_change: bool, tracker: RouteTracker, pose: XY, now: float
    ) -> OperationsResult:
        event = Event(tracker.last_node, tracker.current_edge, tracker.edge_exited,
                      tracker.route, pose, now)  # fmt: skip
        result = OperationsResult()
        if status_change:
            for op in self._graph_operations(event):
                served = self.on_graph.get(op.type)
                if served is None:
                    problem = f"operation '{op.type}' asked for by the graph is not loaded"
                    raise RouteError("OPERATION_FAILED", problem)
                result.add(served.name, await served.perform(_with(event, op.metadata)))
            for change in self.on_change:
                result.add(change.name, await change.perform(event))
        for query in self.on_query:  # every cycle; named only when it acted (not Nav2's)
            outcome = await query.perform(event)
            if outcome.reroute or outcome.blocked_ids:
                result.add(query.name, outcome)
        return result

    @staticmethod
    def _graph_operations(event: Event) -> list[Operation]:
        found: list[Operation] = []
        holders: tuple[tuple[GraphNode | GraphEdge | None, Trigger], ...] = (
            (event.node, "NODE"), (event.edge_entered, "ON_ENTER"), (event.edge_exited, "ON_EXIT")
        )  # fmt: skip
        for holder, trigger in holders:
            if holder is not None:
                found.extend(op for op in holder.operations if op.trigger == trigger)
        return found


def _with(event: Event, metadata: Metadata) -> Event:
    return Event(event.node, event.edge_entered, event.edge_exited, event.route, event.pose,
                 event.now, metadata)  # fmt: skip


OPERATIONS: dict[str, type[RouteOperation]] = {
    "AdjustSpeedLimit": AdjustSpeedLimit,
    "ReroutingService": ReroutingService,
    "CollisionMonitor": CollisionMonitor,
    "TimeMarker": TimeMarker,
    "TriggerEvent": TriggerEvent,
}
"""The route operations by Nav2's plugin ids (:func:`.plugins.make_plugin` builds them)."""
DEFAULT_OPERATIONS = ("AdjustSpeedLimit", "ReroutingService", "CollisionMonitor")  # bringup's
