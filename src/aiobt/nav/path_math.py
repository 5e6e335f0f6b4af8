"""Path arithmetic as Nav2's ``nav2_util::geometry_utils`` does it, vectorised.

Distances are planar (x, y), as Nav2's defaults. A :class:`PathGeometry` is
built once per path object (nodes keep it while the path stays the same).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from aiobt.msgs import Path, PoseStamped


def distance(a: PoseStamped, b: PoseStamped) -> float:
    """Planar distance between two poses."""
    pa, pb = a.pose.position, b.pose.position
    return math.hypot(pa.x - pb.x, pa.y - pb.y)


class PathGeometry:
    """The points of a list of poses, their segment lengths and the sums Nav2 uses."""

    __slots__ = ("_poses", "_quats", "segments", "xy")

    def __init__(self, poses: Sequence[PoseStamped]) -> None:
        self._poses = poses
        self._quats: npt.NDArray[np.float64] | None = None
        self.xy: npt.NDArray[np.float64] = np.array(
            [(p.pose.position.x, p.pose.position.y) for p in poses], dtype=np.float64
        ).reshape(-1, 2)
        self.segments: npt.NDArray[np.float64] = np.hypot(*np.diff(self.xy, axis=0).T)

    def __len__(self) -> int:
        return int(self.xy.shape[0])

    def length(self, start: int = 0) -> float:
        """Length from pose ``start`` to the end (Nav2's calculate_path_length)."""
        return float(self.segments[start:].sum()) if start + 1 < len(self) else 0.0

    def first_after(self, begin: int, limit: float) -> int:
        """Index of the first pose after ``begin`` beyond ``limit`` metres along the
        path, or ``len`` if none (Nav2's first_after_integrated_distance)."""
        if begin >= len(self):
            return len(self)
        walked = np.cumsum(self.segments[begin:])
        j = int(np.searchsorted(walked, limit, side="right"))
        return begin + j + 1 if j < walked.shape[0] else len(self)

    def first_before(self, end: int, limit: float) -> int:
        """Index of the first pose kept going back from ``end`` up to ``limit`` metres
        (Nav2's backward first_after_integrated_distance, as ``.base()``)."""
        walked = np.cumsum(self.segments[:end][::-1])
        j = int(np.searchsorted(walked, limit, side="right"))
        return end - j if j < walked.shape[0] else 0

    def closest(self, begin: int, end: int, pose: PoseStamped, angular_weight: float = 0.0) -> int:
        """Index in ``[begin, end)`` of the pose nearest ``pose``; the last of equals, as
        Nav2's min_by (``begin`` when the range is empty). ``angular_weight`` adds the
        weighted rotation between the orientations (TruncatePathLocal's distance)."""
        if end <= begin:
            return begin
        position = pose.pose.position
        d = np.hypot(self.xy[begin:end, 0] - position.x, self.xy[begin:end, 1] - position.y)
        if angular_weight:
            q = pose.pose.orientation
            dots = np.abs(self._quaternions()[begin:end] @ np.array([q.x, q.y, q.z, q.w]))
            angle = 2.0 * np.arccos(np.minimum(dots, 1.0))
            d = np.hypot(d, angular_weight * angle)
        return int(end - 1 - np.argmin(d[::-1]))

    def _quaternions(self) -> npt.NDArray[np.float64]:
        if self._quats is None:
            self._quats = np.array(
                [(o.x, o.y, o.z, o.w) for o in (p.pose.orientation for p in self._poses)],
                dtype=np.float64,
            ).reshape(-1, 4)
        return self._quats


class ClosestPoseSearch:
    """Where the robot is along a path, tick after tick (Nav2's IsGoalNearby and
    TruncatePathLocal): the search for the closest pose restarts at the path's start
    unless ``limit`` bounds it and the path is the same as on the previous call, in
    which case it continues from the previous closest pose and looks at most
    ``limit`` metres further."""

    __slots__ = ("_begin", "_path", "geometry")

    def __init__(self) -> None:
        self._path: Path | None = None
        self._begin = 0
        self.geometry = PathGeometry(())

    def closest(
        self, path: Path, pose: PoseStamped, limit: float, angular_weight: float = 0.0
    ) -> int:
        """Index of the pose of ``path`` closest to ``pose``; ``limit`` < infinity bounds
        the search (and makes it continue from the previous result)."""
        bounded = limit < math.inf
        if path is not self._path:
            if self._path is None or path != self._path:
                self._begin = 0
                self.geometry = PathGeometry(path.poses)
            self._path = path
        if not bounded:
            self._begin = 0
        end = self.geometry.first_after(self._begin, limit) if bounded else len(self.geometry)
        found = self.geometry.closest(self._begin, end, pose, angular_weight)
        if bounded:
            self._begin = found
        return found
