"""Feedback numbers as Nav2's navigators compute them: distance left along the
path from the closest segment, and the time left at the current speed."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from aiobt.msgs import Path, PoseStamped

SEARCH_WINDOW = 2.0  # m of path searched ahead of the last closest segment (Nav2's default)
MIN_SPEED = 0.01  # m/s; slower than this, no time estimate (Nav2)
MIN_DISTANCE = 0.1  # m; closer than this, no time estimate (Nav2)


def _points(path: Path) -> npt.NDArray[np.float64]:
    return np.array([(p.pose.position.x, p.pose.position.y) for p in path.poses], dtype=float)


@dataclass(slots=True)
class PathProgress:
    """Tracks the robot along the current path; a new path restarts the search."""

    search_window: float = SEARCH_WINDOW
    _path: Path | None = None
    _points: npt.NDArray[np.float64] | None = None
    _steps: npt.NDArray[np.float64] | None = None
    _index: int = 0

    def _adopt(self, path: Path) -> None:
        self._path = path
        self._points = _points(path)
        self._steps = np.hypot(*np.diff(self._points, axis=0).T) if len(path.poses) > 1 else None
        self._index = 0

    def distance_remaining(self, path: Path | None, pose: PoseStamped) -> float | None:
        """Metres from the robot's closest path segment to the path's end (None: no path)."""
        if path is None or not path.poses:
            return None
        if path is not self._path:
            self._adopt(path)
        assert self._points is not None
        if self._steps is None:
            robot = (pose.pose.position.x, pose.pose.position.y)
            return float(np.hypot(*(self._points[0] - robot)))
        self._index = self._closest_segment(pose)
        return float(self._steps[self._index :].sum())

    def _closest_segment(self, pose: PoseStamped) -> int:
        assert self._points is not None
        assert self._steps is not None
        start = self._index
        ahead = np.cumsum(self._steps[start:])
        stop = min(start + int(np.searchsorted(ahead, self.search_window)) + 1, len(self._steps))
        a, b = self._points[start:stop], self._points[start + 1 : stop + 1]
        robot = np.array((pose.pose.position.x, pose.pose.position.y))
        seg = b - a
        length2 = np.maximum((seg**2).sum(axis=1), 1e-12)
        t = np.clip(((robot - a) * seg).sum(axis=1) / length2, 0.0, 1.0)
        nearest = a + seg * t[:, None]
        return start + int(np.argmin(((nearest - robot) ** 2).sum(axis=1)))


def time_remaining(distance: float, speed: float) -> float:
    """Seconds left at ``speed`` (0 when nearly there or nearly stopped, as Nav2)."""
    speed = abs(speed)
    if speed > MIN_SPEED and distance > MIN_DISTANCE:
        return distance / speed
    return 0.0
