"""Paths as numpy arrays, so that per-cycle work (closest point, lookahead, tracking
error) is vectorised, and the arcs a unicycle command drives."""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from .pose import Pose2D, Velocity

FloatArray = NDArray[np.float64]


@dataclass(slots=True, frozen=True)
class PlanarPath:
    """A path in one frame: ``xy`` is (N, 2), ``yaw`` is (N,).

    The segment lengths are computed once here: the control loop reads them
    several times per cycle (search windows, remaining length, DWB's local path).
    """

    frame_id: str
    xy: FloatArray
    yaw: FloatArray
    _lengths: FloatArray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        diff = np.diff(self.xy, axis=0)
        lengths: FloatArray = np.hypot(diff[:, 0], diff[:, 1])
        lengths.flags.writeable = False
        object.__setattr__(self, "_lengths", lengths)

    @classmethod
    def from_poses(cls, frame_id: str, poses: list[tuple[float, float, float]]) -> PlanarPath:
        array = np.asarray(poses, dtype=np.float64).reshape(-1, 3)
        return cls(frame_id, array[:, :2].copy(), array[:, 2].copy())

    @classmethod
    def through(
        cls, points: Sequence[tuple[float, float]], spacing: float = 0.05, frame_id: str = "map"
    ) -> PlanarPath:
        """A path through ``points`` sampled every ``spacing`` m or less, yaw along the path."""
        out: list[tuple[float, float]] = []
        for (x0, y0), (x1, y1) in itertools.pairwise(points):
            n = max(1, math.ceil(math.hypot(x1 - x0, y1 - y0) / spacing))
            out.extend((x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * i / n) for i in range(n))
        out.append(points[-1])
        xy = np.asarray(out, dtype=np.float64)
        d = np.diff(xy, axis=0)
        yaw = np.arctan2(d[:, 1], d[:, 0])
        return cls(frame_id, xy, np.append(yaw, yaw[-1]))

    def __len__(self) -> int:
        return int(self.xy.shape[0])

    @property
    def goal(self) -> Pose2D:
        x, y = self.xy[-1]
        return Pose2D(float(x), float(y), float(self.yaw[-1]))

    def segment_lengths(self) -> FloatArray:
        """Length of each of the N - 1 segments (read-only, computed at construction)."""
        return self._lengths

    def length(self) -> float:
        return float(self.segment_lengths().sum())


def to_robot_frame(pose: Pose2D, points: FloatArray) -> FloatArray:
    """Points (N, 2) expressed in the robot frame of ``pose`` (x ahead, y left)."""
    cos_yaw, sin_yaw = math.cos(pose.yaw), math.sin(pose.yaw)
    dx = points[:, 0] - pose.x
    dy = points[:, 1] - pose.y
    return np.column_stack((cos_yaw * dx + sin_yaw * dy, -sin_yaw * dx + cos_yaw * dy))


def integrate_arc(pose: Pose2D, cmd: Velocity, times: FloatArray) -> FloatArray:
    """Poses (T, 3) reached from ``pose`` holding ``cmd`` for each of ``times``."""
    yaw = pose.yaw + cmd.w * times
    half = 0.5 * cmd.w * times
    # the chord of the arc: exact for any w and free of the v / w cancellation near w = 0
    chord = cmd.v * times * np.sinc(half / math.pi)
    x = pose.x + chord * np.cos(pose.yaw + half)
    y = pose.y + chord * np.sin(pose.yaw + half)
    return np.column_stack((x, y, yaw))
