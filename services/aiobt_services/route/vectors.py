"""The two bits of plane geometry Nav2's route code leans on (``nav2_route/utils.hpp``)."""

from __future__ import annotations

import math

XY = tuple[float, float]


def normalized_dot(v1x: float, v1y: float, v2x: float, v2y: float) -> float:
    """Cosine of the angle between two vectors; 0 when either is (near) zero."""
    mag1, mag2 = math.hypot(v1x, v1y), math.hypot(v2x, v2y)
    if mag1 < 1e-6 or mag2 < 1e-6:
        return 0.0
    return (v1x * v2x + v1y * v2y) / (mag1 * mag2)


def closest_point(point: XY, start: XY, end: XY) -> XY:
    """The point of segment start-end nearest ``point``."""
    vx, vy = end[0] - start[0], end[1] - start[1]
    vv = vx * vx + vy * vy
    if vv < 1e-12:
        return start
    t = ((point[0] - start[0]) * vx + (point[1] - start[1]) * vy) / vv
    t = min(1.0, max(0.0, t))
    return (start[0] + t * vx, start[1] + t * vy)


def distance(a: XY, b: XY) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])
