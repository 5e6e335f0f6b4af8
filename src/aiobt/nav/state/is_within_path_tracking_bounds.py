"""IsWithinPathTrackingBounds (Nav2): is the controller tracking its path closely?"""

from __future__ import annotations

import logging
from typing import Any

from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import input_port
from aiobt.msgs import TrackingFeedback
from aiobt.nav.robot_state import TRACKING, RobotStateNode

log = logging.getLogger("aiobt.nav.is_within_path_tracking_bounds")


class IsWithinPathTrackingBounds(RobotStateNode, ConditionNode):
    """``<IsWithinPathTrackingBounds max_error_left="0.5" max_error_right="0.5"
    max_error_heading="3.14" tracking_feedback="{tracking_feedback}"/>`` (Nav2).

    SUCCESS when the cross-track error is within ``max_error_left`` (positive:
    robot left of the path) or ``max_error_right`` (negative) and the heading
    error within ``max_error_heading``; FAILURE otherwise (warned at most once
    a second of robot time). The feedback is the port's, else the last one
    the controller published on ``{ns}/tracking_feedback``; with none: SUCCESS,
    as Nav2. Negative bounds are used as their absolute value.
    """

    READS = (TRACKING,)
    PORTS = (
        input_port("max_error_left", float, 0.5, "Max tracking error (m) left of the path."),
        input_port("max_error_right", float, 0.5, "Max tracking error (m) right of the path."),
        input_port("max_error_heading", float, 3.14, "Max heading error (rad)."),
        input_port(
            "tracking_feedback",
            TrackingFeedback,
            description="The controller's tracking feedback, with the current tracking error.",
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._warned_at = float("-inf")

    def _feedback(self) -> TrackingFeedback | None:
        feedback: TrackingFeedback | None = self.get_input("tracking_feedback", None)
        if feedback is None and self.nav.bus is not None:
            feedback = self.robot.tracking_feedback
        return feedback

    def check(self) -> bool:
        feedback = self._feedback()
        if feedback is None:
            return True
        error, heading = feedback.cross_track_error, feedback.heading_error
        side = "max_error_left" if error >= 0.0 else "max_error_right"
        bound = abs(float(self.get_input(side)))
        within = abs(error) <= bound
        within = within and abs(heading) <= abs(float(self.get_input("max_error_heading")))
        if not within:
            self._warn(error, heading)
        return within

    def _warn(self, error: float, heading: float) -> None:
        now = self.clock.now()
        if now - self._warned_at >= 1.0:
            self._warned_at = now
            log.warning(
                "%s: robot out of path tracking bounds: position error %.2f m, heading %.2f rad",
                self.path,
                error,
                heading,
            )
