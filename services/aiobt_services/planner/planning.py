"""Plan a path between world poses with a named planner (pure logic, no Zenoh)."""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence

from aiobt.costmap import CostGrid
from aiobt.geometry import XYYaw

from .astar import astar
from .base import GlobalPlanner
from .dijkstra import compiled_dijkstra
from .errors import PlanningError
from .legs import path_points
from .theta import theta_star
from .traversal import Budget, SearchParams, Traversal


class GridBased:
    """Nav2's NavFn-class ``GridBased``: a cheapest cost-aware 8-connected path, by the
    compiled Dijkstra, or the CPython A* (same metric and optimum) when the traversal's
    ``params.use_astar`` is set."""

    def create_plan(
        self, traversal: Traversal, start: int, goal: int, budget: Budget | None = None
    ) -> list[int]:
        search = astar if traversal.params.use_astar else compiled_dijkstra
        return search(traversal, start, goal, budget)


class ThetaStar:
    """Nav2's ``ThetaStar``: an any-angle path (:mod:`.theta`)."""

    def create_plan(
        self, traversal: Traversal, start: int, goal: int, budget: Budget | None = None
    ) -> list[int]:
        return theta_star(traversal, start, goal, budget)


PLANNERS: dict[str, GlobalPlanner] = {"GridBased": GridBased(), "ThetaStar": ThetaStar()}
DEFAULT_PLANNER = "GridBased"


def check_pose(pose: XYYaw, which: str) -> None:
    """A pose with a non-finite field is outside any map."""
    if not all(math.isfinite(v) for v in pose):
        reason = "START_OUTSIDE_MAP" if which == "start" else "GOAL_OUTSIDE_MAP"
        raise PlanningError(reason, f"{which} pose {pose} is not finite")


def planner_for(planner_id: str) -> GlobalPlanner:
    planner = PLANNERS.get(planner_id or DEFAULT_PLANNER)
    if planner is None:
        known = ", ".join(sorted(PLANNERS))
        raise PlanningError(
            "INVALID_PLANNER", f"unknown planner id '{planner_id}' (known: {known})"
        )
    return planner


def plan(
    grid: CostGrid | Traversal,
    start: XYYaw,
    goal: XYYaw,
    planner_id: str = DEFAULT_PLANNER,
    budget: Budget | None = None,
    params: SearchParams | None = None,
) -> list[XYYaw]:
    """Poses from ``start`` to ``goal``: the exact start, cell centres, the exact goal.

    Intermediate poses face the next one; the last takes the goal's yaw.
    Raises :class:`PlanningError` with Nav2's reason, or PlanningCancelled.
    """
    return plan_through(grid, start, [goal], planner_id, budget, params)


def plan_through(
    grid: CostGrid | Traversal,
    start: XYYaw,
    goals: Sequence[XYYaw],
    planner_id: str = DEFAULT_PLANNER,
    budget: Budget | None = None,
    params: SearchParams | None = None,
) -> list[XYYaw]:
    """One path through every goal in order (ComputePathThroughPoses)."""
    planner = planner_for(planner_id)
    if not goals:
        raise PlanningError("NO_VIAPOINTS_GIVEN", "no goals given to plan through")
    check_pose(start, "start")
    for goal in goals:
        check_pose(goal, "goal")
    traversal = grid if isinstance(grid, Traversal) else Traversal(grid, params)
    budget = budget or Budget()
    points: list[tuple[float, float]] = [(start[0], start[1])]
    here, origin = traversal.locate(start[0], start[1], "start"), start
    for goal in goals:
        there = traversal.locate(goal[0], goal[1], "goal")
        leg = traversal.opened(origin[0], origin[1]).opened(goal[0], goal[1])
        cells = planner.create_plan(leg, here, there, budget)
        points.extend(path_points(leg, cells, (origin[0], origin[1]), (goal[0], goal[1]))[1:])
        here, origin = there, goal
    return _with_headings(_dedupe(points), goals[-1][2])


def _dedupe(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    out = [points[0]]
    for p in points[1:]:
        if math.hypot(p[0] - out[-1][0], p[1] - out[-1][1]) > 1e-9:
            out.append(p)
    return out


def _with_headings(points: list[tuple[float, float]], final_yaw: float) -> list[XYYaw]:
    poses: list[XYYaw] = []
    for i, (x, y) in enumerate(points[:-1]):
        nx, ny = points[i + 1]
        poses.append((x, y, math.atan2(ny - y, nx - x)))
    poses.append((points[-1][0], points[-1][1], final_yaw))
    return poses


def path_length(poses: Sequence[XYYaw]) -> float:
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in itertools.pairwise(poses))
