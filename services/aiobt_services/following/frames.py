"""The robot's poses as the server reads them, and the frames a detection may come in.

:class:`RobotFrames` keeps a short history of the robot's pose per frame (``odom``
from ``{odom_topic}``, ``map`` from ``{ns}/pose``, as the other services read them)
and the newest measured turn rate. A pose given in one of those frames, or in the robot's
own frame (``base_frame``, ``base_scan``: a tracker on the robot), is put in the
fixed frame with the robot's poses at its stamp, within ``transform_tolerance``:
what TF does for Nav2's server.
"""

from __future__ import annotations

import bisect
from collections import deque
from collections.abc import Callable

from aiobt.geometry import Pose2D
from aiobt.geometry.pose_filter import StampedPose

from .errors import TransformError

ROBOT_FRAMES = ("base_link", "base_footprint", "base_scan")
HISTORY = 2.0  # s of poses kept per frame


class RobotFrames:
    """``add(frame, stamp, pose)`` as poses arrive; then look-ups and transforms."""

    __slots__ = ("_history", "base_frame", "refresh", "tolerance", "turn_rate")

    def __init__(
        self, base_frame: str, tolerance: float, refresh: Callable[[], None] = lambda: None
    ) -> None:
        self.base_frame = base_frame
        self.tolerance = tolerance
        self.refresh = refresh  # reads the poses that came meanwhile, before each look-up
        self._history: dict[str, deque[tuple[float, Pose2D]]] = {}
        self.turn_rate = 0.0  # the newest measured, rad/s

    def add(self, frame: str, stamp: float, pose: Pose2D) -> None:
        history = self._history.setdefault(frame, deque())
        if history and stamp < history[-1][0]:  # the robot restarted (sim time anew)
            history.clear()
        history.append((stamp, pose))
        while history and history[0][0] < stamp - HISTORY:
            history.popleft()

    def add_turn_rate(self, rate: float) -> None:
        """The odometry's measured turn rate (Nav2 turns from the raw twist)."""
        self.turn_rate = rate

    def is_robot_frame(self, frame: str) -> bool:
        return frame == self.base_frame or frame in ROBOT_FRAMES

    def knows(self, frame: str) -> bool:
        """A pose in ``frame`` can be put in the others: the robot's own frame, or one
        with robot poses (``odom``, ``map``)."""
        self.refresh()
        return self.is_robot_frame(frame) or frame in self._history

    def robot_in(self, frame: str, stamp: float | None = None) -> Pose2D:
        """The robot's pose in ``frame`` at ``stamp`` (None: the newest); TransformError
        when there is none within ``transform_tolerance``."""
        self.refresh()
        history = self._history.get(frame)
        if not history:
            known = ", ".join(sorted(self._history)) or "none yet"
            raise TransformError(f"no robot pose in frame '{frame}' (frames with poses: {known})")
        if stamp is None:
            return history[-1][1]
        stamps = [s for s, _ in history]
        i = bisect.bisect_left(stamps, stamp)
        near = min((j for j in (i - 1, i) if 0 <= j < len(stamps)),
                   key=lambda j: abs(stamps[j] - stamp))  # fmt: skip
        if abs(stamps[near] - stamp) > self.tolerance:
            raise TransformError(
                f"no robot pose in frame '{frame}' within {self.tolerance} s "
                f"(transform_tolerance) of {stamp:.3f} s: the nearest is at {stamps[near]:.3f} s"
            )
        return history[near][1]

    def to_frame(self, pose: StampedPose, frame: str) -> StampedPose:
        """``pose`` put in ``frame`` (a frame with robot poses) at its own stamp."""
        if pose.frame == frame:
            return pose
        robot = self.robot_in(frame, pose.stamp)
        if self.is_robot_frame(pose.frame):
            return StampedPose(robot.compose(pose.pose), pose.stamp, frame)
        if pose.frame not in self._history:
            robot_frames = ", ".join((self.base_frame, *self._history))
            raise TransformError(f"a pose in frame '{pose.frame}' cannot be put in '{frame}' "
                                 f"(frames known: {robot_frames})")  # fmt: skip
        there = self.robot_in(pose.frame, pose.stamp)
        moved = robot.compose(there.inverse()).compose(pose.pose)
        return StampedPose(moved, pose.stamp, frame)
