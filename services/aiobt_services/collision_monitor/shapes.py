"""Zones around the robot in its base frame: polygons and circles, with vectorised
point-in-zone counts and the checks that refuse a zone that cannot work.

Point-in-polygon is the even-odd ray cast of Nav2's ``isPointInsidePolygon``, for
all points against all edges at once (points x edges boolean arrays). A zone looks
only at the points within its ``reach`` of the base origin (no point farther can be
inside): of a lidar's hundreds of returns, a zone about the robot sees a few.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

Points = NDArray[np.float64]  # (n, 2) x, y in the base frame
CIRCLE_EDGES = 16  # as Nav2's circleToPolygon, for drawing


class ShapeError(ValueError):
    """A zone that cannot be used; the message names the zone and the fault."""


def inside_polygon(points: Points, vertices: Points) -> NDArray[np.bool_]:
    """Whether each point lies inside the polygon (even-odd rule, as Nav2's)."""
    if len(points) == 0:
        return np.zeros(0, dtype=bool)
    return _inside_edges(points, _edges(vertices))


Edges = tuple[Points, Points, Points, Points]  # x1, y1, x2, y2 of each edge


def _edges(vertices: Points) -> Edges:
    x1, y1 = vertices[:, 0], vertices[:, 1]
    return x1, y1, np.roll(x1, -1), np.roll(y1, -1)


def _inside_edges(points: Points, edges: Edges) -> NDArray[np.bool_]:
    x, y = points[:, 0:1], points[:, 1:2]  # (n, 1) against (1, m) edges
    x1, y1, x2, y2 = edges
    straddles = (y1 > y) != (y2 > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        crossing_x = x1 + (y - y1) * (x2 - x1) / (y2 - y1)
    crossings = straddles & (x < crossing_x)
    return np.asarray(np.count_nonzero(crossings, axis=1) % 2 == 1)


def _segments_cross(p1: Points, p2: Points, q1: Points, q2: Points) -> NDArray[np.bool_]:
    """Whether segments p1-p2 and q1-q2 cross properly (broadcast)."""

    def orient(a: Points, b: Points, c: Points) -> NDArray[np.float64]:
        return np.asarray(
            (b[..., 0] - a[..., 0]) * (c[..., 1] - a[..., 1])
            - (b[..., 1] - a[..., 1]) * (c[..., 0] - a[..., 0])
        )

    d1, d2 = orient(q1, q2, p1), orient(q1, q2, p2)
    d3, d4 = orient(p1, p2, q1), orient(p1, p2, q2)
    return np.asarray((d1 * d2 < 0.0) & (d3 * d4 < 0.0))


def check_polygon(name: str, vertices: Points) -> None:
    """Refuse fewer than 3 points, non-finite points, no area, or crossing edges."""
    if vertices.ndim != 2 or vertices.shape[1] != 2:
        raise ShapeError(f"polygon '{name}': points must be [x, y] pairs, got {vertices.tolist()}")
    if len(vertices) < 3:
        raise ShapeError(f"polygon '{name}' has {len(vertices)} points: a polygon needs at least 3")
    if not np.all(np.isfinite(vertices)):
        raise ShapeError(f"polygon '{name}': points must be finite, got {vertices.tolist()}")
    a, b = vertices, np.roll(vertices, -1, axis=0)
    n = len(vertices)
    crosses = _segments_cross(a[:, None], b[:, None], a[None, :], b[None, :])
    adjacent = np.abs(np.subtract.outer(np.arange(n), np.arange(n))) % (n - 1) <= 1
    if n > 3 and bool(np.any(crosses & ~adjacent)):
        i, j = np.argwhere(crosses & ~adjacent)[0]
        raise ShapeError(
            f"polygon '{name}' is self-intersecting: edge {i} {a[i].tolist()}->{b[i].tolist()} "
            f"crosses edge {j} {a[j].tolist()}->{b[j].tolist()}"
        )
    area = 0.5 * float(np.sum(a[:, 0] * b[:, 1] - b[:, 0] * a[:, 1]))
    if abs(area) < 1e-9:
        raise ShapeError(f"polygon '{name}' has no area: {vertices.tolist()}")


@dataclass(slots=True, frozen=True)
class Shape:
    """A polygon (``vertices``) or a circle about the base origin (``radius``)."""

    vertices: Points | None = None
    radius: float = 0.0
    reach: float = field(init=False)  # the farthest a point inside is from the origin
    _edges: Edges | None = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        v = self.vertices
        reach = self.radius if v is None else float(np.max(np.hypot(v[:, 0], v[:, 1])))
        object.__setattr__(self, "reach", reach)
        object.__setattr__(self, "_edges", None if v is None else _edges(v))

    def inside(self, points: Points) -> NDArray[np.bool_]:
        x, y = points[:, 0], points[:, 1]
        if self._edges is None:
            return np.asarray(x * x + y * y < self.radius**2)
        near = x * x + y * y <= self.reach**2
        result = np.zeros(len(points), dtype=bool)
        if near.any():
            result[near] = _inside_edges(points[near], self._edges)
        return result

    def outline(self) -> Points:
        """Vertices to draw (a circle as Nav2's 16-edge polygon)."""
        if self.vertices is not None:
            return self.vertices
        angles = np.arange(CIRCLE_EDGES) * (2.0 * math.pi / CIRCLE_EDGES)
        return np.column_stack((np.cos(angles), np.sin(angles))) * self.radius


def polygon(name: str, points: object) -> Shape:
    """A checked polygon from ``[[x, y], ...]``."""
    try:
        vertices = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise ShapeError(
            f"polygon '{name}': points must be [[x, y], ...], got {points!r}"
        ) from None
    check_polygon(name, vertices)
    return Shape(vertices=vertices)


def circle(name: str, radius: float) -> Shape:
    if not (math.isfinite(radius) and radius > 0.0):
        raise ShapeError(f"circle '{name}': radius must be a number > 0, got {radius!r}")
    return Shape(radius=radius)
