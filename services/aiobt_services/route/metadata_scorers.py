"""Nav2's edge scorers on graph metadata: ``TimeScorer`` (the time to drive an edge) and
``SemanticScorer`` (costs by semantic class)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from .graph import GraphEdge, Metadata, metadata_float
from .request import EdgeType, RouteRequest


@dataclass(slots=True)
class TimeScorer:
    """``weight`` times the edge's time: its ``time_tag`` metadata when > 0 (the time
    the TimeMarker operation, or the graph file, recorded), else its length over its
    ``speed_tag`` metadata (m/s), or over ``max_vel`` when that is not > 0."""

    weight: float = 1.0
    speed_tag: str = "abs_speed_limit"
    time_tag: str = "abs_time_taken"
    max_vel: float = 0.5

    def __post_init__(self) -> None:
        if not self.max_vel > 0.0:
            raise ValueError(f"TimeScorer.max_vel must be > 0 m/s, got {self.max_vel}")

    def prepare(self) -> None:
        return None

    def score(self, edge: GraphEdge, request: RouteRequest, edge_type: EdgeType) -> float | None:
        taken = metadata_float(edge, self.time_tag, 0.0)
        if taken > 0.0:
            return self.weight * taken
        speed = metadata_float(edge, self.speed_tag, 0.0)
        return self.weight * edge.length / (speed if speed > 0.0 else self.max_vel)


@dataclass(slots=True)
class SemanticScorer:
    """``weight`` times the costs of the semantic classes of the edge and of its end
    node: the class each names under ``semantic_key``, or, with ``semantic_key`` empty,
    every metadata key that is a class. ``semantic_classes`` lists the classes; each
    class's cost is the parameter of its name (``SemanticScorer.<class>``), which must be
    given, as in Nav2."""

    EXTRA_PARAMS: ClassVar[str] = "class_costs"  # parameters named by semantic_classes

    weight: float = 1.0
    semantic_key: str = "class"
    semantic_classes: tuple[str, ...] = ()
    class_costs: dict[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for name in self.class_costs:
            if name not in self.semantic_classes:
                raise ValueError(f"SemanticScorer.{name}: no such parameter (known: weight, "
                                 "semantic_key, semantic_classes, and one cost for each class "
                                 f"of semantic_classes {list(self.semantic_classes)})")  # fmt: skip
        for name in self.semantic_classes:
            if name not in self.class_costs:
                raise ValueError(f"SemanticScorer.{name}: no cost given for the semantic class "
                                 f"'{name}' of semantic_classes")  # fmt: skip

    def prepare(self) -> None:
        return None

    def score(self, edge: GraphEdge, request: RouteRequest, edge_type: EdgeType) -> float | None:
        return self.weight * (self._cost(edge.end.metadata) + self._cost(edge.metadata))

    def _cost(self, metadata: Metadata) -> float:
        costs = self.class_costs
        if not self.semantic_key:
            return sum(costs[key] for key in metadata if key in costs)
        value = metadata.get(self.semantic_key)
        return costs.get(value, 0.0) if isinstance(value, str) else 0.0
