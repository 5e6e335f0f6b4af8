"""The robot's frames as the docking server sees them, from what the other services
read: the pose in ``map`` (``{ns}/pose``: localization's, or the robot's stand-in)
and the wheel odometry (``{ns}/odom``: the pose in ``odom``, smooth, drifting).

Nav2 runs its docking control loop in ``fixed_frame`` (``odom``): detections of the
dock, taken in ``base_link``, go into ``odom`` with the odometry at their stamp; the
dock database's poses (``map``) go into ``odom`` through ``map -> odom``, the newest
map pose composed with the inverse of the newest odometry. Any other frame (a camera's
that a detection is given in, a dock's) reaches one of those through the static
transforms of ``{ns}/tf_static`` (:class:`~aiobt.geometry.static_frames.StaticFrames`),
as Nav2's tf2 buffer finds it; a detection in 3D, a pose planar (x, y, yaw of its chain).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from aiobt.geometry import Pose2D
from aiobt.geometry.pose_filter import StampedPose3D
from aiobt.geometry.static_frames import StaticFrames
from aiobt.msgs import Odometry, PoseStamped

MAP_FRAMES = ("map", "")
FRAMES = ("map", "odom", "base_link")
ODOM_MATCH = 0.1  # s: an odometry this far from a detection's stamp is too far to use


def _pose2d(pose: PoseStamped | Odometry) -> Pose2D:
    return Pose2D(pose.pose.position.x, pose.pose.position.y, pose.pose.orientation.yaw)


class RobotFrames:
    """``map``, ``odom`` and ``base_link`` from the newest pose and odometry messages,
    other frames through ``statics``; a missing one is a LookupError naming what is
    missing (Nav2's transform error)."""

    def __init__(
        self,
        pose: Callable[[], PoseStamped | None],
        odometry: Callable[[], Iterable[Odometry]],
        statics: StaticFrames | None = None,
    ) -> None:
        self._pose = pose
        self._odometry = odometry  # newest first
        self.statics = statics or StaticFrames()

    @staticmethod
    def knows(frame: str) -> bool:
        return frame in FRAMES or frame in MAP_FRAMES

    def lift(self, seen: StampedPose3D) -> StampedPose3D:
        """A detection in any frame, in the first of ``map``, ``odom``, ``base_link`` up
        its static chain."""
        try:
            return self.statics.lift(seen, self.knows)
        except LookupError as exc:
            raise LookupError(f"{exc}, and it is none of {', '.join(FRAMES)}") from None

    def _known(self, pose: Pose2D, frame: str) -> tuple[Pose2D, str]:
        """``pose`` in ``frame`` as a pose in a known frame, through the static chain."""
        if self.knows(frame):
            return pose, frame
        try:
            known, link = self.statics.up_to(frame, self.knows)
        except LookupError as exc:
            raise LookupError(f"{exc}, and it is none of {', '.join(FRAMES)}") from None
        return link.planar().compose(pose), known

    def _odom(self, stamp: float | None = None) -> Pose2D:
        odoms = iter(self._odometry())
        newest = next(odoms, None)
        if newest is None:
            raise LookupError("no odometry yet on {ns}/odom")
        if stamp is None or newest.header.stamp <= stamp:
            return _pose2d(newest)
        best = min((newest, *odoms), key=lambda o: abs(o.header.stamp - stamp))
        if abs(best.header.stamp - stamp) > ODOM_MATCH:
            raise LookupError(f"no odometry near the stamp {stamp:.3f} s")
        return _pose2d(best)

    def _map(self) -> Pose2D:
        pose = self._pose()
        if pose is None:
            raise LookupError("no robot pose yet on {ns}/pose")
        return _pose2d(pose)

    def robot(self, frame: str) -> Pose2D:
        """The robot (``base_link``) in ``frame``."""
        if not self.knows(frame):
            in_frame, known = self._known(Pose2D(), frame)  # frame's origin in a known one
            return in_frame.inverse().compose(self.robot(known))
        if frame in MAP_FRAMES:
            return self._map()
        if frame == "odom":
            return self._odom()
        if frame == "base_link":
            return Pose2D()
        raise LookupError(f"unknown frame '{frame}' (known: {', '.join(FRAMES)})")

    def transform(self, pose: Pose2D, source: str, target: str,
                  stamp: float | None = None) -> Pose2D:  # fmt: skip
        """``pose`` given in ``source`` expressed in ``target``; a ``base_link`` pose is
        placed with the odometry nearest ``stamp`` (default: the newest)."""
        pose, source = self._known(pose, source)
        if not self.knows(target):
            origin, known = self._known(Pose2D(), target)
            return origin.inverse().compose(self.transform(pose, source, known, stamp))
        if source == target or (source in MAP_FRAMES and target in MAP_FRAMES):
            return pose
        in_odom = self._to_odom(pose, source, stamp)
        if target == "odom":
            return in_odom
        if target == "base_link":
            return self._odom().inverse().compose(in_odom)
        if target in MAP_FRAMES:
            return self._map_from_odom().compose(in_odom)
        raise LookupError(f"unknown frame '{target}' (known: {', '.join(FRAMES)})")

    def _to_odom(self, pose: Pose2D, source: str, stamp: float | None) -> Pose2D:
        if source == "odom":
            return pose
        if source == "base_link":
            return self._odom(stamp).compose(pose)
        if source in MAP_FRAMES:
            return self._map_from_odom().inverse().compose(pose)
        raise LookupError(f"unknown frame '{source}' (known: {', '.join(FRAMES)})")

    def _map_from_odom(self) -> Pose2D:
        return self._map().compose(self._odom().inverse())
