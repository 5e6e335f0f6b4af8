"""Nav2's ``TimeMarker`` route operation: the time the robot took to drive each edge,
written into that edge's metadata under ``time_tag`` (Nav2's ``abs_time_taken``),
where the ``TimeScorer`` reads it in later searches."""

from __future__ import annotations

from dataclasses import dataclass, field

from .operation_event import Event, OperationResult, ProcessType

NO_START = 1e-3  # Nav2 writes no time for an edge whose start time is not after this


@dataclass(slots=True)
class TimeMarker:
    """At every node achieved: when the edge exited is the one entered at the last node
    achieved, its metadata ``time_tag`` becomes the robot time between the two (an edge
    entered at robot time 0 is not timed, as in Nav2). The times stay in the loaded graph
    for the server's life, not in its file."""

    name: str = "TimeMarker"  # the name it is loaded under
    time_tag: str = "abs_time_taken"
    process_type: ProcessType = field(default="ON_STATUS_CHANGE", init=False)
    edge_start_time: float = field(default=0.0, init=False)
    curr_edge: int | None = field(default=None, init=False)  # the edge entered last

    async def perform(self, event: Event) -> OperationResult:
        exited = event.edge_exited
        if (
            exited is not None
            and exited.edgeid == self.curr_edge
            and (self.edge_start_time > NO_START)
        ):
            exited.metadata[self.time_tag] = event.now - self.edge_start_time
        self.edge_start_time = event.now
        entered = event.edge_entered
        self.curr_edge = entered.edgeid if entered is not None else None
        return OperationResult()
