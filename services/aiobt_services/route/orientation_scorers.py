"""Nav2's edge scorers on the request's poses: ``StartPoseOrientationScorer`` (the first
edge against the start pose's heading) and ``GoalOrientationScorer`` (the last edge
against the goal pose's).

Each scores ``orientation_weight`` times the angle between its edge's direction and
the pose's heading; with ``use_orientation_threshold``, an edge whose angle is over
``orientation_tolerance`` is closed. Other edges score 0. A request without poses (by
node ids) cannot be scored by them: INVALID_EDGE_SCORER_USE, as in Nav2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from aiobt.geometry import wrap_angle

from .errors import RouteError
from .graph import GraphEdge
from .request import EdgeType, RouteRequest


def _heading_error(edge: GraphEdge, heading: float) -> float:
    direction = math.atan2(edge.end.y - edge.start.y, edge.end.x - edge.start.x)
    return abs(wrap_angle(heading - direction))


def _score(scorer: _Orientation, edge: GraphEdge, heading: float) -> float | None:
    error = _heading_error(edge, heading)
    if scorer.use_orientation_threshold and error > scorer.orientation_tolerance:
        return None
    return scorer.orientation_weight * error


@dataclass(slots=True)
class _Orientation:
    orientation_tolerance: float = math.pi / 2.0
    orientation_weight: float = 1.0
    use_orientation_threshold: bool = False

    def prepare(self) -> None:
        return None


@dataclass(slots=True)
class StartPoseOrientationScorer(_Orientation):
    """An edge leaving the start node, against the start pose's heading."""

    def score(self, edge: GraphEdge, request: RouteRequest, edge_type: EdgeType) -> float | None:
        if not request.use_poses:
            raise RouteError("INVALID_EDGE_SCORER_USE", "StartPoseOrientationScorer needs "
                             "a start pose: the request is by node ids")  # fmt: skip
        return _score(self, edge, request.start_yaw) if edge_type == "START" else 0.0


@dataclass(slots=True)
class GoalOrientationScorer(_Orientation):
    """An edge reaching the goal node, against the goal pose's heading."""

    def score(self, edge: GraphEdge, request: RouteRequest, edge_type: EdgeType) -> float | None:
        if not request.use_poses:
            raise RouteError("INVALID_EDGE_SCORER_USE", "GoalOrientationScorer needs a goal "
                             "pose: the request is by node ids")  # fmt: skip
        return _score(self, edge, request.goal_yaw) if edge_type == "END" else 0.0
