"""A ``tracked_frame`` goal (Nav2's ``FollowingServer::getFramePose``): the object is a
TF frame, published as a transform on ``{ns}/tf`` (``TFMessage``, as localization
publishes ``map`` -> ``odom``) by whatever tracks it: a person tracker, another
robot's localization. Nav2 looks the frame up in the TF tree; aiobt has no TF tree, so
:class:`TransformTree` keeps the newest transform per child frame from ``{ns}/tf`` and
walks from the tracked frame up its parents to the first frame the server's
:class:`~.frames.RobotFrames` knows (``base_link`` and the robot's own frames,
``odom``, ``map``), which puts it in the fixed frame as it puts a detection.

Planar: each transform's x, y and yaw. A chain's stamp is its oldest link's, so a
stale link makes a stale pose (lost after ``detection_timeout``, as a detection).
"""

from __future__ import annotations

from collections.abc import Callable

from aiobt.geometry import Pose2D
from aiobt.geometry.pose_filter import StampedPose
from aiobt.msgs import TFMessage

MAX_DEPTH = 32  # links walked before a chain counts as a loop


class TransformTree:
    """``add(msg)`` as ``{ns}/tf`` arrives; :meth:`pose_of` a frame in a known one."""

    def __init__(self, known: Callable[[str], bool]) -> None:
        self.known = known  # a frame the robot's frames can put in the fixed frame
        self._links: dict[str, tuple[str, Pose2D, float]] = {}  # child: parent, pose, stamp

    def add(self, msg: TFMessage) -> None:
        for t in msg.transforms:
            if t.child_frame_id and t.header.frame_id:
                x, y = t.transform.translation.x, t.transform.translation.y
                self._links[t.child_frame_id] = (t.header.frame_id, Pose2D(x, y, t.yaw),
                                                 t.header.stamp)  # fmt: skip

    def pose_of(self, frame: str) -> StampedPose:
        """``frame``'s pose in the first known frame up its chain; LookupError naming
        the missing link when none leads there."""
        pose, stamp, at = Pose2D(), float("inf"), frame
        for _ in range(MAX_DEPTH):
            if self.known(at):
                return StampedPose(pose, stamp, at)
            link = self._links.get(at)
            if link is None:
                whose = "" if at == frame else f" (a parent of '{frame}')"
                raise LookupError(f"no transform to frame '{at}'{whose} on tf, and it is not "
                                  "one of the robot's frames, odom or map")  # fmt: skip
            parent, to_child, link_stamp = link
            pose, stamp, at = to_child.compose(pose), min(stamp, link_stamp), parent
        raise LookupError(f"frame '{frame}': no known frame within {MAX_DEPTH} links (a loop?)")


class FrameDetections:
    """The tracked frame as a :class:`~.tracking.Detections`: its newest pose, or None
    while its chain is incomplete (``why`` says what is missing, in :attr:`topic`)."""

    def __init__(self, tree: TransformTree, frame: str, key: str) -> None:
        self.tree = tree
        self.frame = frame
        self.key = key  # {ns}/tf
        self.why = ""

    @property
    def topic(self) -> str:
        why = f": {self.why}" if self.why else ""
        return f"{self.key} (tracked_frame '{self.frame}'{why})"

    def latest(self) -> StampedPose | None:
        try:
            found = self.tree.pose_of(self.frame)
        except LookupError as exc:
            self.why = str(exc)
            return None
        self.why = ""
        return found
