"""Where the robot is relative to its path: Nav2's TrackingFeedback figures."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from aiobt.geometry import PlanarPath, Pose2D, wrap_angle


@dataclass(slots=True, frozen=True)
class PathProjection:
    """The robot's foot point on the path."""

    segment: int  # index of the segment's first pose
    fraction: float  # 0..1 along that segment
    point: tuple[float, float]
    signed_distance: float  # > 0: robot left of the path


@dataclass(slots=True, frozen=True)
class TrackingFeedback:
    """Cross-track error (m, > 0 left of path), heading error (rad), and what remains."""

    current_path_index: int
    cross_track_error: float
    heading_error: float
    distance_to_goal: float
    remaining_path_length: float
    position: tuple[float, float]


def project_onto_path(
    path: PlanarPath, pose: Pose2D, start: int = 0, stop: int | None = None
) -> PathProjection:
    """Closest point of the path's segments ``start..stop`` to the robot (vectorised)."""
    last = len(path) - 1
    stop = last if stop is None else min(stop, last)
    start = max(0, min(start, last - 1))
    if last == 0 or stop <= start:
        x, y = path.xy[min(start, last)]
        return PathProjection(min(start, last), 0.0, (float(x), float(y)), 0.0)
    a = path.xy[start:stop]
    d = path.xy[start + 1 : stop + 1] - a
    length_sq = np.maximum((d * d).sum(axis=1), 1e-12)
    rel = np.array([pose.x, pose.y]) - a
    t = np.clip((rel * d).sum(axis=1) / length_sq, 0.0, 1.0)
    foot = a + d * t[:, None]
    dist_sq = ((np.array([pose.x, pose.y]) - foot) ** 2).sum(axis=1)
    best = int(np.argmin(dist_sq))
    cross = d[best, 0] * rel[best, 1] - d[best, 1] * rel[best, 0]
    sign = 1.0 if cross >= 0.0 else -1.0
    fx, fy = foot[best]
    return PathProjection(
        start + best, float(t[best]), (float(fx), float(fy)), sign * math.sqrt(float(dist_sq[best]))
    )


def search_stop(path: PlanarPath, start: int, distance: float) -> int:
    """Index of the last pose within ``distance`` along the path from pose ``start``."""
    seg = path.segment_lengths()[start:]
    return start + int((np.cumsum(seg) <= distance).sum()) + 1


def remaining_length(path: PlanarPath, projection: PathProjection) -> float:
    seg = path.segment_lengths()
    if seg.size == 0:
        return 0.0
    i = projection.segment
    return float(seg[i] * (1.0 - projection.fraction) + seg[i + 1 :].sum())


def tracking_feedback(
    path: PlanarPath, pose: Pose2D, projection: PathProjection
) -> TrackingFeedback:
    i = projection.segment
    if len(path) > 1:
        dx, dy = path.xy[min(i + 1, len(path) - 1)] - path.xy[i]
        tangent = math.atan2(dy, dx) if math.hypot(dx, dy) > 1e-9 else float(path.yaw[i])
    else:
        tangent = float(path.yaw[0])
    goal = path.goal
    return TrackingFeedback(
        current_path_index=i,
        cross_track_error=projection.signed_distance,
        heading_error=wrap_angle(pose.yaw - tangent),
        distance_to_goal=pose.distance_to(goal),
        remaining_path_length=remaining_length(path, projection),
        position=(pose.x, pose.y),
    )
