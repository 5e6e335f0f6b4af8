"""Boustrophedon coverage of a polygon field (ComputeCoveragePath, simplified F2C).

Rows run along the field's longest boundary edge, ``row_spacing`` apart,
starting half a spacing inside the headland. Each row is cut by the field
(outer boundary minus cut-outs, even-odd rule) and shortened by the headland
width at both ends; swaths alternate direction and are joined by straight
turn legs into one drivable path.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

Point2D = tuple[float, float]


class CoverageError(ValueError):
    """A field that cannot be covered; ``reason`` is opennav_coverage's code name."""

    def __init__(self, reason: str, message: str) -> None:
        super().__init__(message)
        self.reason = reason


@dataclass(frozen=True, slots=True)
class CoverageParams:
    row_spacing: float = 0.5
    headland_width: float = 0.5
    spacing: float = 0.05  # distance between poses of the dense path


@dataclass(frozen=True, slots=True)
class Coverage:
    swaths: list[tuple[Point2D, Point2D]]
    path: list[tuple[float, float, float]]


def _check(polygons: Sequence[Sequence[Point2D]]) -> list[np.ndarray]:
    if not polygons:
        raise CoverageError("INVALID_REQUEST", "no polygons given: need the field boundary")
    rings = []
    for i, polygon in enumerate(polygons):
        ring = np.array(polygon, dtype=np.float64).reshape(-1, 2)
        if len(ring) > 1 and np.allclose(ring[0], ring[-1]):
            ring = ring[:-1]
        if len(ring) < 3:
            raise CoverageError("INVALID_COORDS", f"polygon {i} has {len(ring)} points, needs 3")
        if not np.isfinite(ring).all():
            raise CoverageError("INVALID_COORDS", f"polygon {i} has a non-finite coordinate")
        rings.append(ring)
    return rings


def _row_angle(outer: np.ndarray) -> float:
    edges = np.roll(outer, -1, axis=0) - outer
    longest = int(np.argmax(np.hypot(edges[:, 0], edges[:, 1])))
    return math.atan2(edges[longest, 1], edges[longest, 0])


def _crossings(rings: list[np.ndarray], y: float) -> list[float]:
    xs: list[float] = []
    for ring in rings:
        a, b = ring, np.roll(ring, -1, axis=0)
        spans = (a[:, 1] <= y) != (b[:, 1] <= y)
        t = (y - a[spans, 1]) / (b[spans, 1] - a[spans, 1])
        xs.extend((a[spans, 0] + t * (b[spans, 0] - a[spans, 0])).tolist())
    return sorted(xs)


def plan_coverage(
    polygons: Sequence[Sequence[Point2D]], params: CoverageParams | None = None
) -> Coverage:
    """Swaths and a dense path (x, y, yaw) covering the field; raises CoverageError."""
    params = params or CoverageParams()
    rings = _check(polygons)
    angle = _row_angle(rings[0])
    c, s = math.cos(angle), math.sin(angle)
    to_local = np.array([[c, -s], [s, c]])  # row direction becomes +x
    local = [ring @ to_local for ring in rings]
    low, high = local[0][:, 1].min(), local[0][:, 1].max()
    first = low + params.headland_width + params.row_spacing / 2
    swaths: list[tuple[Point2D, Point2D]] = []
    for k, y in enumerate(
        np.arange(first, high - params.headland_width + 1e-9, params.row_spacing)
    ):
        xs = _crossings(local, float(y))
        pieces = [
            (x0 + params.headland_width, x1 - params.headland_width)
            for x0, x1 in zip(xs[::2], xs[1::2], strict=False)
            if x1 - x0 > 2 * params.headland_width + 1e-9
        ]
        if k % 2:
            pieces = [(x1, x0) for x0, x1 in reversed(pieces)]
        swaths.extend(((x0, float(y)), (x1, float(y))) for x0, x1 in pieces)
    if not swaths:
        raise CoverageError("INVALID_REQUEST", "the field is too small for one swath")
    back = to_local.T
    world = [
        (tuple((np.array(a) @ back).tolist()), tuple((np.array(b) @ back).tolist()))
        for a, b in swaths
    ]
    return Coverage(world, _dense([p for swath in world for p in swath], params.spacing))


def _dense(points: list[Point2D], spacing: float) -> list[tuple[float, float, float]]:
    out: list[tuple[float, float, float]] = []
    for (x0, y0), (x1, y1) in itertools.pairwise(points):
        length = math.hypot(x1 - x0, y1 - y0)
        if length < 1e-9:
            continue
        yaw = math.atan2(y1 - y0, x1 - x0)
        pieces = max(1, math.ceil(length / spacing))
        out.extend(
            (x0 + (x1 - x0) * i / pieces, y0 + (y1 - y0) * i / pieces, yaw) for i in range(pieces)
        )
    last_yaw = out[-1][2] if out else 0.0
    out.append((points[-1][0], points[-1][1], last_yaw))
    return out
