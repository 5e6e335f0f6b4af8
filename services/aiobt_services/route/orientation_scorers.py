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
from typing import ClassVar

from aiobt.geometry import wrap_angle

from .errors import RouteError
from .graph import GraphEdge
from .request import EdgeType, RouteRequest


def _heading_error(edge: GraphEdge, heading: float) -> float:
    direction = math.atan2(edge.end.y - edge.start.y, edge.end.x - edge.start.x)
    return abs(wrap_angle(heading - direction))


@dataclass(slots=True)
class _Orientation:
    EDGE: ClassVar[EdgeType]  # the edges it scores; the pose it scores them against

    orientation_tolerance: float = math.pi / 2.0
    orientation_weight: float = 1.0
    use_orientation_threshold: bool = False

    def prepare(self) -> None:
        return None

    def score(self, edge: GraphEdge, request: RouteRequest, edge_type: EdgeType) -> float | None:
        pose = "start" if self.EDGE == "START" else "goal"
        if not request.use_poses:
            raise RouteError("INVALID_EDGE_SCORER_USE", f"{type(self).__name__} needs a {pose} "
                             "pose: the request is by node ids")  # fmt: skip
        if edge_type != self.EDGE:
            return 0.0
        error = _heading_error(edge, request.start_yaw if pose == "start" else request.goal_yaw)
        if self.use_orientation_threshold and error > self.orientation_tolerance:
            return None
        return self.orientation_weight * error


@dataclass(slots=True)
class StartPoseOrientationScorer(_Orientation):
    """An edge leaving the start node, against the start pose's heading."""

    EDGE: ClassVar[EdgeType] = "START"


@dataclass(slots=True)
class GoalOrientationScorer(_Orientation):
    """An edge reaching the goal node, against the goal pose's heading."""

    EDGE: ClassVar[EdgeType] = "END"
