"""Recent odometry poses by stamp: where the base was (in ``odom``) when a scan
was taken, interpolated between the two odometry messages around its stamp, as
AMCL asks TF for ``odom`` -> ``base`` at the scan's time."""

from __future__ import annotations

from collections import deque

import numpy as np

from .se2 import FloatArray, angle_diff, wrap

KEEP = 128  # 2.5 s at the robot's 50 Hz


class OdomBuffer:
    """The last ``keep`` odometry poses (x, y, yaw in ``odom``) with their stamps."""

    __slots__ = ("_poses", "_stamps")

    def __init__(self, keep: int = KEEP) -> None:
        self._stamps: deque[float] = deque(maxlen=keep)
        self._poses: deque[tuple[float, float, float]] = deque(maxlen=keep)

    def add(self, stamp: float, x: float, y: float, yaw: float) -> None:
        """A new odometry pose; a stamp older than the newest (the simulation reset)
        starts the buffer afresh."""
        if self._stamps and stamp < self._stamps[-1]:
            self.clear()
        self._stamps.append(stamp)
        self._poses.append((x, y, yaw))

    def clear(self) -> None:
        self._stamps.clear()
        self._poses.clear()

    @property
    def newest(self) -> tuple[float, FloatArray] | None:
        """(stamp, pose) of the newest odometry, None before any."""
        if not self._stamps:
            return None
        return self._stamps[-1], np.array(self._poses[-1])

    def at(self, stamp: float, tolerance: float) -> FloatArray | None:
        """The pose at ``stamp``: interpolated inside the buffer, the nearest end if it
        is within ``tolerance`` s, else None (too old, or odometry not there yet)."""
        if not self._stamps:
            return None
        stamps = np.fromiter(self._stamps, dtype=np.float64, count=len(self._stamps))
        poses = np.array(self._poses)
        if stamp <= stamps[0] or stamp >= stamps[-1]:
            end = 0 if stamp <= stamps[0] else -1
            return poses[end].copy() if abs(stamp - stamps[end]) <= tolerance else None
        i = int(np.searchsorted(stamps, stamp))
        span = stamps[i] - stamps[i - 1]
        f = 0.0 if span <= 0.0 else (stamp - stamps[i - 1]) / span
        a, b = poses[i - 1], poses[i]
        out: FloatArray = a + f * (b - a)
        out[2] = float(wrap(a[2] + f * angle_diff(b[2], a[2])))
        return out
