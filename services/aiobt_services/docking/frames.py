"""The robot's frames as the docking server sees them, from what the other services
read: the pose in ``map`` (``{ns}/pose``: localization's, or the robot's stand-in)
and the wheel odometry (``{ns}/odom``: the pose in ``odom``, smooth, drifting).

Nav2 runs its docking control loop in ``fixed_frame`` (``odom``): detections of the
dock, taken in ``base_link``, go into ``odom`` with the odometry at their stamp; the
dock database's poses (``map``) go into ``odom`` through ``map -> odom``, the newest
map pose composed with the inverse of the newest odometry.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from aiobt.geometry import Pose2D
from aiobt.msgs import Odometry, PoseStamped

MAP_FRAMES = ("map", "")
FRAMES = ("map", "odom", "base_link")
ODOM_MATCH = 0.1  # s: an odometry this far from a detection's stamp is too far to use


def _pose2d(pose: PoseStamped | Odometry) -> Pose2D:
    return Pose2D(pose.pose.position.x, pose.pose.position.y, pose.pose.orientation.yaw)


class RobotFrames:
    """``map``, ``odom`` and ``base_link`` from the newest pose and odometry messages;
    a missing one is a LookupError naming what is missing (Nav2's transform error)."""

    def __init__(
        self,
        pose: Callable[[], PoseStamped | None],
        odometry: Callable[[], Iterable[Odometry]],
    ) -> None:
        self._pose = pose
        self._odometry = odometry  # newest first

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
