"""The robot's footprint as Nav2's ``nav2_costmap_2d/footprint`` makes it: a polygon
``(k, 2)`` in the robot's frame, from Nav2's ``footprint`` string or from a radius."""

from __future__ import annotations

import json
import math

import numpy as np

from .grid import FloatArray

RADIUS_POINTS = 16  # Nav2's makeFootprintFromRadius


def parse_footprint(text: str) -> FloatArray:
    """Nav2's footprint string ``[[x, y], [x, y], [x, y], ...]`` (at least 3 points, m)."""
    try:
        points = np.array(json.loads(text), dtype=np.float64)
    except (ValueError, TypeError) as exc:
        raise ValueError(f"footprint {text!r} is not a list of [x, y] points: {exc}") from None
    if points.ndim != 2 or points.shape[1] != 2 or len(points) < 3:
        raise ValueError(f"footprint {text!r} needs at least 3 [x, y] points")
    if not np.isfinite(points).all():
        raise ValueError(f"footprint {text!r} has a non-finite coordinate")
    return points


def footprint_from_radius(radius: float) -> FloatArray:
    """Nav2's ``makeFootprintFromRadius``: 16 points on the circle, the first ahead."""
    if not (math.isfinite(radius) and radius > 0.0):
        raise ValueError(f"footprint radius must be finite and > 0 m, got {radius!r}")
    angles = np.arange(RADIUS_POINTS) * (2.0 * math.pi / RADIUS_POINTS)
    points: FloatArray = radius * np.column_stack((np.cos(angles), np.sin(angles)))
    return points
