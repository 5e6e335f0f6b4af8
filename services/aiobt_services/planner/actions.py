"""The planner's action executes: plan, plan through poses, smooth, coverage.

Searches run in a worker thread on a snapshot of the costmap, so the event
loop (and every other goal's cancellation) stays responsive; cancelling a
goal sets the search's cancel flag, which the Python searches check every
~1000 expansions and the compiled Dijkstra (GridBased's default) before and
after its one uninterruptible call (~6 ms on the default world; it holds the
GIL meanwhile, so the loop stalls that long).
Every failure becomes a result with Nav2's error code and a message.
"""

from __future__ import annotations

import asyncio
import logging
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from enum import IntEnum
from typing import Any, TypeVar

from aiobt.geometry import XYYaw
from aiobt.msgs import (
    ComputeCoveragePath,
    ComputePathThroughPoses,
    ComputePathToPose,
    Path,
    PoseStamped,
    SmoothPath,
    pose_fields,
)

from .base import Smoother
from .coverage import CoverageError, CoverageParams, plan_coverage
from .errors import PlanningCancelled, PlanningError
from .planning import plan_through
from .smoother import SimpleSmoother, in_collision
from .state import MAP_FRAMES, GlobalCostmap
from .traversal import Budget

log = logging.getLogger("aiobt_services.planner.actions")
_SIMPLE = SimpleSmoother()
SMOOTHERS: dict[str, Smoother] = {
    "": _SIMPLE, "simple_smoother": _SIMPLE, "route_smoother": _SIMPLE, "SmoothPath": _SIMPLE
}  # fmt: skip
"""Smoother plugins by Nav2's ids ("" the default; ``SmoothPath`` is the id Nav2's trees use,
``route_smoother`` nav2_params.yaml's for the route server's paths)."""
T = TypeVar("T")
TALLY_EVERY = 50  # plans between two log lines of searches run and reused


@dataclass(frozen=True, slots=True)
class ActionOptions:
    max_planning_time: float = 2.0
    coverage: CoverageParams = field(default_factory=CoverageParams)


async def run_cancellable(work: Callable[[Budget], T], budget: Budget) -> T:
    """Run ``work(budget)`` in a thread; a cancelled caller cancels the work."""
    try:
        return await asyncio.to_thread(work, budget)
    except asyncio.CancelledError:
        budget.cancel.set()
        raise


def to_path(poses: Sequence[XYYaw], stamp: float) -> Path:
    """The path in ``map``, validated as one nested dict: half the CPU of building each
    pose's five models one by one (a few ms for a long path), the same message."""
    header = {"stamp": stamp, "frame_id": "map"}
    return Path.model_validate(
        {
            "header": header,
            "poses": [{"header": header, "pose": pose_fields(x, y, yaw)} for x, y, yaw in poses],
        }
    )


def pose_of(msg: PoseStamped, which: str) -> XYYaw:
    if msg.header.frame_id not in MAP_FRAMES:
        raise PlanningError(
            "TF_ERROR", f"{which} is in frame '{msg.header.frame_id}'; the planner plans in 'map'"
        )
    return (msg.x, msg.y, msg.yaw)


