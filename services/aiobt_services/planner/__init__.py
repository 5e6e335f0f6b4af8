"""The planner service: global costmap, GridBased / ThetaStar planners, smoother,
path validity and coverage (pure logic here; Zenoh only in ``main`` and ``service``)."""

from .coverage import Coverage, CoverageError, CoverageParams, plan_coverage
from .errors import PlanningCancelled, PlanningError
from .planning import PLANNERS, path_length, plan, plan_through
from .smoother import SmootherParams, SmoothResult, in_collision, smooth
from .traversal import Budget, SearchParams, Traversal
from .validity import invalid_poses

__all__ = [
    "PLANNERS",
    "Budget",
    "Coverage",
    "CoverageError",
    "CoverageParams",
    "PlanningCancelled",
    "PlanningError",
    "SearchParams",
    "SmoothResult",
    "SmootherParams",
    "Traversal",
    "in_collision",
    "invalid_poses",
    "path_length",
    "plan",
    "plan_coverage",
    "plan_through",
    "smooth",
]
