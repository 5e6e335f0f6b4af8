"""Nav2's edge scorers: the ``Scorer`` protocol, ``DistanceScorer``, ``PenaltyScorer``,
``CostmapScorer``, ``DynamicEdgesScorer``, and the registry of every scorer (those of
:mod:`.metadata_scorers` and :mod:`.orientation_scorers` too).

A scorer gives an edge a cost, or ``None`` when the edge may not be used now
(Nav2's ``score`` returning false), seeing, as Nav2's ``score(edge, route_request,
edge_type, cost)``, the request and whether the edge leaves the search's start or
reaches its goal. Parameters carry Nav2's names and defaults (the code's:
``CostmapScorer.check_resolution`` is 2). :class:`EdgeScorer` sums the scorers of
``edge_cost_functions``; one ``None`` closes the edge.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from aiobt.costmap import CostGrid, line_cells

from .graph import GraphEdge, metadata_float
from .metadata_scorers import SemanticScorer, TimeScorer
from .orientation_scorers import GoalOrientationScorer, StartPoseOrientationScorer
from .request import EdgeType, RouteRequest

UNKNOWN_COST = 255
CostmapSource = Callable[[], CostGrid | None]


class Scorer(Protocol):
    def prepare(self) -> None: ...
    def score(
        self, edge: GraphEdge, request: RouteRequest, edge_type: EdgeType
    ) -> float | None: ...


@dataclass(slots=True)
class DistanceScorer:
    """The edge's length, divided by its ``speed_tag`` metadata when set (Nav2 divides
    by the stored percentage as it is), times ``weight``."""

    weight: float = 1.0
    speed_tag: str = "speed_limit"

    def prepare(self) -> None:
        return None

    def score(self, edge: GraphEdge, request: RouteRequest, edge_type: EdgeType) -> float | None:
        speed = metadata_float(edge, self.speed_tag, 1.0)
        if speed <= 0.0:
            return None  # a zero speed limit: the edge cannot be driven
        return self.weight * edge.length / speed


@dataclass(slots=True)
class PenaltyScorer:
    """``weight`` times the edge's ``penalty_tag`` metadata (0 when absent)."""

    weight: float = 1.0
    penalty_tag: str = "penalty"

    def prepare(self) -> None:
        return None

    def score(self, edge: GraphEdge, request: RouteRequest, edge_type: EdgeType) -> float | None:
        return self.weight * metadata_float(edge, self.penalty_tag, 0.0)


@dataclass(slots=True)
class CostmapScorer:
    """Costs of the cells the edge crosses (every ``check_resolution``-th), as a share
    of ``max_cost``: the largest (``use_maximum``) or the mean. A cell at or over
    ``max_cost`` closes the edge (``invalid_on_collision``), as does an end off the
    map (``invalid_off_map``); no costmap closes every edge, as in Nav2."""

    costmap: CostmapSource = field(repr=False)
    weight: float = 1.0
    max_cost: float = 253.0
    use_maximum: bool = True
    invalid_on_collision: bool = True
    invalid_off_map: bool = True
    check_resolution: int = 2
    _grid: CostGrid | None = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        if self.check_resolution < 1:
            raise ValueError(f"CostmapScorer.check_resolution must be >= 1, got "
                             f"{self.check_resolution}")  # fmt: skip
        if self.max_cost <= 0.0:
            raise ValueError(f"CostmapScorer.max_cost must be > 0, got {self.max_cost}")

    def prepare(self) -> None:
        self._grid = self.costmap()

    def score(self, edge: GraphEdge, request: RouteRequest, edge_type: EdgeType) -> float | None:
        grid = self._grid
        if grid is None:
            return None
        start = grid.geometry.world_to_cell(edge.start.x, edge.start.y)
        end = grid.geometry.world_to_cell(edge.end.x, edge.end.y)
        if start is None or end is None:
            return None if self.invalid_off_map else 0.0
        cols, rows = line_cells(*start, *end)
        costs = grid.costs[rows[:: self.check_resolution], cols[:: self.check_resolution]]
        costs = costs.astype(np.float64)
        if (self.invalid_on_collision and self.max_cost != UNKNOWN_COST
                and bool((costs >= self.max_cost).any())):  # fmt: skip
            return None
        if self.use_maximum:
            known = costs[costs != UNKNOWN_COST]
            return self.weight * (float(known.max()) if known.size else 0.0) / self.max_cost
        return self.weight * float(costs.mean()) / self.max_cost


@dataclass(slots=True)
class DynamicEdgesScorer:
    """Edges closed, and costs set, from outside (``adjust_edges``): a closed edge is
    not used; an edge with a cost set scores it; any other scores 0."""

    closed: set[int] = field(default_factory=set, init=False)
    costs: dict[int, float] = field(default_factory=dict, init=False)

    def adjust(self, closed: list[int], opened: list[int], costs: dict[int, float]) -> None:
        """Nav2's ``adjust_edges``: close, then reopen, then set costs."""
        self.closed.update(closed)
        self.closed.difference_update(opened)
        self.costs.update(costs)

    def prepare(self) -> None:
        return None

    def score(self, edge: GraphEdge, request: RouteRequest, edge_type: EdgeType) -> float | None:
        if edge.edgeid in self.closed:
            return None
        return self.costs.get(edge.edgeid, 0.0)


SCORERS: dict[str, type[Scorer]] = {
    "DistanceScorer": DistanceScorer,
    "PenaltyScorer": PenaltyScorer,
    "CostmapScorer": CostmapScorer,
    "DynamicEdgesScorer": DynamicEdgesScorer,
    "TimeScorer": TimeScorer,
    "SemanticScorer": SemanticScorer,
    "StartPoseOrientationScorer": StartPoseOrientationScorer,
    "GoalOrientationScorer": GoalOrientationScorer,
}
"""The edge scorers by Nav2's plugin ids (:func:`.plugins.make_plugin` builds them)."""
DEFAULT_SCORERS = ("DistanceScorer", "CostmapScorer")  # nav2_bringup's nav2_params.yaml


class EdgeScorer:
    """The sum of ``scorers`` (Nav2's ``EdgeScorer``); ``None`` if one closes the edge."""

    def __init__(self, scorers: Sequence[Scorer]) -> None:
        self.scorers = tuple(scorers)

    def __len__(self) -> int:
        return len(self.scorers)

    def prepare(self) -> None:
        for scorer in self.scorers:
            scorer.prepare()

    def score(self, edge: GraphEdge, request: RouteRequest, edge_type: EdgeType) -> float | None:
        total = 0.0
        for scorer in self.scorers:
            cost = scorer.score(edge, request, edge_type)
            if cost is None:
                return None
            total += cost
        return total
