"""Tracking feedback on the wire: the controller's measure -> ``aiobt.msgs.TrackingFeedback``.

Published on ``{ns}/tracking_feedback`` for IsWithinPathTrackingBounds.
"""

from __future__ import annotations

from aiobt.msgs import Header, Point
from aiobt.msgs import TrackingFeedback as TrackingFeedbackMsg

from .tracking import TrackingFeedback

__all__ = ["TrackingFeedbackMsg", "tracking_feedback_msg"]


def tracking_feedback_msg(
    fb: TrackingFeedback, stamp: float, frame_id: str = "map"
) -> TrackingFeedbackMsg:
    return TrackingFeedbackMsg(
        header=Header(stamp=max(0.0, stamp), frame_id=frame_id),
        current_path_index=fb.current_path_index,
        cross_track_error=fb.cross_track_error,
        heading_error=fb.heading_error,
        distance_to_goal=fb.distance_to_goal,
        remaining_path_length=fb.remaining_path_length,
        robot_position=Point(x=fb.position[0], y=fb.position[1]),
    )
