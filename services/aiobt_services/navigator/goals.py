"""What a navigation asks for, and the checks a goal passes before its tree runs."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from aiobt.msgs import Goals, OccupancyGrid, PoseStamped, WaypointStatus

NAVIGATE_TO_POSE = "navigate_to_pose"
NAVIGATE_THROUGH_POSES = "navigate_through_poses"
GLOBAL_FRAME = "map"


@dataclass(frozen=True, slots=True)
class NavRequest:
    """One goal of either action: its poses (one for navigate_to_pose) and its tree.

    ``behavior_tree`` is what the goal gave (empty: the action's default tree).
    """

    action: str
    goal_id: str
    poses: tuple[PoseStamped, ...]
    behavior_tree: str = ""

    @property
    def through_poses(self) -> bool:
        return self.action == NAVIGATE_THROUGH_POSES

    def blackboard_entries(self) -> dict[str, object]:
        """The blackboard entries Nav2's navigator sets for this goal: ``goal``; or
        ``goals`` and ``waypoint_statuses`` (one PENDING status per pose)."""
        if not self.through_poses:
            return {"goal": self.poses[0]}
        statuses = [
            WaypointStatus(waypoint_index=index, waypoint_pose=pose)
            for index, pose in enumerate(self.poses)
        ]
        return {"goals": Goals(goals=list(self.poses)), "waypoint_statuses": statuses}


@dataclass(frozen=True, slots=True)
class MapBounds:
    """The rectangle the map covers, in the map frame."""

    min_x: float
    min_y: float
    max_x: float
    max_y: float

    @classmethod
    def of(cls, grid: OccupancyGrid) -> MapBounds:
        info = grid.info
        x0, y0 = info.origin.position.x, info.origin.position.y
        return cls(x0, y0, x0 + info.width * info.resolution, y0 + info.height * info.resolution)

    def contains(self, x: float, y: float) -> bool:
        return self.min_x <= x < self.max_x and self.min_y <= y < self.max_y

    def __str__(self) -> str:
        return f"x [{self.min_x:g}, {self.max_x:g}), y [{self.min_y:g}, {self.max_y:g})"


@dataclass(frozen=True, slots=True)
class PoseProblem:
    """Why goal poses cannot be navigated to; ``outside_map``: the planner's GOAL_OUTSIDE_MAP."""

    message: str
    outside_map: bool = False


def pose_problem(poses: Sequence[PoseStamped], bounds: MapBounds | None) -> PoseProblem | None:
    """Why these goal poses cannot be navigated to (naming the pose), or None.

    Frames other than ``map`` are refused (aiobt has no TF); a pose outside
    ``bounds`` (the robot's map, when one was received) is refused. NaN never
    gets here: the message models refuse it.
    """
    if not poses:
        return PoseProblem("the goal has no poses")
    for index, pose in enumerate(poses):
        where = f"pose {index}" if len(poses) > 1 else "the goal pose"
        frame = pose.header.frame_id
        if frame not in ("", GLOBAL_FRAME):
            return PoseProblem(f"{where} is in frame {frame!r}; only {GLOBAL_FRAME!r} is supported")
        x, y = pose.pose.position.x, pose.pose.position.y
        if bounds is not None and not bounds.contains(x, y):
            return PoseProblem(f"{where} ({x:g}, {y:g}) is outside the map ({bounds})", True)
    return None
