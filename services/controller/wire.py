"""Wire shape of the tracking feedback (Nav2's ``nav2_msgs/TrackingFeedback``).

Published on ``{ns}/tracking_feedback`` for IsWithinPathTrackingBounds.
TODO(msgs owner): move into ``aiobt.msgs`` so all wire models live in one place.
"""

from __future__ import annotations

from pydantic import Field

from aiobt.msgs import Header, Msg, Point

from .tracking import TrackingFeedback


class TrackingFeedbackMsg(Msg):
    header: Header = Field(default_factory=lambda: Header(frame_id="map"))
    current_path_index: int = Field(default=0, ge=0)
    cross_track_error: float = Field(default=0.0, description="m, > 0: robot left of the path")
    heading_error: float = Field(default=0.0, description="rad, robot yaw - path tangent")
    distance_to_goal: float = Field(default=0.0, ge=0.0)
    remaining_path_length: float = Field(default=0.0, ge=0.0)
    robot_position: Point = Field(default_factory=Point)

    @classmethod
    def of(cls, fb: TrackingFeedback, stamp: float, frame_id: str = "map") -> TrackingFeedbackMsg:
        return cls(
            header=Header(stamp=max(0.0, stamp), frame_id=frame_id),
            current_path_index=fb.current_path_index,
            cross_track_error=fb.cross_track_error,
            heading_error=fb.heading_error,
            distance_to_goal=fb.distance_to_goal,
            remaining_path_length=fb.remaining_path_length,
            robot_position=Point(x=fb.position[0], y=fb.position[1]),
        )