class PlannerActions:
    """Action executes bound to a :class:`GlobalCostmap`."""

    def __init__(self, world: GlobalCostmap, options: ActionOptions | None = None) -> None:
        self.world = world
        self.options = options or ActionOptions()
        self.tally = [0, 0, 0]  # plans, searches, searches served by a kept one

    def _count(self, budget: Budget) -> None:
        tally = self.tally
        tally[0] += 1
        tally[1] += budget.searched
        tally[2] += budget.reused
        if tally[0] % TALLY_EVERY == 0:
            log.info("%d plans: %d searches, %d of them served by a kept search (same goal, "
                     "costmap unchanged)", *tally)  # fmt: skip

    async def _plan(
        self, table: type[IntEnum], result: Any, start: XYYaw | None, goals: list[XYYaw],
        planner_id: str,
    ) -> Any:  # fmt: skip
        began = time.monotonic()
        try:
            traversal = self.world.traversal()
            if traversal is None:
                raise PlanningError("UNKNOWN", "no map received yet on {ns}/map")
            origin = start if start is not None else self._robot_pose()
            budget = Budget(self.options.max_planning_time)
            poses = await run_cancellable(
                lambda b: plan_through(traversal, origin, goals, planner_id, b), budget
            )
            self._count(budget)
        except PlanningError as exc:
            return result(error_code=int(table[exc.reason]), error_msg=exc.message)
        except PlanningCancelled:  # the goal is being cancelled: not an error
            raise asyncio.CancelledError from None
        except Exception as exc:  # never let a bad goal take the server down
            log.exception("planning failed unexpectedly")
            return result(error_code=int(table["UNKNOWN"]), error_msg=f"planner error: {exc}")
        path = to_path(poses, self.world.pose_stamp)
        return result(path=path, planning_time=time.monotonic() - began)

    def _robot_pose(self) -> XYYaw:
        try:
            return self.world.require_pose()
        except LookupError as exc:
            raise PlanningError("TF_ERROR", str(exc)) from None

    async def compute_path_to_pose(
        self, goal: ComputePathToPose.Goal, _handle: object
    ) -> ComputePathToPose.Result:
        table, result = ComputePathToPose.ErrorCode, ComputePathToPose.Result
        try:
            start = pose_of(goal.start, "start") if goal.use_start else None
            targets = [pose_of(v, f"viapoint {i}") for i, v in enumerate(goal.viapoints)]
            targets.append(pose_of(goal.goal, "goal"))
        except PlanningError as exc:
            return result(error_code=int(table[exc.reason]), error_msg=exc.message)
        out: ComputePathToPose.Result = await self._plan(
            table, result, start, targets, goal.planner_id
        )
        return out

    async def compute_path_through_poses(
        self, goal: ComputePathThroughPoses.Goal, _handle: object
    ) -> ComputePathThroughPoses.Result:
        table, result = ComputePathThroughPoses.ErrorCode, ComputePathThroughPoses.Result
        try:
            start = pose_of(goal.start, "start") if goal.use_start else None
            targets = [pose_of(g, f"goal {i}") for i, g in enumerate(goal.goals.goals)]
        except PlanningError as exc:
            return result(error_code=int(table[exc.reason]), error_msg=exc.message)
        out: ComputePathThroughPoses.Result = await self._plan(
            table, result, start, targets, goal.planner_id
        )
        return out

    async def smooth_path(self, goal: SmoothPath.Goal, _handle: object) -> SmoothPath.Result:
        codes, result = SmoothPath.ErrorCode, SmoothPath.Result
        smoother = SMOOTHERS.get(goal.smoother_id)
        if smoother is None:
            known = ", ".join(s for s in SMOOTHERS if s)
            msg = f"unknown smoother id '{goal.smoother_id}' (known: {known})"
            return result(error_code=codes.INVALID_SMOOTHER, error_msg=msg)
        if not goal.path.poses:
            return result(error_code=codes.INVALID_PATH, error_msg="the path to smooth is empty")
        if goal.path.header.frame_id not in MAP_FRAMES:
            msg = f"path is in frame '{goal.path.header.frame_id}'; the smoother works in 'map'"
            return result(error_code=codes.INVALID_PATH, error_msg=msg)
        grid = self.world.snapshot()
        if grid is None:
            return result(error_code=codes.UNKNOWN, error_msg="no map received yet on {ns}/map")
        poses = [(p.x, p.y, p.yaw) for p in goal.path.poses]
        began = time.monotonic()
        budget = Budget(goal.max_smoothing_duration)
        done = await run_cancellable(
            lambda _b: smoother.smooth(grid, poses, goal.max_smoothing_duration), budget
        )
        elapsed = time.monotonic() - began
        path = to_path(done.poses, goal.path.header.stamp)
        if done.timed_out:
            msg = f"smoothing exceeded max_smoothing_duration {goal.max_smoothing_duration} s"
            return result(error_code=codes.TIMEOUT, error_msg=msg, path=path)
        if goal.check_for_collisions and (hits := in_collision(grid, done.poses)):
            msg = f"smoothed path is in collision at pose index {hits[0]}"
            return result(error_code=codes.SMOOTHED_PATH_IN_COLLISION, error_msg=msg)
        return result(path=path, smoothing_duration=elapsed, was_completed=done.completed)

    async def compute_coverage_path(
        self, goal: ComputeCoveragePath.Goal, _handle: object
    ) -> ComputeCoveragePath.Result:
        codes, result = ComputeCoveragePath.ErrorCode, ComputeCoveragePath.Result
        began = time.monotonic()
        if goal.use_gml_file:
            msg = "GML field files are not supported; give the field as polygons"
            return result(error_code=codes.INVALID_REQUEST, error_msg=msg)
        if goal.frame_id not in MAP_FRAMES:
            msg = f"field is in frame '{goal.frame_id}'; coverage is planned in 'map'"
            return result(error_code=codes.INVALID_COORDS, error_msg=msg)
        params = self.options.coverage
        if not goal.generate_headland:
            params = CoverageParams(params.row_spacing, 0.0, params.spacing)
        polygons = [[(p.x, p.y) for p in polygon] for polygon in goal.polygons]
        try:
            coverage = plan_coverage(polygons, params)
        except CoverageError as exc:
            return result(error_code=int(codes[exc.reason]), error_msg=str(exc))
        stamp = self.world.pose_stamp
        ends = [(x, y, 0.0) for swath in coverage.swaths for (x, y) in swath]
        return result(
            nav_path=to_path(coverage.path, stamp),
            coverage_path=to_path(_headed(ends), stamp),
            planning_time=time.monotonic() - began,
        )


def _headed(points: list[XYYaw]) -> list[XYYaw]:
    """Each point faces the next (the last keeps the previous heading)."""
    out: list[XYYaw] = []
    for (x, y, _), (nx, ny, _) in zip(points, [*points[1:], points[-1]], strict=True):
        same = math.isclose(x, nx) and math.isclose(y, ny)
        yaw = (out[-1][2] if out else 0.0) if same else math.atan2(ny - y, nx - x)
        out.append((x, y, yaw))
    return out
