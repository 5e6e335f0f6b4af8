"""Why a plan failed, in Nav2's vocabulary (names shared by the planner tables)."""

from __future__ import annotations

# Nav2 error-code names shared by ComputePathToPose and ComputePathThroughPoses:
# UNKNOWN, INVALID_PLANNER, TF_ERROR, START_OUTSIDE_MAP, GOAL_OUTSIDE_MAP,
# START_OCCUPIED, GOAL_OCCUPIED, TIMEOUT, NO_VALID_PATH, NO_VIAPOINTS_GIVEN.
Reason = str


class PlanningError(Exception):
    """A plan that cannot be made; ``reason`` is the Nav2 error-code name."""

    def __init__(self, reason: Reason, message: str) -> None:
        super().__init__(message)
        self.reason: Reason = reason
        self.message = message


class PlanningCancelled(Exception):
    """The caller cancelled the search (not an error: the goal is cancelled)."""
